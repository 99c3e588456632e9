// `stickslip-cli simulate`: one run (dynamics or prescribed slip) written as CSV.
#include <iostream>
#include <memory>

#include "cancel.hpp"
#include "cli_common.hpp"
#include "core/integrate/simulate.hpp"
#include "core/io/run_csv.hpp"

namespace stickslip::cli {

namespace {

struct SimulateOptions {
    SimOptions sim;
    std::string input;
    std::string out;
};

void runSimulate(const SimulateOptions& o, int& exitCode) {
    SimOptions sim = o.sim;
    if (!o.input.empty()) {
        if (sim.setup.empty()) sim.setup = "prescribed";  // an input history implies the prescribed set-up
        if (sim.setup != "prescribed") {
            reportError("simulate", "--input needs --setup prescribed (got --setup " + sim.setup + ")", kBadArguments,
                        exitCode);
            return;
        }
    }
    SimParams p;
    std::string error;
    if (const int rc = buildSimParams(sim, p, &error); rc != kOk) {
        reportError("simulate", error, rc, exitCode);
        return;
    }

    SlipHistory history;
    std::vector<std::string> comments;
    if (!o.input.empty()) {
        io::CsvError err;
        if (!io::readSlipHistoryCsv(o.input, history, err)) {
            reportError("simulate", err.what(), kBadInput, exitCode);
            return;
        }
        comments.push_back("input = " + o.input);
    }

    if (p.integration.tolerance > 0.0)
        comments.push_back("integration = adaptive, tolerance = " + exactNumber(p.integration.tolerance) +
                           " (dt unused; samples every output interval exactly)");
    RunControl ctl;
    ctl.cancel = &cancelFlag();
    // A file is written while the run computes (its rows never all in memory); standard
    // output gets the whole text at the end, since the '#' lines with the status come first.
    std::unique_ptr<io::RunCsvStream> stream;
    long streamed = 0;
    if (o.out != "-") {
        stream = std::make_unique<io::RunCsvStream>(o.out);
        if (!stream->open(&error)) {
            reportError("simulate", error, kBadInput, exitCode);
            return;
        }
        ctl.onSample = [&stream, &streamed](const Sample& x) {
            stream->add(x);
            ++streamed;
        };
    }
    const RunResult r = simulate(p, ctl, o.input.empty() ? nullptr : &history);
    const long samples = stream ? streamed : static_cast<long>(r.samples.size());
    // Cancelled: nothing is written (a partial run under the output name would pass for a
    // whole one). A failed run still writes what it computed (its status and message are in
    // the '#' lines) so the lead-up to the failure can be inspected; the exit code says it failed.
    if (r.status == RunStatus::Cancelled || cancelRequested()) {
        reportError("simulate", "cancelled; no output written", kCancelled, exitCode);
        return;
    }
    if (stream ? !stream->finish(p, r, &error, comments) : !io::writeRunCsv(o.out, p, r, &error, comments)) {
        reportError("simulate", error, kBadInput, exitCode);
        return;
    }
    if (r.status == RunStatus::Failed) {
        reportError("simulate", "run failed: " + r.message, kRunFailed, exitCode);
        return;
    }
    if (o.out != "-")
        std::cerr << "stickslip-cli simulate: " << samples << " samples (" << r.stats.steps << " steps) -> " << o.out
                  << '\n';
    exitCode = kOk;
}

}  // namespace

void addSimulateCommand(CLI::App& root, int& exitCode) {
    auto* cmd = root.add_subcommand(
        "simulate", "Run one simulation (spring-mass dynamics or prescribed slip) and write its samples as CSV");
    auto o = std::make_shared<SimulateOptions>();
    addSimOptions(cmd, o->sim);
    addToleranceOption(cmd, o->sim, "output exactly every --output-every");
    cmd->add_option("--input", o->input,
                    "Prescribed slip history CSV: time_s and one of rel_disp_m, stage_disp_m (slider held fixed) "
                    "or rel_vel_mps; optional normal_force_N; '#' lines skipped")
        ->type_name("FILE.csv");
    cmd->add_option("--out", o->out, "Output CSV file, or - for standard output")->required()->type_name("FILE.csv|-");
    cmd->footer(
        "Exit codes: 0 ok, 2 bad arguments or parameters, 3 unreadable or malformed input (file:line:column) or "
        "an output file that cannot be written, "
        "4 run failed numerically, 5 cancelled (Ctrl-C or SIGTERM; no output written).");
    cmd->callback([&exitCode, o] { runSimulate(*o, exitCode); });
}

}  // namespace stickslip::cli
