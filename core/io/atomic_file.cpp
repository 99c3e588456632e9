#include "atomic_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <thread>

namespace stickslip::io {

namespace {

// Test hook for the kill -9 tests: STICKSLIP_TEST_STALL_WRITE=SECONDS makes the first write()
// stop half way through its data for that long (after saying so on stderr), so a test can kill
// the writer while the temporary is certainly half written instead of relying on timing luck.
double stallSecondsFromEnvironment() {
    const char* v = std::getenv("STICKSLIP_TEST_STALL_WRITE");
    if (!v || !*v) return 0.0;
    const double s = std::strtod(v, nullptr);
    return s > 0.0 ? s : 0.0;
}

bool writeAll(int fd, const char* p, size_t left) {
    while (left > 0) {
        const ssize_t n = ::write(fd, p, left);
        if (n < 0) {
            if (errno == EINTR) continue;
            return false;
        }
        p += n;
        left -= static_cast<size_t>(n);
    }
    return true;
}

}  // namespace

AtomicFileWriter::AtomicFileWriter(std::string path) : path_(std::move(path)), stdout_(path_ == "-") {
    stall_s_ = stallSecondsFromEnvironment();
    stallPending_ = stall_s_ > 0.0 && !stdout_;
}

AtomicFileWriter::~AtomicFileWriter() {
    if (!committed_) abort();
}

bool AtomicFileWriter::fail(const std::string& what) {
    error_ = path_ + ": " + what;
    return false;
}

bool AtomicFileWriter::open() {
    if (stdout_) return true;
    if (path_.empty()) return fail("empty file name");
    // The temporary lives in the target's directory so that rename() is atomic.
    tmp_ = path_ + ".tmp.XXXXXX";
    fd_ = ::mkstemp(tmp_.data());
    if (fd_ < 0) {
        tmp_.clear();
        return fail(std::string("cannot create temporary file: ") + std::strerror(errno));
    }
    struct stat st {};
    const mode_t mode = (::stat(path_.c_str(), &st) == 0) ? (st.st_mode & 07777) : 0644;
    ::fchmod(fd_, mode);
    return true;
}

bool AtomicFileWriter::write(std::string_view data) {
    if (stdout_) {
        std::cout.write(data.data(), static_cast<std::streamsize>(data.size()));
        return std::cout ? true : fail("cannot write to standard output");
    }
    if (fd_ < 0) return fail("not open for writing");
    if (stallPending_ && !data.empty()) {
        stallPending_ = false;
        const size_t half = data.size() / 2;
        if (!writeAll(fd_, data.data(), half)) return fail(std::string("write failed: ") + std::strerror(errno));
        std::fprintf(stderr, "stickslip: test hook: stalled mid-write of %s\n", tmp_.c_str());
        std::fflush(stderr);
        std::this_thread::sleep_for(std::chrono::duration<double>(stall_s_));
        data.remove_prefix(half);
    }
    if (!writeAll(fd_, data.data(), data.size())) {
        const std::string why = std::strerror(errno);
        abort();
        return fail("write failed: " + why);
    }
    return true;
}

bool AtomicFileWriter::commit() {
    if (stdout_) {
        std::cout.flush();
        committed_ = true;
        return std::cout ? true : fail("cannot write to standard output");
    }
    if (fd_ < 0) return fail("not open for writing");
    const bool synced = ::fsync(fd_) == 0;
    const bool closed = ::close(fd_) == 0;
    fd_ = -1;
    if (!synced || !closed) {
        const std::string why = std::strerror(errno);
        abort();
        return fail("write failed: " + why);
    }
    if (::rename(tmp_.c_str(), path_.c_str()) != 0) {
        const std::string why = std::strerror(errno);
        abort();
        return fail("cannot replace file: " + why);
    }
    tmp_.clear();
    committed_ = true;
    return true;
}

void AtomicFileWriter::abort() {
    if (fd_ >= 0) ::close(fd_);
    fd_ = -1;
    if (!tmp_.empty()) ::unlink(tmp_.c_str());
    tmp_.clear();
}

}  // namespace stickslip::io
