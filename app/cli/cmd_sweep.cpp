// `stickslip-cli sweep`: bifurcation sweep of one parameter (continuation or independent),
// writing the Poincaré samples (--out) and a per-value summary (--summary). Under mpirun the
// independent mode interleaves its values over the ranks and rank 0 writes the files (the same
// bytes as one process); a continuation is sequential and runs on rank 0 alone.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <tuple>
#include <numbers>

#include "cancel.hpp"
#include "cell_records.hpp"
#include "checkpoint_plan.hpp"
#include "cli_common.hpp"
#include "mpi_runner.hpp"
#include "core/analysis/sweep.hpp"
#include "core/io/csv_table.hpp"
#include "core/io/units.hpp"
#include "core/version.hpp"

namespace stickslip::cli {

namespace {

struct SweepCliOptions {
    SimOptions sim;
    std::string param = "A", from, to, direction = "up", mode = "continuation", out, summary, checkpoint;
    int steps = 50;
    long settle = 50, samples = 100, stepsPerPeriod = 0;
    int threads = 0;
    double phase = 0.0, tol = 1e-4;
    bool noLyapunov = false, progress = false, concurrentBranches = false, independent = false;
};

std::string num(double v) {
    if (std::isnan(v)) return "nan";
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.10g", v);
    return buf;
}

// Every setting that changes a value's record (not --direction, which only orders the output),
// for the checkpoint's fingerprint.
std::string settingsText(const SweepCliOptions& o, const SimParams& p, const SweepOptions& so) {
    auto g = [](double v) { return exactNumber(v); };
    return std::string("sweep independent ") + kVersion + "\n" + simSettingsText(o.sim, p) + so.key + " " +
           g(std::min(so.from, so.to)) + " " + g(std::max(so.from, so.to)) + " " + std::to_string(so.steps) +
           "\nsettle " + std::to_string(so.settleCycles) + " samples " + std::to_string(so.sampleCycles) + " n " +
           std::to_string(stepsPerPeriodFor(p, so.stepsPerPeriod)) + " phase " + g(so.phase_rad) + " tol " +
           g(so.classify.relTol) + " lyapunov " + (so.lyapunov ? g(so.lyapunovD0) : "no") + "\n";
}

// Independent mode across the ranks (or on this process alone): every value's record is
// streamed to rank 0, which logs it to the checkpoint and assembles the result. Other ranks
// return an empty result. Returns false (exitCode set) when the checkpoint was refused.
bool distributedIndependentSweep(const SweepCliOptions& o, const SimParams& p, const SweepOptions& so,
                                 SweepResult& result, int& exitCode) {
    CheckpointLog ckpt;
    std::vector<SweepValueRecord> records;
    std::vector<std::size_t> todo;
    const std::size_t count = static_cast<std::size_t>(so.steps);
    const CheckpointSpec spec{o.checkpoint, "sweep", settingsText(o, p, so), "values " + std::to_string(count),
                              "value INDEX HEX, INDEX < " + std::to_string(count)};
    if (planFromCheckpoint<SweepValueRecord>(spec, count, parseSweepValueLine, ckpt, records, todo, exitCode) != kOk)
        return false;
    std::string ckptError;
    mpiDistribute(
        todo, batchSize(so.threads),
        [&](const std::vector<std::size_t>& mine, const EmitFn& emit) {
            RunControl ctl;
            ctl.cancel = &cancelFlag();
            independentSweepValues(p, so, mine, ctl, [&](const SweepValueRecord& r) { emit(encodeSweepValue(r)); });
        },
        [&](const std::string& bytes) {
            SweepValueRecord r;
            if (!decodeSweepValue(bytes, r)) r = SweepValueRecord{};  // cannot happen between ranks of one binary
            if (r.done && r.point.section.ok() && ckptError.empty()) ckpt.append(formatSweepValueLine(r), &ckptError);
            records.push_back(std::move(r));
            if (o.progress)
                std::fprintf(stderr, "\rsweep: %5.1f %%", 100.0 * static_cast<double>(records.size()) / double(so.steps));
        });
    if (mpiRank() != 0) return true;
    if (!ckptError.empty()) {
        reportError("sweep", ckptError, kBadInput, exitCode);
        return false;
    }
    result = assembleIndependentSweep(p, so, records);
    return true;
}

// Rank 0 (or the single process): the samples CSV (--out) and the summary (--summary).
bool writeSweepFiles(const SweepCliOptions& o, const std::string& unit, const SimParams& p, const SweepOptions& so,
                     const SweepResult& r, int& exitCode) {
    std::string error;
    std::string head = std::string("# stickslip-cli ") + kVersion + " sweep\n# param = " + o.param + " [" + unit +
                       "]\n# mode = " + toString(so.mode) + ", direction = " + toString(so.direction) +
                       (so.concurrentBranches ? " (branches concurrent: down starts from rest at the top value)" : "") +
                       "\n# settle = " + std::to_string(so.settleCycles) + " cycles, samples = " +
                       std::to_string(so.sampleCycles) + ", " + steppingText(p, so.stepsPerPeriod) + ", period tolerance = " +
                       num(so.classify.relTol) + "\n# status = " + toString(r.status) +
                       (r.message.empty() ? "" : " (" + r.message + ")") + "\n";
    for (const std::string& k : paramKeys()) {
        double v = 0;
        if (k != o.param && getParam(p, k, v)) head += "# " + k + " = " + num(v) + "\n";
    }
    std::string csv = head + "param_value,direction,sample,slider_disp_m,rel_vel_mps,friction_ratio\n";
    std::string sum = head + "param_value,direction,class,period,stick_fraction,max_rel_vel_mps,lyapunov_per_s\n";
    for (const SweepPoint& pt : r.points) {
        const std::string v = num(pt.value), dir = pt.direction > 0 ? "up" : "down";
        for (std::size_t i = 0; i < pt.section.size(); ++i)
            csv += v + "," + dir + "," + std::to_string(i) + "," + num(pt.section.slider_m[i]) + "," +
                   num(pt.section.relVel_mps[i]) + "," + num(pt.section.ratio[i]) + "\n";
        sum += v + "," + dir + "," + toString(pt.classification.motion) + "," +
               std::to_string(pt.classification.period) + "," + num(pt.classification.stickFraction) + "," +
               num(pt.classification.maxRelVel_mps) + "," + num(pt.lyapunovPerSecond) + "\n";
    }
    if (!io::writeFileAtomically(o.out, csv, &error) ||
        (!o.summary.empty() && !io::writeFileAtomically(o.summary, sum, &error))) {
        reportError("sweep", error, kBadInput, exitCode);
        return false;
    }
    return true;
}

void runSweep(const SweepCliOptions& o, int& exitCode) {
    SimParams p;
    std::string error;
    if (const int rc = buildSimParams(o.sim, p, &error); rc != kOk) {
        reportError("sweep", error, rc, exitCode);
        return;
    }
    SweepOptions so;
    so.key = o.param;
    std::string unit;
    if (!io::paramUnit(o.param, unit)) {
        std::string keys;
        for (const std::string& k : paramKeys()) keys += " " + k;
        reportError("sweep", "--param '" + o.param + "' is not a parameter key (known:" + keys + ")", kBadArguments,
                    exitCode);
        return;
    }
    if (!io::parseParamValue(o.param, o.from, so.from, &error) || !io::parseParamValue(o.param, o.to, so.to, &error)) {
        reportError("sweep", error, kBadArguments, exitCode);
        return;
    }
    if (!parseSweepDirection(o.direction, so.direction)) {
        reportError("sweep", "--direction '" + o.direction + "' is not one of: up, down, both", kBadArguments, exitCode);
        return;
    }
    if (!parseSweepMode(o.independent ? "independent" : o.mode, so.mode)) {
        reportError("sweep", "--mode '" + o.mode + "' is not one of: continuation, independent", kBadArguments,
                    exitCode);
        return;
    }
    so.steps = o.steps;
    so.settleCycles = o.settle;
    so.sampleCycles = o.samples;
    so.stepsPerPeriod = o.stepsPerPeriod;
    so.threads = o.threads;
    so.concurrentBranches = o.concurrentBranches;
    so.phase_rad = o.phase;
    so.lyapunov = !o.noLyapunov;
    so.classify.relTol = o.tol;
    if (ParamIssues issues = so.validate(p); !issues.empty()) {
        reportError("sweep", formatIssues(issues), kBadArguments, exitCode);
        return;
    }
    RunControl ctl;
    ctl.cancel = &cancelFlag();
    if (o.progress)
        ctl.progress = [](double f) { std::fprintf(stderr, "\rsweep: %5.1f %%", 100.0 * f); };
    if (so.mode == SweepMode::Continuation && !o.checkpoint.empty()) {
        reportError("sweep", "--checkpoint needs --mode independent (a continuation carries its state from value "
                             "to value, so it cannot resume from a list of finished values)", kBadArguments, exitCode);
        return;
    }
    if (so.mode == SweepMode::Continuation && mpiRank() != 0) {
        exitCode = kOk;  // sequential by nature: rank 0 runs it alone
        return;
    }
    if (so.mode == SweepMode::Continuation && mpiSize() > 1)
        std::fprintf(stderr, "stickslip-cli sweep: a continuation is sequential; it runs on rank 0 only\n");
    SweepResult r;
    if (so.mode == SweepMode::Continuation) r = bifurcationSweep(p, so, ctl);
    else if (!distributedIndependentSweep(o, p, so, r, exitCode)) return;
    if (mpiRank() != 0) {
        exitCode = kOk;  // rank 0 writes the output and reports
        return;
    }
    if (o.progress) std::fprintf(stderr, "\n");
    // Cancelled: no output (the finished values stay in the --checkpoint log, which resumes).
    if (cancelRequested()) {
        reportError("sweep", "sweep cancelled; no output written", kCancelled, exitCode);
        return;
    }
    if (!writeSweepFiles(o, unit, p, so, r, exitCode)) return;
    if (r.status == RunStatus::Failed) { reportError("sweep", "sweep failed: " + r.message, kRunFailed, exitCode); return; }
    if (r.status == RunStatus::Cancelled) { reportError("sweep", "sweep cancelled", kCancelled, exitCode); return; }
    exitCode = kOk;
}

}  // namespace

void addSweepCommand(CLI::App& root, int& exitCode) {
    auto opts = std::make_shared<SweepCliOptions>();
    auto* cmd = root.add_subcommand("sweep", "Bifurcation sweep of one parameter: Poincare samples and a per-value "
                                             "summary (stick / periodic / irregular, Lyapunov exponent)");
    addSimOptions(cmd, opts->sim);
    cmd->add_option("--param", opts->param, "Parameter key to sweep (A, f, tN, k, mu, eta, Dc, vc, ...)")
        ->capture_default_str();
    cmd->add_option("--from", opts->from, "First value (SI or with a unit, e.g. 0.1mm)")->required();
    cmd->add_option("--to", opts->to, "Last value")->required();
    cmd->add_option("--steps", opts->steps, "Number of values, endpoints included")->capture_default_str();
    cmd->add_option("--direction", opts->direction, "up, down or both (down continues from the end of up)")
        ->capture_default_str();
    cmd->add_option("--settle", opts->settle, "Cycles discarded per value")->capture_default_str();
    cmd->add_option("--samples", opts->samples, "Poincare samples (cycles) kept per value")->capture_default_str();
    auto* mode = cmd->add_option("--mode", opts->mode, "continuation (state carried over) or independent (each value "
                                                       "from rest, in parallel)")
                     ->capture_default_str();
    cmd->add_flag("--independent", opts->independent, "Short for --mode independent")->excludes(mode);
    cmd->add_option("--threads", opts->threads, "Threads for --mode independent, --concurrent-branches, and the Lyapunov companion trajectory in continuation (0 = all cores; under mpirun per rank)")
        ->capture_default_str();
    cmd->add_flag("--concurrent-branches", opts->concurrentBranches,
                  "With --direction both: start the down branch from rest at the top value (after a settle+samples "
                  "lead-in there) instead of from the end of the up branch, and run the two branches at the same time "
                  "(about half the wall time on 2 cores). Each branch still carries its state, so hysteresis shows; "
                  "only the down branch's starting state differs");
    cmd->add_option("--steps-per-period", opts->stepsPerPeriod, "Time steps per forcing period (0 = from --dt)")
        ->capture_default_str();
    addToleranceOption(cmd, opts->sim, "Poincare samples at the exact section phase from the dense output (with --no-lyapunov: the Lyapunov companion needs the fixed-step map); not --tol, the period test");
    cmd->add_option("--phase", opts->phase, "Section phase in the forcing cycle [rad]")->capture_default_str();
    cmd->add_option("--tol", opts->tol, "Relative tolerance of the period test")->capture_default_str();
    cmd->add_flag("--no-lyapunov", opts->noLyapunov, "Skip the largest Lyapunov exponent (halves the cost)");
    cmd->add_flag("--progress", opts->progress, "Print progress on stderr");
    cmd->add_option("--checkpoint", opts->checkpoint,
                    "With --mode independent: log each finished value to FILE; an existing FILE from the same "
                    "settings is resumed, one from other settings is refused");
    cmd->add_option("--out", opts->out, "Poincare samples CSV ('-' = stdout)")->required();
    cmd->add_option("--summary", opts->summary, "Per-value summary CSV");
    cmd->callback([opts, &exitCode] { runSweep(*opts, exitCode); });
}

}  // namespace stickslip::cli
