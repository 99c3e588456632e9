#include "extended_model.hpp"

#include <algorithm>
#include <cmath>

#include "../friction/slip_first_root.hpp"
#include "../friction/slip_newton.hpp"
#include "../integrate/dynamics.hpp"

namespace stickslip::identify {

ExtendedLaw ExtendedLaw::make(const ExtendedModel& m) {
    ExtendedLaw l;
    l.base = m.law;
    l.fx = m.effects;
    l.tNref_N = m.tNref_N;
    l.stateStep = m.stateStep;
    l.eps_N_per_m = m.effects.preslidingCompliance ? m.effects.preslidingCompliance->effectiveStiffness(m.law.epsT_N_per_m)
                                                   : m.law.epsT_N_per_m;
    return l;
}

double ExtendedLaw::K1(double alpha) const { return base.C1 * (std::exp(alpha / base.r) - 1.0); }

double ExtendedLaw::muEffective(const LawState& s, double forceSign, double tN) const {
    double mu = base.mu;
    if (fx.normalLoadMu) mu += fx.normalLoadMu->muShift(tN, tNref_N);
    if (fx.wearDrift) mu += fx.wearDrift->muShift(s.aux[0]);
    if (fx.directionAsymmetry) mu += fx.directionAsymmetry->muShift(forceSign);
    return mu;
}

double ExtendedLaw::lawStrength(const LawState& s, double forceSign, double tN) const {
    const double h = fx.stickHealing ? fx.stickHealing->strength(s.aux[1]) : 0.0;  // aux[1]: contact age θ
    return tN * (muEffective(s, forceSign, tN) + h + K1(s.alpha));
}

LawState ExtendedLaw::initialState(const RunContext& ctx) const {
    LawState s;
    s.aux[0] = ctx.accumulatedSlipStart_m;
    const bool loaded = std::isfinite(ctx.initialForce_N);
    if (loaded) s.force_N = ctx.initialForce_N;
    s.aux[2] = ctx.normalForce_N * muEffective(s, s.force_N >= 0 ? 1.0 : -1.0, ctx.normalForce_N);
    if (loaded && fx.backlash) s.aux[3] = fx.backlash->loadedCoordinate(s.force_N, eps_N_per_m);
    return s;
}

// Return mapping with effects. As for the bare law (see friction/rate_state.cpp):
//   trial  F_tr = F_n + ε Δg  (backlash: w_tr = w_n + Δg, F_tr = ε dz(w_tr)),  a = |F_tr|,
//   strength Y(α) = t_N (μ_eff + h + K1(α)),  μ_eff = μ + load, wear and direction shifts
//   (held at their start-of-step values), h the healed strength (stick_healing),
//   Φ_tr = a − Y(α_n); stick if Φ_tr ≤ 0. Otherwise Δλ > 0 solves
//   R(Δλ) = a − ε Δλ − Y(α_{n+1}(Δλ)) − η t_N Δλ/Δt = 0,
//   α_{n+1} = (α_n − C2 Δλ²/(D_c Δt)) / (1 + Δλ/D_c)                        (2), BE
//   or, StateStep::ConstantRate, α_{n+1} = −C2 V + (α_n + C2 V) e^{−Δλ/D_c}, V = Δλ/Δt,
// bracketed by [0, a/ε] and solved by the rate-state law's own safeguarded Newton (solveSlip,
// friction/slip_newton.hpp).
// frictional_lag: the strength is the lagged Y_act, updated exactly over the step with Y_law
// linear in time (FrictionalLag::hold): Y_act,n+1 = Y_b + w Y_law(α_{n+1}), Y_b = E Y_act,n +
// (q − E) Y_law,n. In R this is the law's own equation with t_N(μ_eff + h) → Y_b + w t_N(μ_eff + h)
// and C1 → w C1, solved by the same Newton iteration; τ → 0 (w → 1, E → 0) is the law without
// lag (tst_effects::frictionalLagVanishesAsTauGoesToZero). The consistent tangent is
// dF/dΔg = ε (1 + ε/R') with R' = dR/dΔλ < 0 (0 inside the backlash play).
namespace {

// What a slipping step needs of the trial state (ExtendedLaw::returnMap).
struct SlipStart {
    double a = 0, s = 1;          // |F_tr| and its sign
    double e0 = 1;                // exp(α_n/r)
    double yBase = 0, w = 1;      // strength = yBase + w Y_law(α) (frictional_lag; bare: 0, 1)
    double muPlusH = 0;           // μ_eff + h at the step's start
    double phiTrial = 0, wTrial = 0;
};

// exp(α_n/r), exactly as K1 computes it, from the cache when α_n is the cached state's.
double startExp(const ExtendedLaw& law, double alpha, ExtendedLaw::ExpCache* cache) {
    if (cache && alpha == cache->alpha) return cache->e;
    const double e0 = std::exp(alpha / law.base.r);
    if (cache) cache->alpha = alpha, cache->e = e0;
    return e0;
}

// Φ_tr ≤ 0: the elastic step, α unchanged; the contact ages and the lagged strength holds.
ReturnMapResult stickStep(const ExtendedLaw& law, const LawState& st, double trial, double wTrial, double yTrial,
                          double dt) {
    const EffectSet& fx = law.fx;
    ReturnMapResult res;
    res.state = st;
    res.state.force_N = trial;
    if (fx.backlash) res.state.aux[3] = wTrial;
    if (fx.stickHealing) res.state.aux[1] = fx.stickHealing->ageWhileStuck(st.aux[1], dt);
    if (fx.frictionalLag) res.state.aux[2] = yTrial;
    res.tangent_N_per_m = (fx.backlash && fx.backlash->inPlay(wTrial)) ? 0.0 : law.eps_N_per_m;
    // Inside or at the edge of the play F is not F_n + ε Δg: report "not stuck" so that
    // the Newmark step iterates with this force and tangent instead of its elastic predictor.
    res.stuck = !(fx.backlash && (fx.backlash->inPlay(wTrial) || fx.backlash->inPlay(st.aux[3])));
    return res;
}

// Φ_tr > 0: Δλ from R(Δλ) = 0 (derivation above ExtendedLaw::returnMap), then the state.
ReturnMapResult slipStep(const ExtendedLaw& law, const LawState& st, const SlipStart& in, double dt, double tN,
                         ExtendedLaw::ExpCache* cache) {
    const RateStateParams& base = law.base;
    const EffectSet& fx = law.fx;
    ReturnMapResult res;
    res.state = st;
    res.stuck = false;
    const double eps = law.eps_N_per_m, a = in.a, s = in.s, e0 = in.e0;
    ExtendedLaw::ExpCache local;
    ExtendedLaw::ExpCache& k = cache ? *cache : local;
    if (!(k.dt == dt && k.tN == tN)) {
        k.dt = dt;
        k.tN = tN;
        k.visc = base.eta_s_per_m * tN / dt;  // η t_N/Δt [N/m]
        k.invDc = 1.0 / base.Dc_m;
        k.c2q = base.C2() * k.invDc / dt;
        k.invR = 1.0 / base.r;
        k.c2dt = base.C2() / dt;
    }
    const double visc = k.visc, invDc = k.invDc, c2q = k.c2q, invR = k.invR, c2dt = k.c2dt;
    const bool constantRate = law.stateStep == StateStep::ConstantRate;
    auto alphaAt = [&](double x, double& dalpha) {
        if (constantRate) {  // α₁ = −C2 V + (α₀ + C2 V) e^{−Δλ/D_c}, V = Δλ/Δt (StateStep)
            const double E = expOrZero(-x * invDc), ss = c2dt * x, excess = (st.alpha + ss) * E;
            dalpha = c2dt * (E - 1.0) - excess * invDc;
            return excess - ss;
        }
        const double den = 1.0 + x * invDc;
        const double al = (st.alpha - c2q * x * x) / den;
        dalpha = (-2.0 * c2q * x - al * invDc) / den;
        return al;
    };
    double x = 0.0, alpha = st.alpha, dR = -(eps + visc);
    const double hi0 = a / eps;  // the force cannot change sign in a step
    const double y0 = in.yBase + in.w * tN * in.muPlusH, c1 = in.w * base.C1;
    double eAlpha = e0;  // exp(α/r) at the last evaluated α: the next step's exp(α_n/r)
    auto eval = [&](double xx, double& R, double& dRx, double& al) {
        double da = 0;
        al = alphaAt(xx, da);
        const double e = std::exp(al / base.r);  // as e0 forms it, so the cache below holds exactly e0
        eAlpha = e;
        R = a - eps * xx - y0 - tN * c1 * (e - 1.0) - visc * xx;
        dRx = -eps - visc - tN * c1 * invR * e * da;
    };
    double hi = hi0, R = -1.0;
    // R(Δλ) <= a - y0 + t_N c1 - (ε + η t_N/Δt) Δλ since K1 >= -C1: when that bound puts the
    // root below a/ε, R(a/ε) < 0 and the force cannot reach zero in the step (no evaluation).
    const double rootBound = (a - y0 + tN * c1) / (eps + visc);
    // Else R(a/ε) < 0 is usually still certain from a lower bound of α(a/ε), which needs no
    // exponential (slip_newton.hpp).
    if (!(c1 >= 0.0 && rootBound * (1.0 + 1e-9) < hi0) &&
        !slipResidualCertainlyNegative(a, (eps + visc) * hi, y0, tN * c1,
                                       stateLowerBound(law.stateStep, st.alpha, hi, c2dt, invDc) * invR))
        eval(hi, R, dR, alpha);
    if (R > 0.0) {  // slides to zero force within the step
        x = hi;
    } else {
        // The rate-state law's own solve, from the elastic–viscous predictor Φ_trial/(ε + η t_N/Δt)
        // (as a warm start; from Δλ = 0, where R = Φ_trial and dα/dΔλ = −α_n/D_c in both state
        // steps, when the predictor is beyond the bracket).
        // R may have three roots; the step takes the first (slip_first_root.hpp).
        const double phiTrial = in.phiTrial;
        const double dR0 = -(eps + visc) + tN * c1 * invR * e0 * st.alpha * invDc;
        const SlipShape shape{constantRate, st.alpha, c2dt, invDc, invR, tN * c1 * invR, eps + visc};
        auto evalR = [&](double xx, double& Rx, double& dRx) { eval(xx, Rx, dRx, alpha); };
        const double ftol = 1e-12 * (a + tN);
        const SlipRoot root = solveSlipFirstRoot(evalR, shape, e0, phiTrial, dR0, hi, phiTrial / (eps + visc), ftol);
        x = root.x;
        dR = root.dR;
        res.iterations = root.iterations;
        res.converged = root.converged;
    }
    // α_{n+1} is the next step's α_n: hand its exponential on instead of recomputing it.
    if (cache) cache->alpha = alpha, cache->e = eAlpha;
    res.slipIncrement_m = x;
    res.state.force_N = s * (a - eps * x);
    res.state.alpha = alpha;
    res.state.aux[0] = st.aux[0] + x;
    if (fx.stickHealing) res.state.aux[1] = fx.stickHealing->ageAfterSlip(st.aux[1], x, dt);
    if (fx.frictionalLag) res.state.aux[2] = y0 + tN * c1 * (eAlpha - 1.0);
    if (fx.backlash) res.state.aux[3] = in.wTrial - s * x;
    res.tangent_N_per_m = (dR < 0.0) ? eps * (1.0 + eps / dR) : 0.0;
    return res;
}

}  // namespace

double stateLowerBound(StateStep step, double alpha0, double slip, double c2PerDt, double invDc) {
    if (step == StateStep::BackwardEuler) return (alpha0 - c2PerDt * invDc * slip * slip) / (1.0 + slip * invDc);
    // α = q e^{−y} − C2 Δλ/Δt with q = α_n + C2 Δλ/Δt, y = Δλ/D_c, and
    // 1/(1 + y) ≥ e^{−y} ≥ max(0, 1 − y) (from e^y ≥ 1 + y), the side that bounds q e^{−y} below.
    const double q = alpha0 + c2PerDt * slip, y = slip * invDc;
    return (q >= 0.0 ? q * std::max(0.0, 1.0 - y) : q / (1.0 + y)) - c2PerDt * slip;
}

ReturnMapResult ExtendedLaw::returnMap(const LawState& st, double dg, double dt, double tN, ExpCache* cache) const {
    SlipStart in;
    double trial = 0.0;
    if (fx.backlash) {
        in.wTrial = st.aux[3] + dg;
        trial = eps_N_per_m * fx.backlash->deadZone(in.wTrial);
    } else {
        trial = st.force_N + eps_N_per_m * dg;
    }
    in.a = std::abs(trial);
    in.s = trial >= 0.0 ? 1.0 : -1.0;
    const double mu = muEffective(st, in.s, tN);
    const double h = fx.stickHealing ? fx.stickHealing->strength(st.aux[1]) : 0.0;  // aux[1]: contact age θ
    in.muPlusH = mu + h;
    in.e0 = startExp(*this, st.alpha, cache);
    const double yLaw = tN * (mu + h + base.C1 * (in.e0 - 1.0));
    if (fx.frictionalLag) {
        const FrictionalLag::Hold hd = fx.frictionalLag->hold(dt);
        in.yBase = hd.E * st.aux[2] + (hd.q - hd.E) * yLaw;
        in.w = hd.w;
    }
    const double yTrial = in.yBase + in.w * yLaw;  // α unchanged in a stick step
    in.phiTrial = in.a - yTrial;
    if (in.phiTrial <= 0.0) return stickStep(*this, st, trial, in.wTrial, yTrial, dt);
    return slipStep(*this, st, in, dt, tN, cache);
}

namespace {

// Central difference of y over t (one-sided at the ends).
std::vector<double> derivative(const std::vector<double>& t, const std::vector<double>& y) {
    const size_t n = y.size();
    std::vector<double> d(n, 0.0);
    if (n < 2) return d;
    d[0] = (y[1] - y[0]) / (t[1] - t[0]);
    d[n - 1] = (y[n - 1] - y[n - 2]) / (t[n - 1] - t[n - 2]);
    for (size_t i = 1; i + 1 < n; ++i) d[i] = (y[i + 1] - y[i - 1]) / (t[i + 1] - t[i - 1]);
    return d;
}

}  // namespace

ExtendedTrace simulateExtendedPrescribed(const ExtendedModel& m, const RunContext& ctx, const std::vector<double>& t,
                                         const std::vector<double>& g, const std::vector<double>* accel, int substeps,
                                         const RunControl& ctl, const std::vector<double>* stepSlip,
                                         PrescribedObserver* observer) {
    ExtendedTrace tr;
    const size_t n = t.size();
    if (n < 2 || g.size() != n || (accel && accel->size() != n) || substeps < 1 ||
        (stepSlip && stepSlip->size() != (n - 1) * static_cast<size_t>(substeps))) {
        tr.status = RunStatus::Failed;
        tr.message = "prescribed history: need >= 2 samples, equal lengths, substeps >= 1 and (n - 1) x substeps step slips";
        return tr;
    }
    const ExtendedLaw law = ExtendedLaw::make(m);
    const double tN = ctx.normalForce_N;
    LawState s = law.initialState(ctx);
    ExtendedLaw::ExpCache cache;
    tr.t_s = t;
    tr.slip_m = g;
    tr.relVel_mps = derivative(t, g);
    const std::vector<double> a = accel ? *accel : derivative(t, tr.relVel_mps);
    tr.sliderAccel_mps2 = a;
    tr.contactForce_N.assign(n, 0.0);
    tr.measuredForce_N.assign(n, 0.0);
    tr.stuck.assign(n, 1);
    const double cp = m.effects.viscousDamping ? m.effects.viscousDamping->parallelDamping(tN) : 0.0;
    const double ms = m.effects.sensorInertia ? m.effects.sensorInertia->mass_kg : 0.0;
    for (size_t i = 0; i < n; ++i) {
        if (i > 0) {
            const double dt = (t[i] - t[i - 1]) / substeps;
            const double dg = (g[i] - g[i - 1]) / substeps;
            if (!(dt > 0.0)) {
                tr.status = RunStatus::Failed;
                tr.message = "prescribed history: time not increasing at sample " + std::to_string(i);
                return tr;
            }
            bool stuck = true;
            const double* gs = stepSlip ? stepSlip->data() + (i - 1) * static_cast<size_t>(substeps) : nullptr;
            for (int k = 0; k < substeps; ++k) {
                const double dgk = gs ? gs[k] - (k > 0 ? gs[k - 1] : g[i - 1]) : dg;
                const ReturnMapResult r = law.returnMap(s, dgk, dt, tN, &cache);
                if (!r.converged || !std::isfinite(r.state.force_N)) {
                    tr.status = RunStatus::Failed;
                    tr.message = "return mapping failed at t = " + std::to_string(t[i]) + " s";
                    return tr;
                }
                if (observer) observer->step(s, dgk, dt, r, cache);
                s = r.state;
                stuck = stuck && r.slipIncrement_m == 0.0;
            }
            tr.stuck[i] = stuck ? 1 : 0;
            if ((i & 4095) == 0 && ctl.cancelled()) {
                tr.status = RunStatus::Cancelled;
                tr.message = "cancelled";
                return tr;
            }
        }
        tr.contactForce_N[i] = s.force_N;
        if (observer) observer->sample(i);
        tr.measuredForce_N[i] = s.force_N + cp * tr.relVel_mps[i] + ms * a[i];
    }
    tr.accumulatedSlipEnd_m = s.aux[0];
    return tr;
}

ExtendedTrace simulateExtendedDynamics(const ExtendedModel& m, const RunContext& ctx, const StageMotion& stage,
                                       double t0, double dt, long steps, long outputEvery, const RunControl& ctl) {
    ExtendedTrace tr;
    if (!(dt > 0.0) || steps < 1 || outputEvery < 1) {
        tr.status = RunStatus::Failed;
        tr.message = "dynamics: need dt > 0, steps >= 1, outputEvery >= 1";
        return tr;
    }
    const ExtendedLaw law = ExtendedLaw::make(m);
    RigParams rig = m.rig;
    rig.normalForce_N = ctx.normalForce_N;
    if (m.effects.viscousDamping) rig.damping_Ns_per_m = m.effects.viscousDamping->rigDamping(rig.stiffness_N_per_m, rig.mass_kg);
    const double ms = m.effects.sensorInertia ? m.effects.sensorInertia->mass_kg : 0.0;
    DynState s;
    s.t = t0;
    s.u = stage.displacement(t0);
    s.law = law.initialState(ctx);
    if (m.effects.backlash) s.law.aux[3] = 0.0;
    auto record = [&](const DynState& d) {
        tr.t_s.push_back(d.t);
        tr.stage_m.push_back(d.u);
        tr.slider_m.push_back(d.x);
        tr.sliderVel_mps.push_back(d.v);
        tr.sliderAccel_mps2.push_back(d.a);
        tr.slip_m.push_back(d.u - d.x);
        tr.relVel_mps.push_back(stage.velocity(d.t) - d.v);
        tr.contactForce_N.push_back(d.law.force_N);
        tr.measuredForce_N.push_back(d.law.force_N + ms * d.a);
        tr.stuck.push_back(d.stuck ? 1 : 0);
    };
    record(s);
    for (long i = 1; i <= steps; ++i) {
        int nIts = 0, lIts = 0;
        const char* why = nullptr;
        double bad = 0.0;
        if (!stickslip::detail::newmarkStep(rig, law, stage, dt, s, nIts, lIts, why, bad)) {
            tr.status = RunStatus::Failed;
            tr.message = stickslip::detail::stepFailure(i, s.t + dt, why, bad);
            return tr;
        }
        if (i % outputEvery == 0) record(s);
        if ((i & 4095) == 0 && ctl.cancelled()) {
            tr.status = RunStatus::Cancelled;
            tr.message = "cancelled";
            return tr;
        }
    }
    tr.accumulatedSlipEnd_m = s.law.aux[0];
    return tr;
}

SlipPhasePrediction simulateSlipPhaseForce(const ExtendedModel& m, const RunContext& ctx, const std::vector<double>& t,
                                           const std::vector<double>& V, const std::vector<double>* accel, double vStick) {
    SlipPhasePrediction out;
    const size_t n = std::min(t.size(), V.size());
    out.force_N.assign(n, 0.0);
    out.sliding.assign(n, 0);
    const ExtendedLaw law = ExtendedLaw::make(m);
    const EffectSet& fx = m.effects;
    const double tN = ctx.normalForce_N;
    const double ms = fx.sensorInertia ? fx.sensorInertia->mass_kg : 0.0;
    const bool haveAcc = accel && accel->size() >= n;
    const double C2 = m.law.C2(), Dc = m.law.Dc_m;
    LawState s = law.initialState(ctx);
    double yLawPrev = 0.0;  // Y_law at the previous sample (the lag's first-order hold)
    for (size_t i = 0; i < n; ++i) {
        const double dt = i > 0 ? t[i] - t[i - 1] : 0.0;
        const double v = std::abs(V[i]);
        const double sg = V[i] >= 0 ? 1.0 : -1.0;
        const bool slide = v >= vStick;
        const double mu = law.muEffective(s, sg, tN);
        if (dt > 0) {
            if (slide) {
                const double decay = std::exp(-v * dt / Dc);
                s.alpha = -C2 * v + (s.alpha + C2 * v) * decay;
                if (fx.stickHealing) s.aux[1] = fx.stickHealing->ageAfterSlip(s.aux[1], v * dt, dt);
                s.aux[0] += v * dt;
            } else if (fx.stickHealing) {
                s.aux[1] = fx.stickHealing->ageWhileStuck(s.aux[1], dt);
            }
        }
        const double h = fx.stickHealing ? fx.stickHealing->strength(s.aux[1]) : 0.0;
        const double yLaw = tN * (mu + h + law.K1(s.alpha));  // μ_eff at the interval's start, as returnMap holds it
        if (fx.frictionalLag && dt > 0) s.aux[2] = fx.frictionalLag->lagged(s.aux[2], yLawPrev, yLaw, dt);
        yLawPrev = yLaw;
        const double y = fx.frictionalLag ? s.aux[2] : yLaw;
        if (slide) {
            out.sliding[i] = 1;
            out.force_N[i] = sg * (y + m.law.eta_s_per_m * tN * v) + (haveAcc ? ms * (*accel)[i] : 0.0);
        }
    }
    out.accumulatedSlipEnd_m = s.aux[0];
    return out;
}

}  // namespace stickslip::identify
