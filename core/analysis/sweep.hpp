// Bifurcation sweep of any parameter key (A, f, tN, k, mu, eta, Dc, vc, …; see setParam):
// per value, settleCycles are discarded and sampleCycles Poincaré samples kept.
//  - Continuation (the paper's way): the state is carried from one value to the next,
//    upwards, downwards or both (down starts from the end of the up branch, so hysteresis
//    shows as the two branches differing). Sequential by nature.
//  - Independent: every value starts from rest; values run in parallel on `threads`
//    threads. Each value is a pure function of (params, value), so the result is
//    bit-identical whatever the thread count.
// Progress: fraction of values done (called under a lock, possibly from worker threads).
// Cancel: polled every 4096 steps; the result then holds the values finished so far.
#pragma once

#include <string>
#include <vector>

#include "../params.hpp"
#include "classify.hpp"
#include "poincare.hpp"

namespace stickslip {

enum class SweepMode { Continuation, Independent };
enum class SweepDirection { Up, Down, Both };
const char* toString(SweepMode);       // "continuation", "independent"
const char* toString(SweepDirection);  // "up", "down", "both"
bool parseSweepMode(const std::string&, SweepMode&);
bool parseSweepDirection(const std::string&, SweepDirection&);

struct SweepOptions {
    std::string key = "A";          // parameter key (setParam)
    double from = 0.1e-3;           // first value (SI units of the key)
    double to = 5e-3;               // last value
    int steps = 50;                 // number of values, endpoints included (≥ 1)
    SweepDirection direction = SweepDirection::Up;
    SweepMode mode = SweepMode::Continuation;
    long settleCycles = 50;         // per value, discarded [cycles]
    long sampleCycles = 100;        // per value, Poincaré samples kept [cycles]
    long stepsPerPeriod = 0;        // N, dt = T/N; 0 = from params dt
    double phase_rad = 0.0;         // section phase [rad]
    int threads = 0;                // independent mode; 0 = all hardware threads
    bool lyapunov = false;          // also compute the largest Lyapunov exponent per value (2× cost)
    double lyapunovD0 = 1e-7;       // scaled separation for the Lyapunov companion trajectory
    ClassifyOptions classify;
    // Every violated field (and an unknown key, or a base value that fails validation).
    ParamIssues validate(const SimParams& base) const;
};

struct SweepPoint {
    double value = 0;               // parameter value
    int direction = +1;             // +1 up branch, −1 down branch
    PoincareSection section;        // samples and motion measures
    Classification classification;
    double lyapunovPerCycle = 0;    // NaN when not computed
    double lyapunovPerSecond = 0;   // NaN when not computed
};

struct SweepResult {
    RunStatus status = RunStatus::Ok;
    std::string message;
    std::string key;
    std::vector<SweepPoint> points;  // up branch first (ascending), then down (descending)
    bool ok() const { return status == RunStatus::Ok; }
};

// The values of a sweep: steps values from `from` to `to` inclusive, evenly spaced.
std::vector<double> sweepValues(double from, double to, int steps);

SweepResult bifurcationSweep(const SimParams& base, const SweepOptions& opt, const RunControl& ctl = {});

}  // namespace stickslip
