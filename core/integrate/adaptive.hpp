// Error-controlled integration of the spring–mass rig (issue 15): a base step used in a local
// Richardson extrapolation with step-size control, stick–slip switches located, and dense output
// on the requested sampling grid.
//
// The base step: for laws with a rate-form flow rule (the rate-state law) TR-BDF2
// (trbdf2.hpp), whose two stages are each the law's own return map, second order and L-stable;
// otherwise (Coulomb, Dieterich–Ruina, or AdaptiveOptions::trBdf2 = false) the paper's step
// (Newmark average acceleration + the law's backward-Euler return map, dynamics.hpp). Either way
// the law stays a constrained update solved by its return map with the consistent tangent.
// The global error of the base step expands as
//   e(h) = c2 h² + c3 h³ + …   TR-BDF2, stick and slip,
//   e(h) = c1 h + c2 h² + …   Newmark + backward Euler while slipping (c1 ≠ 0),
//   e(h) = c2 h² + c4 h⁴ + …  Newmark while stuck (the law is linear elastic, the step is the
//                              symmetric trapezoidal rule: only even powers),
// so with one step h (y₁) and two steps h/2 (y₂) per accepted step
//   y = (4 y₂ − y₁)/3   removes c2 (TR-BDF2 always; Newmark while stuck),
//   y = 2 y₂ − y₁       removes c1 (Newmark while slipping),
// and y₂ − y₁ is the embedded error estimate (of y₂, so conservative for y). TR-BDF2 slip steps
// are judged instead by the difference of two third-order values, y and the scheme's TR-X
// companion of y₁ (the error of what is kept), with velocity errors weighted by the rig's ringing
// time 1/ω_n (adaptive.cpp, kRoundoffUlps). A switch inside
// a step would spoil both (the solution has a kink there), so the step is cut at the switch:
// the stick → slip time is the root of the trial slip function Φ_trial(τ) of the scheme's own
// elastic step of length τ (Eq. 1; Illinois), the slip → stick time the largest τ whose step
// still slips (bisection). With AdaptiveOptions::embeddedSlip, TR-BDF2 slip steps are not
// doubled: one step, judged by the scheme's embedded estimate (trbdf2.hpp, TrError), its
// second-order result kept. Cost: 3 base steps per doubled step (1 per embedded one); the step constants
// (NewmarkConstants / TrBdf2Constants, law.prepare) cached on a grid of step sizes
// h_k = h_max 2^(−k/4).
#pragma once

#include <functional>
#include <string>

#include "../params.hpp"
#include "dynamics.hpp"
#include "run_result.hpp"

namespace stickslip {

// Settings of the adaptive integrator (defaults suit the paper's parameter sets).
struct AdaptiveOptions {
    // Target of the relative displacement error max|x − x_exact| / max|x_exact| of a run,
    // 1e-5 … 0.5 (validate()).
    double tolerance = 1e-4;
    double maxStep_s = 0;       // largest step [s]; 0: T/32 of the forcing period (or 1e-2 s)
    double minStep_s = 0;       // smallest regular step [s]; 0: 2^-26 of the largest step
    double displacementScale_m = 0;  // floor of the error scale [m]; 0: 5 % of the stage amplitude
    long maxSteps = 50'000'000;      // accepted + rejected steps of one call: more fails the run
    bool locateSwitches = true;      // cut steps at stick–slip switches (off: error control only)
    // Laws with a rate-form flow rule (the rate-state law) step by TR-BDF2 (trbdf2.hpp), second
    // order in stick and slip; false: the paper's Newmark + backward-Euler step, extrapolated
    // (order 1.31 in rate-state slip; kept for comparison).
    bool trBdf2 = true;
    // While the contact sticks, step the rig in closed form (stuck_flow.hpp: exact for laws
    // elastic in stick under a harmonic stage; the scheme's steps otherwise). False: the
    // scheme's steps throughout (kept for comparison).
    bool closedFormStick = true;
    // TR-BDF2 slip steps judged by the scheme's embedded estimate (trbdf2.hpp, TrError): one
    // base step per attempt, the second-order result kept. Off by default: on the Fig. 20
    // preset (ε_T = 1.1e4, A = 1 mm) the slider rings while it slides, a velocity error then
    // becomes a displacement error v/ω over the ringing rather than h·v over one step, and the
    // runs ended ~10× TOL off (docs/adaptive.md, session 25). Default: step doubling with the
    // extrapolated (third-order) value kept, three base steps per attempt.
    bool embeddedSlip = false;
    ParamIssues validate() const;
};

// What one adaptive call did.
struct AdaptiveReport {
    RunStatus status = RunStatus::Ok;
    std::string message;
    long accepted = 0;       // accepted steps
    long rejected = 0;       // steps redone with a smaller size
    long switches = 0;       // located stick–slip switches
    long baseSteps = 0;      // Newmark + return-map steps taken (all attempts and root finding)
    long lawIterations = 0;
    long stuckSteps = 0;     // accepted steps that stuck
    long closedFormSteps = 0;  // of those, taken in closed form (no base step)
};

// Called after every accepted step with the states at both of its ends.
using AdaptiveObserver = std::function<void(const DynState& prev, const DynState& cur)>;

// Advance s to exactly tEnd with error-controlled steps (the model's dt_s is not used). Never
// throws; polls ctl's cancel flag every 256 accepted steps.
AdaptiveReport advanceAdaptive(const DynamicsModel& m, DynState& s, double tEnd, const AdaptiveOptions& o,
                               const AdaptiveObserver& onStep = {}, const RunControl& ctl = {});

// Dense output between two accepted states a (t_a) and b (t_b), t in [t_a, t_b]: cubic Hermite
// in x (from x, ẋ at both ends) and in ẋ (from ẋ, ẍ), linear in F and α, the stage exact;
// stuck and slip rate are b's. Third-order accurate, matching the scheme's order.
DynState denseState(const DynamicsModel& m, const DynState& a, const DynState& b, double t);

// A full run as SimParams say (transient discarded, `cycles` recorded every
// integration.outputInterval_s exactly, from the dense output), integrated adaptively with
// `o`. The once-per-period states (RunResult::period) are taken at the exact phase t = kT from
// the dense output; period.stepsPerPeriod is then the nominal T/dt of p (1 if dt does not divide T).
RunResult simulateAdaptive(const SimParams& p, const AdaptiveOptions& o, const RunControl& ctl = {});

}  // namespace stickslip
