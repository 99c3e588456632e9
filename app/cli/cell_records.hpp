// Per-cell records of `map` and per-value records of `sweep --mode independent`, as bytes for
// MPI (doubles and integers copied bit for bit, so rank 0 assembles exactly what a single
// process computes; ranks must share one binary format, i.e. one architecture), and the
// checkpoint file: a line-oriented text log that rank 0 appends each finished record to.
#pragma once

#include <cstdio>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "core/analysis/periodicity_map.hpp"
#include "core/analysis/sweep.hpp"

namespace stickslip::cli {

std::string encodeMapCell(const MapCell& c);
bool decodeMapCell(const std::string& bytes, MapCell& out);
std::string encodeSweepValue(const SweepValueRecord& r);
bool decodeSweepValue(const std::string& bytes, SweepValueRecord& out);

// 64-bit FNV-1a of `text`, as 16 hex digits: the fingerprint of a run's settings.
std::string fingerprint(const std::string& text);

// Checkpoint log (`map --checkpoint`, `sweep --mode independent --checkpoint`). Text, one
// record a line:
//   # stickslip-cli <map|sweep> checkpoint v1
//   # fingerprint <16 hex digits>   (of every setting that changes a record)
//   # cells <count>                 (map; "# values <count>" for a sweep)
//   cell <index> <motion 0|1|2> <period> <stick_fraction> <max_rel_vel_mps>    (map, %.17g)
//   value <index> <hex of encodeSweepValue>                                    (sweep)
// Numbers read back bit for bit. Only records that finished Ok are logged; failed ones are
// recomputed (deterministically) on resume. Every line is flushed when written, so kill -9
// loses at most the records in flight; a last line without its newline (killed mid-write) is
// ignored and cut off on resume.
std::string formatMapCellLine(const MapCell& c);
bool parseMapCellLine(const std::string& line, std::size_t cells, MapCell& out);
std::string formatSweepValueLine(const SweepValueRecord& r);
bool parseSweepValueLine(const std::string& line, std::size_t values, SweepValueRecord& out);

class CheckpointLog {
public:
    CheckpointLog() = default;
    CheckpointLog(const CheckpointLog&) = delete;
    CheckpointLog& operator=(const CheckpointLog&) = delete;
    ~CheckpointLog();
    // Opens `path` for appending, creating it with the header when it is missing or empty. An
    // existing file must carry the same kind, fingerprint and count line; each of its record
    // lines goes to accept(), which returns false for a malformed one (`form` describes the
    // expected record in the message). Returns false with "path:line: why" in *error.
    bool open(const std::string& path, const std::string& kind, const std::string& fp, const std::string& countLine,
              const std::function<bool(const std::string&)>& accept, const std::string& form, std::string* error);
    // Appends one record line and flushes. Returns false with a message when the write failed.
    bool append(const std::string& line, std::string* error);

private:
    std::string path_;
    std::FILE* file_ = nullptr;
};

}  // namespace stickslip::cli
