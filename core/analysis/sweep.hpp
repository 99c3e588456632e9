// Bifurcation sweep of any parameter key (A, f, tN, k, mu, eta, Dc, vc, …; see setParam):
// per value, settleCycles are discarded and sampleCycles Poincaré samples kept.
//  - Continuation (the paper's way): the state is carried from one value to the next,
//    upwards, downwards or both (down starts from the end of the up branch, so hysteresis
//    shows as the two branches differing). Sequential by nature.
//    With concurrentBranches (direction both only) the down branch instead starts from rest at
//    the top value and first runs there as long as the up branch does (settle + sample cycles,
//    discarded), then continues downwards exactly as before. The two branches are then
//    independent and run at the same time on two threads (threads ≠ 1), about halving the wall
//    time; each branch still carries its state from value to value, so hysteresis (values
//    where the branches settle on different attractors) still shows. Only the state the down
//    branch starts from differs, so where attractors coexist it can pick another one (Fig. 20
//    sweep, 300 values: its down branch differs in class from the sequential one at 5 values,
//    all next to irregular windows). The result is the same on one thread or two.
//  - Independent: every value starts from rest; values run in parallel on `threads`
//    threads. Each value is a pure function of (params, value), so the result is
//    bit-identical whatever the thread count.
// Lyapunov exponent (lyapunov): in continuation with one branch at a time and threads ≠ 1, the
// companion trajectory runs on a second thread (same result, bit for bit).
// Progress: fraction of values done (called under a lock, possibly from worker threads).
// Cancel: polled every 4096 steps; the result then holds the values finished so far.
#pragma once

#include <cstddef>
#include <functional>
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
    int threads = 0;                // independent mode, concurrent branches, Lyapunov companion; 0 = all cores
    bool concurrentBranches = false;  // continuation, both: down branch from rest at the top, concurrent (above)
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

// Mode independent, one value on its own: a pure function of (base, opt, index), so values can
// be computed in any subsets (MPI ranks) and assembled into exactly the one-call result.
// index counts the ascending values (sweepValues(min(from,to), max(from,to), steps)).
struct SweepValueRecord {
    std::size_t index = 0;
    bool done = false;   // the value ran (point.section.status tells how it ended)
    SweepPoint point;    // direction +1
};

// Computes the values `indices` (each < opt.steps) from rest on opt.threads threads; aligned
// with `indices`, values never started (cancel) have done = false. valueDone, when given, is
// called once per value that ran, under a lock. opt must validate (every record is returned
// done with a Failed section otherwise).
std::vector<SweepValueRecord> independentSweepValues(const SimParams& base, const SweepOptions& opt,
                                                     const std::vector<std::size_t>& indices,
                                                     const RunControl& ctl = {},
                                                     const std::function<void(const SweepValueRecord&)>& valueDone = {});

// The independent-mode SweepResult from records (any order and subset; a later record of an
// index replaces an earlier one): bifurcationSweep(b, o) with o.mode independent equals
// assembleIndependentSweep(b, o, independentSweepValues(b, o, all indices)) bit for bit.
SweepResult assembleIndependentSweep(const SimParams& base, const SweepOptions& opt,
                                     const std::vector<SweepValueRecord>& records);

}  // namespace stickslip
