// What `map` and `sweep --mode independent` do before computing: rank 0 reads the checkpoint
// (when one is asked for) and lists the records still to compute; every rank gets that list.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "cell_records.hpp"
#include "cli_common.hpp"
#include "mpi_runner.hpp"

namespace stickslip::cli {

struct CheckpointSpec {
    std::string path;        // "" = no checkpoint
    std::string command;     // "map" or "sweep": the header's kind and the error's prefix
    std::string settings;    // every setting that changes a record (fingerprinted)
    std::string countLine;   // "cells N" / "values N"
    std::string form;        // the record line, for the malformed-line message
};

// Record: has `std::size_t index`. parse(line, count, record) reads one record line.
// Returns kOk, or kBadInput on every rank after rank 0 reported why (exitCode set).
template <class Record>
int planFromCheckpoint(const CheckpointSpec& spec, std::size_t count,
                       const std::function<bool(const std::string&, std::size_t, Record&)>& parse,
                       CheckpointLog& ckpt, std::vector<Record>& records, std::vector<std::size_t>& todo,
                       int& exitCode) {
    int rc = kOk;
    if (mpiRank() == 0) {
        std::string error;
        auto accept = [&](const std::string& line) {
            Record r;
            if (!parse(line, count, r)) return false;
            records.push_back(std::move(r));
            return true;
        };
        if (!spec.path.empty() && !ckpt.open(spec.path, spec.command, fingerprint(spec.settings), spec.countLine,
                                             accept, spec.form, &error)) {
            reportError(spec.command, error, kBadInput, exitCode);
            rc = kBadInput;
        }
        std::vector<unsigned char> have(count, 0);
        for (const Record& r : records) have[r.index] = 1;
        for (std::size_t i = 0; i < count; ++i)
            if (!have[i]) todo.push_back(i);
    }
    rc = mpiBroadcastInt(rc);
    if (rc != kOk) {
        exitCode = rc;
        return rc;
    }
    todo = mpiBroadcastIndices(todo);
    return kOk;
}

}  // namespace stickslip::cli
