// The baseline rate-state law (paper Eqs. 1–4) plus any composition of missing effects
// (effects/registry.hpp), simulated in both set-ups: prescribed slip (Fig. 15a) and the
// spring–mass rig (Fig. 15b, Eq. 8, reusing the Newmark stepper of integrate/dynamics.hpp).
#pragma once

#include <limits>
#include <string>
#include <vector>

#include "../friction/law_state.hpp"
#include "../integrate/run_result.hpp"
#include "../integrate/stage_motion.hpp"
#include "../params.hpp"
#include "effects/registry.hpp"

namespace stickslip::identify {

// How a return-map step advances the state α of Eq. 2, dα/dt = −(λ̇/D_c)(α + C2 λ̇), over a
// slip increment Δλ in Δt:
//   BackwardEuler  α₁ (1 + Δλ/D_c) = α₀ − C2 Δλ²/(D_c Δt): the paper's discretisation (and the
//                  app's simulator); first order, its relaxation factor 1/(1 + Δλ/D_c) is far
//                  from e^{−Δλ/D_c} once a step slips more than D_c;
//   ConstantRate   α₁ = −C2 V + (α₀ + C2 V) e^{−Δλ/D_c}, V = Δλ/Δt: exact for a slip rate
//                  constant over the step (as frictional_lag's and stick_healing's updates are).
// Both have the same steady state α = −C2 V (Eq. 5). A fit samples the law at the data's rate
// (1–2 ms steps, where Δλ/D_c reaches 2–5 in fast slip): there BackwardEuler's error in the
// state's transients is taken up by biased C1, η, v_c, D_c and hides or imitates effects.
enum class StateStep { BackwardEuler, ConstantRate };

// A lower bound of α_{n+1} after a slip increment `slip` from α_n = alpha0 under `step`
// (c2PerDt = C2/Δt, invDc = 1/D_c), without an exponential: the backward-Euler value itself;
// for ConstantRate from 1/(1 + Δλ/D_c) ≥ e^{−Δλ/D_c} ≥ max(0, 1 − Δλ/D_c). The return map
// uses it to know, without evaluating, that a step cannot slide to zero force.
double stateLowerBound(StateStep step, double alpha0, double slip, double c2PerDt, double invDc);

// Constant model: baseline law and rig, the effects switched on, and the reference load of
// normal_load_mu.
struct ExtendedModel {
    RateStateParams law;      // μ, η, D_c, C1, r, v_c, ε_T
    RigParams rig;            // dynamics set-up: t_N, k, m*, c (c replaced when viscous_damping is on)
    EffectSet effects;
    double tNref_N = 6.2;     // t_N,ref of normal_load_mu [N]
    StateStep stateStep = StateStep::BackwardEuler;
};

// What differs from run to run of one dataset.
struct RunContext {
    double normalForce_N = 6.2;          // t_N of the run [N]
    double accumulatedSlipStart_m = 0;   // slip already accumulated on the specimen (wear_drift) [m]
    // Force the contact carries at the start [N]; NaN: at rest (F = 0). A measured run cut out
    // of a longer recording starts loaded: its first measured force (identify, both set-ups).
    double initialForce_N = std::numeric_limits<double>::quiet_NaN();
};

// An effect-aware friction law with the same concept as RateStateLaw (returnMap, epsT), so it
// runs in detail::newmarkStep. LawState::aux holds:
//   aux[0] accumulated slip s [m] (wear_drift), aux[1] contact age θ [s]
//   (stick_healing), aux[2] lagged strength Y_act [N] (frictional_lag), aux[3] elastic+play
//   coordinate w = g − λ [m] (backlash).
struct ExtendedLaw {
    RateStateParams base;
    EffectSet fx;
    double tNref_N = 6.2;
    double eps_N_per_m = 1e6;  // ε_T, or ε_T in series with presliding_compliance
    StateStep stateStep = StateStep::BackwardEuler;

    static ExtendedLaw make(const ExtendedModel& m);

    // Per-loop scratch (one per time loop, never shared between threads): the step constants
    // of the last (Δt, t_N) and exp(α/r) of the last stuck state. A stuck step leaves α
    // unchanged, so a run of stuck steps evaluates the exponential once.
    struct ExpCache {
        double alpha = std::numeric_limits<double>::quiet_NaN();
        double e = 1.0;
        double dt = std::numeric_limits<double>::quiet_NaN(), tN = std::numeric_limits<double>::quiet_NaN();
        double visc = 0, invDc = 0, c2q = 0, invR = 0, c2dt = 0;
    };
    // Return mapping over one step: backward Euler in the flow, the state α per stateStep
    // (derivation in extended_model.cpp).
    ReturnMapResult returnMap(const LawState& s, double dg_m, double dt_s, double normalForce_N) const {
        return returnMap(s, dg_m, dt_s, normalForce_N, nullptr);
    }
    ReturnMapResult returnMap(const LawState& s, double dg_m, double dt_s, double normalForce_N, ExpCache* cache) const;
    double epsT() const { return eps_N_per_m; }
    double K1(double alpha) const;  // Eq. 1
    // μ with the load-, wear- and direction-dependent shifts for a force of sign `forceSign`.
    double muEffective(const LawState& s, double forceSign, double normalForce_N) const;
    // The law's strength Y = t_N (μ_eff + h(θ) + K1(α)) in state s (before any lag): the
    // force the contact carries in quasi-static sliding. returnMap forms the same sum with its
    // cached exponential.
    double lawStrength(const LawState& s, double forceSign, double normalForce_N) const;
    // Contact at rest at the start of a run: F = 0, α = 0, strength at its law value. With
    // ctx.initialForce_N: that force, with the lagged strength and the play to match. α stays 0:
    // it is not measured, and a sliding state inferred from the signs of F and V is wrong for a
    // run that starts from rest (seen: a false frictional_lag on such runs); its transient lasts
    // D_c of slip.
    LawState initialState(const RunContext& ctx) const;
};

// Time series of a simulated run: the contact force and the force a sensor would measure
// (contact force + parallel dashpot + sensor inertia).
struct ExtendedTrace {
    RunStatus status = RunStatus::Ok;
    std::string message;
    std::vector<double> t_s, stage_m, slider_m, sliderVel_mps, sliderAccel_mps2;
    std::vector<double> slip_m, relVel_mps;
    std::vector<double> contactForce_N, measuredForce_N;
    std::vector<char> stuck;
    double accumulatedSlipEnd_m = 0;
    bool ok() const { return status == RunStatus::Ok; }
};

// Prescribed slip g(t) at the samples t (strictly increasing), `substeps` law steps per
// interval (g linear in between). V for the dashpot is the central difference of g; the
// sensed acceleration is `accel` when given (same length), else the second difference of g.
// `stepSlip_m`, when given ((n − 1)·substeps values), is the slip at the end of every law step
// (step k of interval i at index (i − 1)·substeps + k − 1, the last of each interval equal to
// slip_m[i]): the input between samples taken from a finer record instead of the line.
// `observer`, when given, sees every law step and every recorded sample of the run (what the
// forward sensitivities of prescribed_sensitivity.hpp are carried along).
struct PrescribedObserver {
    virtual ~PrescribedObserver() = default;
    // One return map from `before` over a slip increment dg in dt; `cache` is the loop's, just
    // after the step (it holds exp(α/r) of the new state when the step slipped).
    virtual void step(const LawState& before, double dg_m, double dt_s, const ReturnMapResult& r,
                      const ExtendedLaw::ExpCache& cache) = 0;
    // The contact force of sample i is recorded (the state after the steps of interval i).
    virtual void sample(size_t i) = 0;
};
ExtendedTrace simulateExtendedPrescribed(const ExtendedModel& m, const RunContext& ctx, const std::vector<double>& t_s,
                                         const std::vector<double>& slip_m, const std::vector<double>* accel_mps2,
                                         int substeps, const RunControl& ctl = {},
                                         const std::vector<double>* stepSlip_m = nullptr,
                                         PrescribedObserver* observer = nullptr);

// Spring–mass rig driven by `stage` from rest at t0 with step dt_s; records every
// `outputEvery` steps (the start state included). The contact's t_N is ctx.normalForce_N.
ExtendedTrace simulateExtendedDynamics(const ExtendedModel& m, const RunContext& ctx, const StageMotion& stage,
                                       double t0_s, double dt_s, long steps, long outputEvery,
                                       const RunControl& ctl = {});

// Rigid-contact limit (ε_T → ∞) of the extended law along a measured slip velocity V(t):
// while |V| ≥ vStick the contact slides and
//   F = sign V [Y_act + η t_N |V|] + m_s a,   Y = t_N (μ_eff + h + K1(α)),
// with α updated exactly at constant |V| over each interval (Eq. 2 at λ̇ = |V|):
//   α_{n+1} = −C2|V| + (α_n + C2|V|) exp(−|V| Δt/D_c),
// contact age θ renewed over D_h, accumulated slip s += |V|Δt, Y_act lagged (first-order
// hold of Y_law between samples); while
// |V| < vStick the contact sticks (α frozen, h heals, Y_act follows), the force is set by the
// rig and not predicted (`sliding` = 0). backlash and presliding_compliance act inside stick
// and have no effect here. viscous_damping is a rig effect (not in this force).
struct SlipPhasePrediction {
    std::vector<double> force_N;   // predicted measured force (0 where stuck)
    std::vector<char> sliding;     // 1 where the prediction applies
    double accumulatedSlipEnd_m = 0;
};
SlipPhasePrediction simulateSlipPhaseForce(const ExtendedModel& m, const RunContext& ctx, const std::vector<double>& t_s,
                                           const std::vector<double>& relVel_mps, const std::vector<double>* accel_mps2,
                                           double vStick_mps);

}  // namespace stickslip::identify
