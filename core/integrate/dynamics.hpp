// Spring–mass dynamics (paper Fig. 15b, Eq. 8): m* ẍ + c ẋ + k x = F, with the stage
// displacement u(t) prescribed and F from a friction law driven by the slip g = u − x.
//
// Time stepping: Newmark average acceleration (β = 1/4, γ = 1/2), coupled implicitly to the
// law's return mapping. Per step we solve r(x) = 0 for the slider displacement x_{n+1}:
//   a_{n+1} = 4/h² (x − x_n − h v_n) − a_n,   v_{n+1} = 2/h (x − x_n) − v_n,
//   r(x)    = K_eff x − b − F(Δg),   Δg = (u_{n+1} − u_n) − (x − x_n),
//   K_eff   = 4m/h² + 2c/h + k,      b = m (4/h² (x_n + h v_n) + a_n) + c (2/h x_n + v_n),
// by Newton with the consistent tangent: dr/dx = K_eff + dF/dΔg. The first iterate is the
// elastic (stick) predictor x*, which is exact when the step sticks, so a stuck step costs one
// law evaluation. Unconditionally stable; the step is set by accuracy alone.
//
// Static condensation (the default, Coupling::Condensed): r is linear in x apart from F, and
// in a slipping step F = F* + ε_T (x* − x) − s ε_T Δλ with F* = K_eff x* − b the predictor
// force. Eliminating x from r = 0 gives x − x* = (F − F*)/K_eff and
//   F = F* − s ε_eff Δλ,   ε_eff = ε_T K_eff / (K_eff + ε_T),
// i.e. the coupled system is the law's own scalar return map from the trial F* with the return
// stiffness ε_eff (the contact in series with the structure). Its root is the fixed point of the
// monolithic Newton iteration, reached with one bracketed scalar solve instead of nested
// iterations. Coupling::Newton keeps the monolithic iteration (for laws without
// returnMapFromTrial, and to verify that both paths agree).
#pragma once

#include <cmath>
#include <concepts>
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

enum class Coupling { Condensed, Newton };

// Constant model of a dynamics run.
struct DynamicsModel {
    RigParams rig;
    StageMotion stage = StageMotion::harmonic(DriveParams{});
    FrictionLaw law;
    double dt_s = 1.0 / 30000.0;
    Coupling coupling = Coupling::Condensed;

    static DynamicsModel fromParams(const SimParams& p);
    // State at rest at time t: x = v = 0, F = 0, α = 0, u = u(t).
    DynState initialState(double t = 0.0) const;
    // Every invalid rig or law parameter or step (as SimParams::validate reports them).
    ParamIssues validate() const;
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

template <class Law>
concept HasPreparedReturnMap = requires(const Law& l, const LawState& s) {
    { l.prepare(0.0, 0.0, 0.0).returnMapFromTrial(s, 0.0) } -> std::same_as<ReturnMapResult>;
};

// Constants of a run's steps (h, m, c, k, t_N fixed), computed once.
struct NewmarkConstants {
    double h, m, c, k, tN, i4h2, i2h, Keff, invKeff, eps, invPredictor, returnStiffness;
    NewmarkConstants(const RigParams& rig, double epsT, double dt)
        : h(dt), m(rig.mass_kg), c(rig.damping_Ns_per_m), k(rig.stiffness_N_per_m), tN(rig.normalForce_N),
          i4h2(4.0 / (dt * dt)), i2h(2.0 / dt), Keff(m * i4h2 + c * i2h + k), invKeff(1.0 / Keff), eps(epsT),
          invPredictor(1.0 / (Keff + epsT)), returnStiffness(epsT * Keff / (Keff + epsT)) {}
};

// u(t_n) and u̇(t_n) for consecutive steps: exact for tabulated motion; for harmonic motion a
// rotation recurrence on (sin, cos) of the phase (one multiply-add pair instead of a sin and a
// cos per step), re-anchored to the exact values every 256 steps so round-off cannot accumulate.
class StageSequence {
public:
    StageSequence(const StageMotion& m, double t0, double h) : m_(m), t0_(t0), h_(h), harmonic_(m.isHarmonic()) {
        if (harmonic_) {
            velAmp_ = m.amplitude() * m.omega();
            cr_ = std::cos(m.omega() * h);
            sr_ = std::sin(m.omega() * h);
            anchor(0);
        }
    }
    // Stage displacement at t0 + i h, for i = 1, 2, ... in order.
    double next() {
        ++i_;
        if (!harmonic_) return m_.displacement(t0_ + static_cast<double>(i_) * h_);
        if ((i_ & 255) == 0) { anchor(i_); return m_.amplitude() * s_; }
        const double s1 = s_ * cr_ + c_ * sr_;
        c_ = c_ * cr_ - s_ * sr_;
        s_ = s1;
        return m_.amplitude() * s_;
    }
    // Stage velocity at the time of the last next() (t0 before the first).
    double velocity() const {
        return harmonic_ ? velAmp_ * c_ : m_.velocity(t0_ + static_cast<double>(i_) * h_);
    }

private:
    void anchor(long i) {
        const double th = m_.omega() * (t0_ + static_cast<double>(i) * h_) + m_.phase();
        s_ = std::sin(th);
        c_ = std::cos(th);
    }
    const StageMotion& m_;
    double t0_, h_;
    bool harmonic_;
    double velAmp_ = 0, cr_ = 1, sr_ = 0, s_ = 0, c_ = 1;
    long i_ = 0;
};

// One Newmark step to stage displacement u1 at s.t + h; false (with `why`) if it cannot converge.
// `prep` is the law prepared for the condensed return map (law.prepare), used when the law
// has one and the coupling is Condensed.
template <class Law, class Prepared>
inline bool newmarkStep(const NewmarkConstants& K, const Law& law, Prepared* prep, double u1, DynState& s,
                        Coupling coupling, int& newtonIts, int& lawIts, const char*& why, double& badValue) {
    const double h = K.h;
    const double du = u1 - s.u;
    const double b = K.m * (K.i4h2 * (s.x + h * s.v) + s.a) + K.c * (K.i2h * s.x + s.v);
    const double eps = K.eps;
    // Elastic predictor: F = F_n + ε Δg is linear in x.
    double x = (b + s.law.force_N + eps * (du + s.x)) * K.invPredictor;
    ReturnMapResult rm;
    newtonIts = 1;
    bool solved = false;
    if constexpr (HasPreparedReturnMap<Law>) {
        if (coupling == Coupling::Condensed && prep) {
            const double Ftrial = s.law.force_N + eps * (du - (x - s.x));
            rm = prep->returnMapFromTrial(s.law, Ftrial, s.stuck ? 0.0 : s.slipRate * h);
            lawIts += rm.iterations;
            if (!rm.converged) { why = "return mapping did not converge (slip increment)"; badValue = rm.slipIncrement_m; return false; }
            if (!rm.stuck) x += (rm.state.force_N - Ftrial) * K.invKeff;
            solved = true;
        }
    }
    if (!solved) rm = law.returnMap(s.law, du - (x - s.x), h, K.tN);
    if (!solved) lawIts += rm.iterations;
    if (!solved && !rm.stuck) {
        bool ok = false;
        const double xtol = 1e-13 * (std::abs(s.x) + std::abs(du)) + 1e-18;
        for (int it = 0; it < 60; ++it) {
            const double r = K.Keff * x - b - rm.state.force_N;
            const double J = K.Keff + rm.tangent_N_per_m;
            const double dx = r / J;
            x -= dx;
            if (!std::isfinite(x)) { why = "non-finite slider state (x)"; badValue = x; return false; }
            rm = law.returnMap(s.law, du - (x - s.x), h, K.tN);
            lawIts += rm.iterations;
            ++newtonIts;
            if (!rm.converged) { why = "return mapping did not converge (slip increment)"; badValue = rm.slipIncrement_m; return false; }
            if (std::abs(dx) <= xtol) { ok = true; break; }
        }
        if (!ok) { why = "slider Newton iteration did not converge (x)"; badValue = x; return false; }
    }
    const double a1 = K.i4h2 * (x - s.x - h * s.v) - s.a;
    const double v1 = K.i2h * (x - s.x) - s.v;
    if (!std::isfinite(x) || !std::isfinite(v1) || !std::isfinite(a1)) { why = "non-finite slider state (x)"; badValue = x; return false; }
    if (!std::isfinite(rm.state.force_N)) { why = "non-finite friction force (F)"; badValue = rm.state.force_N; return false; }
    if (!std::isfinite(rm.state.alpha)) { why = "non-finite state variable (alpha)"; badValue = rm.state.alpha; return false; }
    s.t += h; s.x = x; s.v = v1; s.a = a1; s.u = u1;
    s.law = rm.state;
    s.slipRate = rm.slipIncrement_m * K.i2h * 0.5;
    s.stuck = rm.stuck;
    return true;
}

// Convenience form of one step (constants recomputed each call; monolithic Newton coupling).
// Time loops should use advance(), which prepares the constants once.
template <class Law>
inline bool newmarkStep(const RigParams& rig, const Law& law, const StageMotion& stage, double h, DynState& s,
                        int& newtonIts, int& lawIts, const char*& why, double& badValue) {
    const NewmarkConstants K(rig, law.epsT(), h);
    const double u1 = stage.displacement(s.t + h);
    // No prepared map (Newton coupling), typed as the law's own so that the main form compiles
    // for laws that have one (for the others any pointer type does).
    if constexpr (HasPreparedReturnMap<Law>) {
        using Prepared = decltype(law.prepare(0.0, 0.0, 0.0));
        return newmarkStep(K, law, static_cast<Prepared*>(nullptr), u1, s, Coupling::Newton, newtonIts, lawIts, why,
                           badValue);
    } else {
        return newmarkStep(K, law, static_cast<int*>(nullptr), u1, s, Coupling::Newton, newtonIts, lawIts, why,
                           badValue);
    }
}

template <class Law, class Obs>
StepReport advanceWith(const DynamicsModel& m, const Law& law, DynState& s, long n, Obs& obs, const RunControl& ctl,
                       long stepOffset) {
    StepReport rep;
    const NewmarkConstants K(m.rig, law.epsT(), m.dt_s);
    StageSequence stage(m.stage, s.t, m.dt_s);
    const double t0 = s.t;
    auto run = [&](auto* prep) {
        const long block = 4096;
        for (long i = 0; i < n; ++i) {
            if ((i % block) == 0 && i > 0 && ctl.cancelled()) {
                rep.status = RunStatus::Cancelled;
                rep.message = "cancelled";
                return;
            }
            int nIts = 0, lIts = 0;
            const char* why = nullptr;
            double bad = 0;
            const double u1 = stage.next();
            if (!newmarkStep(K, law, prep, u1, s, m.coupling, nIts, lIts, why, bad)) {
                rep.status = RunStatus::Failed;
                rep.message = stepFailure(stepOffset + i + 1, s.t + m.dt_s, why, bad);
                return;
            }
            s.t = t0 + static_cast<double>(i + 1) * m.dt_s;  // no drift from repeated addition
            rep.newtonIterations += nIts;
            rep.lawIterations += lIts;
            rep.stuckSteps += s.stuck ? 1 : 0;
            ++rep.stepsDone;
            obs(s);
        }
    };
    if constexpr (HasPreparedReturnMap<Law>) {
        auto prep = law.prepare(K.returnStiffness, K.h, K.tN);
        run(&prep);
    } else {
        run(static_cast<int*>(nullptr));
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

// Once-per-period recording (RunResult::period): the state after every step whose index
// counted from t = 0 (stepsBefore + steps taken in this call) is a multiple of stepsPerPeriod,
// and max |V| over the steps of this call. stepsPerPeriod = 0: none.
struct PeriodRecording {
    long stepsPerPeriod = 0;
    long stepsBefore = 0;
};

// N such that N·dt is the forcing period to 1e-9 of it, or 0 when dt does not divide the period.
long stepsPerPeriodDividing(const SimParams& p);

// A full run as SimParams say: transient cycles discarded, then `cycles` recorded at the
// output interval (with integration.tolerance > 0: by simulateAdaptive, adaptive.hpp); when the step divides the forcing period, also the states at every whole
// period (RunResult::period). Validates the parameters first (Failed with the list of issues).
RunResult simulateDynamics(const SimParams& p, const RunControl& ctl = {});
// The same from a prepared model and state (continuation, fits): runs `steps` steps,
// recording every `outputEvery` steps (and the start state when recordStart).
RunResult simulateDynamics(const DynamicsModel& m, DynState& s, long steps, long outputEvery, bool recordStart,
                           const RunControl& ctl = {}, const PeriodRecording& period = {});

}  // namespace stickslip
