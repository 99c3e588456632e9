// 2-D periodicity map: the motion class (stick / period-n / irregular) over a grid of two
// parameters (e.g. A × f, A × tN). Every cell starts from rest (independent), and cells
// run in parallel; the result does not depend on the thread count.
#pragma once

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "../params.hpp"
#include "classify.hpp"

namespace stickslip {

struct MapOptions {
    std::string key1 = "A";   double from1 = 0.1e-3, to1 = 5e-3;  int steps1 = 20;  // x axis
    std::string key2 = "f";   double from2 = 3.0,    to2 = 10.0;  int steps2 = 20;  // y axis
    long settleCycles = 50;   // per cell [cycles]
    long sampleCycles = 64;   // per cell [cycles]
    long stepsPerPeriod = 0;  // N, dt = T/N; 0 = from params dt
    int threads = 0;          // 0 = all hardware threads
    ClassifyOptions classify;
    ParamIssues validate(const SimParams& base) const;
};

struct PeriodicityMap {
    std::string key1, key2;
    std::vector<double> values1, values2;     // grid axes
    // Row-major over (i2, i1): cell (i1, i2) at index i2 * values1.size() + i1.
    std::vector<MotionClass> motion;
    std::vector<int> period;                  // as Classification::period
    std::vector<double> stickFraction;        // [-]
    std::vector<double> maxRelVel_mps;        // [m/s]
    std::vector<unsigned char> done;          // 1 when the cell was computed (cancel leaves 0)
    RunStatus status = RunStatus::Ok;
    std::string message;
    std::size_t index(std::size_t i1, std::size_t i2) const { return i2 * values1.size() + i1; }
    bool ok() const { return status == RunStatus::Ok; }
};

PeriodicityMap periodicityMap(const SimParams& base, const MapOptions& opt, const RunControl& ctl = {});

// One cell of a map, as computed on its own: a pure function of (base, opt, index), so cells
// can be computed in any subsets, in any order, on any machine (MPI ranks, a resumed job) and
// assembled into exactly the one-call result.
struct MapCell {
    std::size_t index = 0;            // row-major, as PeriodicityMap::index
    RunStatus status = RunStatus::Cancelled;  // Ok = computed; Cancelled = not run or stopped
    MotionClass motion = MotionClass::Irregular;
    int period = 0;
    double stickFraction = 0;
    double maxRelVel_mps = 0;
    std::string message;              // Failed: "key = v, key2 = v: why"
};

// Number of cells of the grid opt describes (steps1 × steps2; 0 when a count is < 1).
std::size_t mapCellCount(const MapOptions& opt);

// Computes the cells `indices` (each < mapCellCount) in parallel on opt.threads threads. The
// result is aligned with `indices`; cells that never started (cancel) are left Cancelled.
// cellDone, when given, is called once per cell that ran (any status) under a lock, so it may
// write a file without further locking. Progress is the fraction of `indices` done.
// opt must validate (the caller checks MapOptions::validate first); otherwise every cell is
// returned Failed with the issues.
std::vector<MapCell> periodicityMapCells(const SimParams& base, const MapOptions& opt,
                                         const std::vector<std::size_t>& indices, const RunControl& ctl = {},
                                         const std::function<void(const MapCell&)>& cellDone = {});

// The map from per-cell records (any order, any subset; a later record of an index replaces
// an earlier one): axes from opt, status as periodicityMap (first failure by index, else
// Cancelled when a cell is missing). periodicityMap(b, o) equals
// assemblePeriodicityMap(b, o, periodicityMapCells(b, o, all indices)) bit for bit.
PeriodicityMap assemblePeriodicityMap(const SimParams& base, const MapOptions& opt, const std::vector<MapCell>& cells);

}  // namespace stickslip
