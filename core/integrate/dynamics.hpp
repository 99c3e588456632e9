// Spring–mass dynamics (paper Fig. 15b, Eq. 8): m* ẍ + c ẋ + k x = F, with the stage
// displacement u(t) prescribed and F from a friction law driven by the slip g = u − x.
//
// Time stepping: Newmark average acceleration (β = 1/4, γ = 1/2), coupled implicitly to the
// law's return mapping. Per step we solve r(x) = 0 for the slider displacement x_{n+1}:
//   a_{n+1} = 4/h² (x − x_n − h v_n) − a_n,   v_{n+1} = 2/h (x − x_n) − v_n,
//   r(x)    = K_eff x − b − F(Δg),   Δg = (u_{n+1} − u_n) − (x − x_n),
//   K_eff   = 4m/h² + 2c/h + k,      b = m (4/h² (x_n + h v_n) + a_n) + c (2/h x_n + v_n),
// by Newton with the consistent tangent: dr/dx = K_eff + dF/dΔg. The first iterate is the
// elastic (stick) predictor, which is exact when the step sticks, so a stuck step costs one
// law evaluation. Unconditionally stable; the step is set by accuracy alone.
#pragma once

#include <cmath>
#include <cstdio>
#include <string>
#include <variant>

#include "../friction/friction_law.hpp"
#include "../params.hpp"
#include "run_result.hpp"
#include "stage_motion.hpp"

namespace stickslip {

// Changing state of the oscillator and the contact.
struct DynState {
    double t = 0;        // time [s]
    double x = 0;        // slider displacement [m]
    double v = 0;        // slider velocity [m/s]
    double a = 0;        // slider acceleration [m/s²]
    double u = 0;        // stage displacement at t [m]
    LawState law;        // friction force and α
    double slipRate = 0; // λ̇ of the last step [m/s]
    bool stuck = true;   // last step was elastic
};

// Constant model of a dynamics run.
struct DynamicsModel {
    RigParams rig;
    StageMotion stage = StageMotion::harmonic(DriveParams{});
    FrictionLaw law;
    double dt_s = 1.0 / 30000.0;

    static DynamicsModel fromParams(const SimParams& p);
    // State at rest at time t: x = v = 0, F = 0, α = 0, u = u(t).
    DynState initialState(double t = 0.0) const;
};

struct StepReport {
    RunStatus status = RunStatus::Ok;
    std::string message;
    long stepsDone = 0;
    long newtonIterations = 0;
    long lawIterations = 0;
    long stuckSteps = 0;
};

namespace detail {

inline std::string stepFailure(long step, double t, const char* what, double value) {
    char buf[256];
    std::snprintf(buf, sizeof buf, "step %ld at t = %.9g s: %s (value %.6g)", step, t, what, value);
    return buf;
}

// One Newmark step; returns false (with a message in `why`) if it cannot converge.
template <class Law>
inline bool newmarkStep(const RigParams& rig, const Law& law, const StageMotion& stage, double h, DynState& s,
                        int& newtonIts, int& lawIts, const char*& why, double& badValue) {
    const double m = rig.mass_kg, c = rig.damping_Ns_per_m, k = rig.stiffness_N_per_m, tN = rig.normalForce_N;
    const double t1 = s.t + h;
    const double u1 = stage.displacement(t1);
    const double du = u1 - s.u;
    const double i4h2 = 4.0 / (h * h), i2h = 2.0 / h;
    const double Keff = m * i4h2 + c * i2h + k;
    const double b = m * (i4h2 * (s.x + h * s.v) + s.a) + c * (i2h * s.x + s.v);
    const double eps = law.epsT();
    // Elastic predictor: F = F_n + ε Δg is linear in x.
    double x = (b + s.law.force_N + eps * (du + s.x)) / (Keff + eps);
    ReturnMapResult rm = law.returnMap(s.law, du - (x - s.x), h, tN);
    lawIts += rm.iterations;
    newtonIts = 1;
    if (!rm.stuck) {
        bool ok = false;
        const double xtol = 1e-13 * (std::abs(s.x) + std::abs(du)) + 1e-18;
        for (int it = 0; it < 60; ++it) {
            const double r = Keff * x - b - rm.state.force_N;
            const double J = Keff + rm.tangent_N_per_m;
            const double dx = r / J;
            x -= dx;
            rm = law.returnMap(s.law, du - (x - s.x), h, tN);
            lawIts += rm.iterations;
            ++newtonIts;
            if (!rm.converged) { why = "return mapping did not converge (slip increment)"; badValue = rm.slipIncrement_m; return false; }
            if (std::abs(dx) <= xtol) { ok = true; break; }
        }
        if (!ok) { why = "slider Newton iteration did not converge (x)"; badValue = x; return false; }
    }
    const double a1 = i4h2 * (x - s.x - h * s.v) - s.a;
    const double v1 = i2h * (x - s.x) - s.v;
    if (!std::isfinite(x) || !std::isfinite(v1) || !std::isfinite(a1)) { why = "non-finite slider state (x)"; badValue = x; return false; }
    if (!std::isfinite(rm.state.force_N) || !std::isfinite(rm.state.alpha)) { why = "non-finite friction force (F)"; badValue = rm.state.force_N; return false; }
    s.t = t1; s.x = x; s.v = v1; s.a = a1; s.u = u1;
    s.law = rm.state;
    s.slipRate = rm.slipIncrement_m / h;
    s.stuck = rm.stuck;
    return true;
}

template <class Law, class Obs>
StepReport advanceWith(const DynamicsModel& m, const Law& law, DynState& s, long n, Obs& obs, const RunControl& ctl,
                       long stepOffset) {
    StepReport rep;
    const long block = 4096;
    for (long i = 0; i < n; ++i) {
        if ((i % block) == 0 && i > 0) {
            if (ctl.cancelled()) { rep.status = RunStatus::Cancelled; rep.message = "cancelled"; return rep; }
        }
        int nIts = 0, lIts = 0;
        const char* why = nullptr;
        double bad = 0;
        if (!newmarkStep(m.rig, law, m.stage, m.dt_s, s, nIts, lIts, why, bad)) {
            rep.status = RunStatus::Failed;
            rep.message = stepFailure(stepOffset + i + 1, s.t + m.dt_s, why, bad);
            return rep;
        }
        rep.newtonIterations += nIts;
        rep.lawIterations += lIts;
        rep.stuckSteps += s.stuck ? 1 : 0;
        ++rep.stepsDone;
        obs(s);
    }
    return rep;
}

}  // namespace detail

// Advance the state by n steps, calling obs(const DynState&) after each. Polls the cancel
// flag every 4096 steps. stepOffset only numbers steps in failure messages.
template <class Obs>
StepReport advance(const DynamicsModel& m, DynState& s, long n, Obs&& obs, const RunControl& ctl = {},
                   long stepOffset = 0) {
    return std::visit([&](const auto& law) { return detail::advanceWith(m, law, s, n, obs, ctl, stepOffset); }, m.law);
}

// Advance without observing the intermediate states.
inline StepReport advanceQuiet(const DynamicsModel& m, DynState& s, long n, const RunControl& ctl = {}) {
    return advance(m, s, n, [](const DynState&) {}, ctl);
}

Sample toSample(const DynamicsModel& m, const DynState& s);

// A full run as SimParams say: transient cycles discarded, then `cycles` recorded at the
// output interval. Validates the parameters first (Failed with the list of issues).
RunResult simulateDynamics(const SimParams& p, const RunControl& ctl = {});
// The same from a prepared model and state (continuation, fits): runs `steps` steps,
// recording every `outputEvery` steps (and the start state when recordStart).
RunResult simulateDynamics(const DynamicsModel& m, DynState& s, long steps, long outputEvery, bool recordStart,
                           const RunControl& ctl = {});

}  // namespace stickslip
