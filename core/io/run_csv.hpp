// Runs as CSV files: the output of a simulation, and prescribed-slip histories as input.
#pragma once

#include <string>
#include <vector>

#include "../integrate/prescribed.hpp"
#include "../integrate/run_result.hpp"
#include "../params.hpp"
#include "csv_table.hpp"

namespace stickslip::io {

// Column names of a run file, in order.
const std::vector<std::string>& runCsvColumns();

// The values of the run file's columns (runCsvColumns order), one vector per column, as
// doubles (stuck is 0 or 1): the numbers runCsvText prints (it rounds them to %.10g).
std::vector<std::vector<double>> runCsvValues(const RunResult& r);

// The full text of a run file: '#' lines with the program version, model, set-up, status
// and every parameter ("# A = 0.001 m"), any `extraComments` (one '#' line each), then
// the header time_s,stage_disp_m,slider_disp_m,slider_vel_mps,rel_vel_mps,
// friction_force_N,friction_ratio,state_alpha,stuck and one row per sample (%.10g).
std::string runCsvText(const SimParams& p, const RunResult& r, const std::vector<std::string>& extraComments = {});
// runCsvText written atomically ("-" = stdout).
bool writeRunCsv(const std::string& path, const SimParams& p, const RunResult& r, std::string* error,
                 const std::vector<std::string>& extraComments = {});

// A run file written while the run computes: pass `[&](const Sample& x) { stream.add(x); }` as
// RunControl::onSample. The rows go to an unnamed temporary in the target's directory (gone
// when the process ends, even by kill -9); finish() then writes the '#' lines, which carry the
// run's final status, and the rows atomically to `path`. Memory stays at one block of text
// however long the run; the file is byte for byte what writeRunCsv writes. Not for "-".
class RunCsvStream {
public:
    explicit RunCsvStream(std::string path);
    ~RunCsvStream();
    RunCsvStream(const RunCsvStream&) = delete;
    RunCsvStream& operator=(const RunCsvStream&) = delete;
    bool open(std::string* error);
    void add(const Sample& x);  // a write error is kept and reported by finish()
    // `r` gives the status and message (its samples are not used: they came through add()).
    bool finish(const SimParams& p, const RunResult& r, std::string* error,
                const std::vector<std::string>& extraComments = {});

private:
    bool flush();
    std::string path_, block_, error_;
    int rowsFd_ = -1;
};

// A prescribed-slip history from a table, by header name: `time_s` and one of
// `rel_disp_m` (g), `stage_disp_m` (slider held fixed, so g = u) or `rel_vel_mps` (V,
// integrated from g = 0), in that order of preference; `rel_vel_mps` is also kept as the
// velocity when a displacement column is used; `normal_force_N` (optional) gives t_N per
// sample. Errors name the file and line (and column where known).
bool slipHistoryFromTable(const CsvTable& t, SlipHistory& out, CsvError& err);
bool readSlipHistoryCsv(const std::string& path, SlipHistory& out, CsvError& err);

}  // namespace stickslip::io
