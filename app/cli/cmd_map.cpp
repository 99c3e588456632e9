// `stickslip-cli map`: periodicity class over a grid of two parameters, in parallel on the
// threads of one process and, under mpirun, across ranks (a rank-0 work queue hands out cells;
// rank 0 gathers them and writes the CSV). --checkpoint logs each finished cell so that a
// killed run resumes where it stopped. The CSV is the same byte for byte in every case.
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <tuple>

#include "cancel.hpp"
#include "cell_records.hpp"
#include "checkpoint_plan.hpp"
#include "cli_common.hpp"
#include "mpi_runner.hpp"
#include "core/analysis/periodicity_map.hpp"
#include "core/io/csv_table.hpp"
#include "core/io/units.hpp"
#include "core/version.hpp"

namespace stickslip::cli {

namespace {

struct MapCliOptions {
    SimOptions sim;
    std::string param = "A", from, to, param2 = "f", from2, to2, out, checkpoint;
    int steps = 20, steps2 = 20, threads = 0;
    long settle = 50, samples = 64, stepsPerPeriod = 0;
    double tol = 1e-4;
    bool progress = false;
};

std::string num(double v) {
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.10g", v);
    return buf;
}

// Every setting that changes a cell's result (not --threads, --progress, --out), for the
// checkpoint's fingerprint: the options as given and the parameters they resolved to.
std::string settingsText(const MapCliOptions& o, const SimParams& p, const MapOptions& mo) {
    auto g = [](double v) { return exactNumber(v); };
    std::string t = std::string("map ") + kVersion + "\n" + simSettingsText(o.sim, p);
    t += mo.key1 + " " + g(mo.from1) + " " + g(mo.to1) + " " + std::to_string(mo.steps1) + "\n";
    t += mo.key2 + " " + g(mo.from2) + " " + g(mo.to2) + " " + std::to_string(mo.steps2) + "\n";
    t += "settle " + std::to_string(mo.settleCycles) + " samples " + std::to_string(mo.sampleCycles) + " n " +
         std::to_string(stepsPerPeriodFor(p, mo.stepsPerPeriod)) + " tol " + g(mo.classify.relTol) + "\n";
    return t;
}

// The map CSV exactly as a one-process run writes it (cells row by row, done ones only).
std::string mapCsv(const MapCliOptions& o, const std::string& u1, const std::string& u2, const SimParams& p,
                   const MapOptions& mo, const PeriodicityMap& m) {
    std::string csv = std::string("# stickslip-cli ") + kVersion + " map\n# param = " + o.param + " [" + u1 +
                      "]\n# param2 = " + o.param2 + " [" + u2 + "]\n# settle = " + std::to_string(mo.settleCycles) +
                      " cycles, samples = " + std::to_string(mo.sampleCycles) + ", " + steppingText(p, mo.stepsPerPeriod) + ", period tolerance = " +
                      num(mo.classify.relTol) + "\n# status = " + toString(m.status) +
                      (m.message.empty() ? "" : " (" + m.message + ")") + "\n";
    csv += "param_value,param2_value,class,period,stick_fraction,max_rel_vel_mps\n";
    for (std::size_t i2 = 0; i2 < m.values2.size(); ++i2)
        for (std::size_t i1 = 0; i1 < m.values1.size(); ++i1) {
            const std::size_t k = m.index(i1, i2);
            if (!m.done[k]) continue;
            csv += num(m.values1[i1]) + "," + num(m.values2[i2]) + "," + toString(m.motion[k]) + "," +
                   std::to_string(m.period[k]) + "," + num(m.stickFraction[k]) + "," + num(m.maxRelVel_mps[k]) + "\n";
        }
    return csv;
}

void runMap(const MapCliOptions& o, int& exitCode) {
    SimParams p;
    std::string error;
    if (const int rc = buildSimParams(o.sim, p, &error); rc != kOk) {
        reportError("map", error, rc, exitCode);
        return;
    }
    MapOptions mo;
    mo.key1 = o.param;
    mo.key2 = o.param2;
    std::string u1, u2;
    for (const auto& [flag, key, unit] : {std::tuple{"--param", &o.param, &u1}, std::tuple{"--param2", &o.param2, &u2}})
        if (!io::paramUnit(*key, *unit)) {
            reportError("map", std::string(flag) + " '" + *key + "' is not a parameter key", kBadArguments, exitCode);
            return;
        }
    if (!io::parseParamValue(o.param, o.from, mo.from1, &error) || !io::parseParamValue(o.param, o.to, mo.to1, &error) ||
        !io::parseParamValue(o.param2, o.from2, mo.from2, &error) ||
        !io::parseParamValue(o.param2, o.to2, mo.to2, &error)) {
        reportError("map", error, kBadArguments, exitCode);
        return;
    }
    mo.steps1 = o.steps;
    mo.steps2 = o.steps2;
    mo.settleCycles = o.settle;
    mo.sampleCycles = o.samples;
    mo.stepsPerPeriod = o.stepsPerPeriod;
    mo.threads = o.threads;
    mo.classify.relTol = o.tol;
    if (ParamIssues issues = mo.validate(p); !issues.empty()) {
        reportError("map", formatIssues(issues), kBadArguments, exitCode);
        return;
    }
    CheckpointLog ckpt;
    std::vector<MapCell> records;
    std::vector<std::size_t> todo;
    const std::size_t cells = mapCellCount(mo);
    const CheckpointSpec spec{o.checkpoint, "map", settingsText(o, p, mo), "cells " + std::to_string(cells),
                              "cell INDEX MOTION PERIOD STICK_FRACTION MAX_REL_VEL, INDEX < " + std::to_string(cells)};
    if (planFromCheckpoint<MapCell>(spec, cells, parseMapCellLine, ckpt, records, todo, exitCode) != kOk) return;
    const std::size_t total = mapCellCount(mo);
    std::string ckptError;
    mpiDistribute(
        todo, batchSize(mo.threads),
        [&](const std::vector<std::size_t>& mine, const EmitFn& emit) {
            RunControl ctl;
            ctl.cancel = &cancelFlag();
            periodicityMapCells(p, mo, mine, ctl, [&](const MapCell& c) { emit(encodeMapCell(c)); });
        },
        [&](const std::string& bytes) {
            MapCell c;
            if (!decodeMapCell(bytes, c)) c = MapCell{};  // cannot happen between ranks of one binary
            records.push_back(c);
            if (c.status == RunStatus::Ok && ckptError.empty()) ckpt.append(formatMapCellLine(c), &ckptError);
            if (o.progress)
                std::fprintf(stderr, "\rmap: %5.1f %%", 100.0 * static_cast<double>(records.size()) / double(total));
        });
    if (mpiRank() != 0) {
        exitCode = kOk;  // rank 0 writes the output and reports
        return;
    }
    if (o.progress) std::fprintf(stderr, "\n");
    // Cancelled: no output (the finished cells stay in the --checkpoint log, which resumes).
    if (cancelRequested()) {
        reportError("map", ckptError.empty() ? "map cancelled; no output written" : ckptError, kCancelled, exitCode);
        return;
    }
    const PeriodicityMap m = assemblePeriodicityMap(p, mo, records);
    const std::string csv = mapCsv(o, u1, u2, p, mo, m);
    if (!io::writeFileAtomically(o.out, csv, &error)) {
        reportError("map", error, kBadInput, exitCode);
        return;
    }
    if (!ckptError.empty()) { reportError("map", ckptError, kBadInput, exitCode); return; }
    if (m.status == RunStatus::Failed) { reportError("map", "map failed: " + m.message, kRunFailed, exitCode); return; }
    if (m.status == RunStatus::Cancelled) { reportError("map", "map cancelled", kCancelled, exitCode); return; }
    exitCode = kOk;
}

}  // namespace

void addMapCommand(CLI::App& root, int& exitCode) {
    auto opts = std::make_shared<MapCliOptions>();
    auto* cmd = root.add_subcommand("map", "Periodicity map: motion class over a grid of two parameters (parallel)");
    addSimOptions(cmd, opts->sim);
    cmd->add_option("--param", opts->param, "First parameter key (x axis)")->capture_default_str();
    cmd->add_option("--from", opts->from, "First value of --param (SI or with a unit)")->required();
    cmd->add_option("--to", opts->to, "Last value of --param")->required();
    cmd->add_option("--steps", opts->steps, "Values of --param")->capture_default_str();
    cmd->add_option("--param2", opts->param2, "Second parameter key (y axis)")->capture_default_str();
    cmd->add_option("--from2", opts->from2, "First value of --param2")->required();
    cmd->add_option("--to2", opts->to2, "Last value of --param2")->required();
    cmd->add_option("--steps2", opts->steps2, "Values of --param2")->capture_default_str();
    cmd->add_option("--settle", opts->settle, "Cycles discarded per cell")->capture_default_str();
    cmd->add_option("--samples", opts->samples, "Poincare samples per cell")->capture_default_str();
    cmd->add_option("--steps-per-period", opts->stepsPerPeriod, "Time steps per forcing period (0 = from --dt)")
        ->capture_default_str();
    addToleranceOption(cmd, opts->sim, "Poincare samples at the exact phase from the dense output; not --tol, the period test");
    cmd->add_option("--threads", opts->threads, "Threads per process (0 = all cores; under mpirun per rank)")
        ->capture_default_str();
    cmd->add_option("--tol", opts->tol, "Relative tolerance of the period test")->capture_default_str();
    cmd->add_flag("--progress", opts->progress, "Print progress on stderr");
    cmd->add_option("--checkpoint", opts->checkpoint,
                    "Log each finished cell to FILE; an existing FILE from the same settings is resumed (its cells "
                    "are not computed again), one from other settings is refused");
    cmd->add_option("--out", opts->out, "Map CSV ('-' = stdout)")->required();
    cmd->callback([opts, &exitCode] { runMap(*opts, exitCode); });
}

}  // namespace stickslip::cli
