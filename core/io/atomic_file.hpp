// A file that appears under its final name only complete: written to NAME.tmp.XXXXXX in the
// same directory, fsync'ed and renamed over NAME on commit(). A writer killed at any point
// (even kill -9) leaves NAME as it was; only the temporary may stay behind. Such a stale
// NAME.tmp.XXXXXX is never read by StickSlip Lab (files are opened by the name given) and
// is not removed by a later write either (it may belong to another writer still running);
// delete it by hand.
#pragma once

#include <string>
#include <string_view>

namespace stickslip::io {

class AtomicFileWriter {
public:
    // "-" writes straight to standard output (nothing to make atomic there).
    explicit AtomicFileWriter(std::string path);
    ~AtomicFileWriter();  // without a successful commit(): the temporary is removed
    AtomicFileWriter(const AtomicFileWriter&) = delete;
    AtomicFileWriter& operator=(const AtomicFileWriter&) = delete;

    bool open();                       // creates the temporary (keeps the target's mode)
    bool write(std::string_view data);
    bool commit();                     // fsync, close, rename over the target
    void abort();                      // removes the temporary; the target stays as it was
    const std::string& error() const { return error_; }  // "PATH: what went wrong"
    const std::string& tempPath() const { return tmp_; }

private:
    bool fail(const std::string& what);
    std::string path_, tmp_, error_;
    int fd_ = -1;
    bool stdout_ = false, committed_ = false, stallPending_ = false;
    double stall_s_ = 0.0;
};

}  // namespace stickslip::io
