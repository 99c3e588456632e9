// Largest Lyapunov exponent of the forced stick–slip oscillator, by two nearby trajectories
// with renormalisation once per forcing period (Benettin). The system is nonsmooth (stick ↔
// slip switches): the perturbed trajectory carries its own full state (x, v, a and the law
// state F, α), so it may switch at a different step than the reference; the separation is
// measured in scaled (x, v, F, α) and rescaled back to d0 after every period, which keeps
// it small enough to stay in the same switching pattern almost always.
#pragma once

#include <string>
#include <vector>

#include "../integrate/dynamics.hpp"
#include "../params.hpp"
#include "poincare.hpp"

namespace stickslip {

// Scales that make the separation dimensionless: x / xScale, v / vScale, F / fScale, α / alphaScale.
struct SeparationScales {
    double x_m = 1e-3;
    double v_mps = 1e-2;
    double force_N = 1.0;
    double alpha = 1.0;
};
// x: μ t_N / k (slip displacement at the friction limit), v: that × ω_n, F: μ t_N, α: 1.
SeparationScales separationScales(const SimParams& p);

// Scaled distance between two states over (x, v, F, α).
double stateSeparation(const DynState& a, const DynState& b, const SeparationScales& sc);

// A copy of `s` displaced by a scaled distance d0 along (x, v) = (1, 1)/√2 (in scaled units),
// with the Newmark acceleration made consistent: δa = −(k δx + c δv) / m.
DynState perturbedState(const DynState& s, const RigParams& rig, const SeparationScales& sc, double d0);

// Pull `pert` back towards `ref` so that their separation is d0 (every state component
// scaled by the same factor). Returns the separation before rescaling.
double renormalise(const DynState& ref, DynState& pert, const SeparationScales& sc, double d0);

struct LyapunovOptions {
    long stepsPerPeriod = 0;   // N steps per forcing period; 0 = from params dt
    long settleCycles = 50;    // discarded before measuring [-]
    long cycles = 100;         // cycles averaged over [-]
    double d0 = 1e-7;          // initial / renormalised scaled separation [-]
    ParamIssues validate() const;
};

struct LyapunovResult {
    double perCycle = 0;            // λ_max per forcing cycle [1/cycle]
    double perSecond = 0;           // λ_max per second = perCycle · f [1/s]
    std::vector<double> logGrowth;  // ln(d/d0) of every cycle (their mean is perCycle)
    RunStatus status = RunStatus::Ok;
    std::string message;
    bool ok() const { return status == RunStatus::Ok; }
};

// From rest: settle, then measure over `cycles` periods. Validates p and the options.
LyapunovResult largestLyapunov(const SimParams& p, const LyapunovOptions& opt, const RunControl& ctl = {});

// From a prepared (settled) state; `ref` is advanced by cycles·stepsPerPeriod steps.
// When `section` is given, the reference trajectory's Poincaré samples and motion
// measures are recorded into it as poincareSectionFrom would (sharing the work).
// companionThread: advance the companion trajectory on a second thread while the reference
// advances (they meet once per cycle to renormalise); the same operations, so the same result
// bit for bit, in about half the wall time on two idle cores.
LyapunovResult largestLyapunovFrom(const DynamicsModel& m, DynState& ref, long stepsPerPeriod, long cycles,
                                   double d0, const SeparationScales& sc, const RunControl& ctl = {},
                                   PoincareSection* section = nullptr, bool companionThread = false);

}  // namespace stickslip
