// 2-D periodicity map: the motion class (stick / period-n / irregular) over a grid of two
// parameters (e.g. A × f, A × tN). Every cell starts from rest (independent), and cells
// run in parallel; the result does not depend on the thread count.
#pragma once

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

}  // namespace stickslip
