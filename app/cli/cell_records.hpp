// Per-cell records of `map` and per-value records of `sweep --mode independent`, as bytes for
// MPI (doubles and integers copied bit for bit, so rank 0 assembles exactly what a single
// process computes; ranks must share one binary format, i.e. one architecture), and the map's
// checkpoint file: a line-oriented text log that rank 0 appends each finished cell to.
#pragma once

#include <cstdio>
#include <cstdint>
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

// Checkpoint of a map. Format (text, one record a line, numbers with %.17g so they read back
// bit for bit):
//   # stickslip-cli map checkpoint v1
//   # fingerprint <16 hex digits>   (of every setting that changes a cell's result)
//   # cells <count>
//   cell <index> <motion 0|1|2> <period> <stick_fraction> <max_rel_vel_mps>
// Only cells that finished Ok are logged; failed cells are recomputed (deterministically) on
// resume. Every line is flushed when written, so kill -9 loses at most the cells in flight; a
// last line without its newline (killed mid-write) is ignored and cut off on resume.
class MapCheckpoint {
public:
    MapCheckpoint() = default;
    MapCheckpoint(const MapCheckpoint&) = delete;
    MapCheckpoint& operator=(const MapCheckpoint&) = delete;
    ~MapCheckpoint();
    // Opens `path` for appending, creating it with a header when it is missing or empty. An
    // existing file must carry the same fingerprint and cell count; its cells are returned in
    // `loaded`. Returns false with "path:line: why" in *error (unreadable, malformed,
    // written for other settings).
    bool open(const std::string& path, const std::string& fp, std::size_t cells, std::vector<MapCell>& loaded,
              std::string* error);
    // Appends one Ok cell and flushes. Returns false with a message when the write failed.
    bool append(const MapCell& c, std::string* error);

private:
    std::string path_;
    std::FILE* file_ = nullptr;
};

}  // namespace stickslip::cli
