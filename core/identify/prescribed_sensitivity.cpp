#include "prescribed_sensitivity.hpp"

#include <cmath>

#include "../friction/rate_state.hpp"
#include "../friction/slip_newton.hpp"

namespace stickslip::identify {

namespace {

// How parameter j moves the primitive quantities of a step: ε (the law's stiffness), μ, the
// load, wear and direction coefficients, η, D_c, C1, r, C2 = 1/v_c, the effects' own constants
// (τ, b, t_c, D_h, δ) and the sensor's (ζ, m_s). Each parameter moves one or two of them, by
// these factors.
struct Seeds {
    std::vector<double> eps, mu, load, wear, dir, eta, Dc, C1, r, C2, tau, bHeal, tc, Dh, delta, zeta, ms;
    void resize(size_t p) {
        for (auto* v : {&eps, &mu, &load, &wear, &dir, &eta, &Dc, &C1, &r, &C2, &tau, &bHeal, &tc, &Dh, &delta, &zeta, &ms})
            v->assign(p, 0.0);
    }
};

// Seeds of `names` for model m; false with the first name it cannot differentiate by.
bool seedsOf(const ExtendedModel& m, const std::vector<std::string>& names, Seeds& sd, std::string* why) {
    const EffectSet& fx = m.effects;
    sd.resize(names.size());
    const double epsT = m.law.epsT_N_per_m;
    const double kt = fx.preslidingCompliance ? fx.preslidingCompliance->kt_N_per_m : 0.0;
    for (size_t j = 0; j < names.size(); ++j) {
        const std::string& k = names[j];
        bool known = true;
        if (k == "mu") sd.mu[j] = 1;
        else if (k == "eta") sd.eta[j] = 1;
        else if (k == "Dc") sd.Dc[j] = 1;
        else if (k == "C1") sd.C1[j] = 1;
        else if (k == "r") sd.r[j] = 1;
        else if (k == "vc") sd.C2[j] = -1.0 / (m.law.vc_mps * m.law.vc_mps);
        else if (k == "epsT") {
            // ε = ε_T, or ε_T k_t/(ε_T + k_t) in series with presliding_compliance.
            const double f = fx.preslidingCompliance ? kt / (epsT + kt) : 1.0;
            sd.eps[j] = f * f;
        } else if (k == "presliding_compliance.kt_N_per_m" && fx.preslidingCompliance) {
            const double f = epsT / (epsT + kt);
            sd.eps[j] = f * f;
        } else if (k == "normal_load_mu.dmu_dtN_per_N" && fx.normalLoadMu) sd.load[j] = 1;
        else if (k == "wear_drift.dmu_ds_per_m" && fx.wearDrift) sd.wear[j] = 1;
        else if (k == "direction_asymmetry.mu_pos_minus_mu_neg" && fx.directionAsymmetry) sd.dir[j] = 1;
        else if (k == "frictional_lag.tau_s" && fx.frictionalLag) sd.tau[j] = 1;
        else if (k == "stick_healing.b_heal" && fx.stickHealing) sd.bHeal[j] = 1;
        else if (k == "stick_healing.tc_s" && fx.stickHealing) sd.tc[j] = 1;
        else if (k == "stick_healing.Dh_m" && fx.stickHealing) sd.Dh[j] = 1;
        else if (k == "backlash.halfWidth_m" && fx.backlash) sd.delta[j] = 1;
        else if (k == "viscous_damping.zeta" && fx.viscousDamping) sd.zeta[j] = 1;
        else if (k == "sensor_inertia.mass_kg" && fx.sensorInertia) sd.ms[j] = 1;
        else known = false;
        if (!known) {
            if (why) *why = "forward sensitivities: no parameter '" + k + "' in this model";
            return false;
        }
    }
    return true;
}

// ∂ of a state's quantities, one entry per parameter.
using Column = std::vector<double>;

// Carries the derivatives of the run's state along every law step: F, α, the accumulated slip
// s (aux[0]), the contact age θ (aux[1]), the lagged strength Y_act (aux[2]) and the play
// coordinate w (aux[3]). The step's formulas are ExtendedLaw::returnMap's (extended_model.cpp).
class Carrier final : public PrescribedObserver {
public:
    Carrier(const ExtendedModel& m, const RunContext& ctx, const Seeds& sd, size_t n)
        : law_(ExtendedLaw::make(m)), sd_(sd), tN_(ctx.normalForce_N), p_(sd.mu.size()), dF_(p_, 0.0), dA_(p_, 0.0),
          dS_(p_, 0.0), dAge_(p_, 0.0), dY_(p_, 0.0), dW_(p_, 0.0), dFtr_(p_), dx_(p_), dAfx_(p_), dMH_(p_),
          dyLaw_(p_), dy0_(p_), dc1_(p_), dyTrial_(p_),
          dContact(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(p_)) {
        dContact.setZero();
        // The start (ExtendedLaw::initialState): F and α are given, Y_act = t_N μ_eff and, when
        // loaded with a play, w = F/ε ± δ.
        const LawState s0 = law_.initialState(ctx);
        const double f0 = s0.force_N, sg0 = f0 >= 0.0 ? 1.0 : -1.0;
        muAndHealing(s0, sg0, dMH_);
        for (size_t j = 0; j < p_; ++j) dY_[j] = tN_ * dMH_[j];
        if (law_.fx.backlash && std::isfinite(ctx.initialForce_N)) {
            const double eps = law_.eps_N_per_m;
            for (size_t j = 0; j < p_; ++j) dW_[j] = -f0 / (eps * eps) * sd_.eps[j] + sg0 * sd_.delta[j];
        }
    }

    void step(const LawState& st, double dg, double dt, const ReturnMapResult& r,
              const ExtendedLaw::ExpCache& cache) override {
        const EffectSet& fx = law_.fx;
        const RateStateParams& b = law_.base;
        const double eps = law_.eps_N_per_m;
        // The elastic trial: F_n + ε Δg, or ε dz(w_n + Δg) across a play.
        double trial;
        if (fx.backlash) {
            const double wTr = st.aux[3] + dg, dz = fx.backlash->deadZone(wTr);
            trial = eps * dz;
            const bool play = fx.backlash->inPlay(wTr);
            const double sw = wTr > 0.0 ? 1.0 : -1.0;
            for (size_t j = 0; j < p_; ++j) dFtr_[j] = sd_.eps[j] * dz + (play ? 0.0 : eps * (dW_[j] - sw * sd_.delta[j]));
        } else {
            trial = st.force_N + eps * dg;
            for (size_t j = 0; j < p_; ++j) dFtr_[j] = dF_[j] + dg * sd_.eps[j];
        }
        const double a = std::abs(trial), s = trial >= 0.0 ? 1.0 : -1.0;
        // The strength at the step's start: y0 + t_N c1 (e^{α/r} − 1) with, without a lag,
        // y0 = t_N (μ_eff + h) and c1 = C1; with one (FrictionalLag::Hold), y0 = E Y_act +
        // (q − E) Y_law,n + w t_N (μ_eff + h) and c1 = w C1. Only c1 and y0's derivative are
        // needed: the step's Δλ and state come from the run itself.
        const double mh = muAndHealing(st, s, dMH_);
        double c1 = b.C1;
        for (size_t j = 0; j < p_; ++j) dy0_[j] = tN_ * dMH_[j], dc1_[j] = sd_.C1[j];
        if (fx.frictionalLag) {
            const double tau = fx.frictionalLag->tau_s;
            const FrictionalLag::Hold hd = fx.frictionalLag->hold(dt);
            const double e0 = std::exp(st.alpha / b.r);
            const double dEdTau = hd.E * dt / (tau * tau), dqdTau = (1.0 - hd.E) / dt - hd.E / tau;
            const double wLag = hd.w, yLaw = tN_ * (mh + b.C1 * (e0 - 1.0));
            c1 = wLag * b.C1;
            for (size_t j = 0; j < p_; ++j) {
                dyLaw_[j] = tN_ * (dMH_[j] + (e0 - 1.0) * sd_.C1[j] + b.C1 * e0 * (dA_[j] - st.alpha * sd_.r[j] / b.r) / b.r);
                const double dE = dEdTau * sd_.tau[j], dq = dqdTau * sd_.tau[j];
                dy0_[j] = dE * st.aux[2] + hd.E * dY_[j] + (dq - dE) * yLaw + (hd.q - hd.E) * dyLaw_[j] -
                          dq * tN_ * mh + wLag * tN_ * dMH_[j];
                dc1_[j] = -dq * b.C1 + wLag * sd_.C1[j];
                // Y_act of a stuck step: E Y_act + (1 − E) Y_law,n (q + w = 1).
                dyTrial_[j] = dE * (st.aux[2] - yLaw) + hd.E * dY_[j] + (1.0 - hd.E) * dyLaw_[j];
            }
        }
        const double x = r.slipIncrement_m;
        if (x == 0.0) {  // stuck: F = trial, α and s unchanged, θ += Δt, Y_act = its trial value
            dF_.swap(dFtr_);
            if (fx.frictionalLag) dY_.swap(dyTrial_);
            return;
        }
        slipStep(st, r, dt, cache, a, s, c1);
    }

    void sample(size_t i) override {
        for (size_t j = 0; j < p_; ++j) dContact(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) = dF_[j];
    }

private:
    // μ_eff + h at state st for a force of sign s (ExtendedLaw::muEffective, StickHealing::strength)
    // and its derivative into d.
    double muAndHealing(const LawState& st, double s, Column& d) const {
        const EffectSet& fx = law_.fx;
        const double loadArm = tN_ - law_.tNref_N, slip = st.aux[0];
        const double wear = fx.wearDrift ? fx.wearDrift->dmu_ds_per_m : 0.0;
        const double dirSign = s < 0.0 ? -1.0 : 0.0;
        double hb = 0, hAge = 0, hTc = 0;
        if (fx.stickHealing) {  // h = b ln(1 + θ/t_c), θ ≥ 0
            const StickHealing& hl = *fx.stickHealing;
            const double age = std::max(st.aux[1], 0.0);
            hb = std::log1p(age / hl.tc_s);
            hAge = st.aux[1] > 0.0 ? hl.b_heal / (hl.tc_s + age) : 0.0;
            hTc = -hl.b_heal * age / (hl.tc_s * (hl.tc_s + age));
        }
        for (size_t j = 0; j < p_; ++j)
            d[j] = sd_.mu[j] + loadArm * sd_.load[j] + slip * sd_.wear[j] + wear * dS_[j] + dirSign * sd_.dir[j] +
                   hb * sd_.bHeal[j] + hAge * dAge_[j] + hTc * sd_.tc[j];
        return law_.muEffective(st, s, tN_) + (fx.stickHealing ? fx.stickHealing->strength(st.aux[1]) : 0.0);
    }

    // A slipping step: Δλ's derivative from R(Δλ) = a − ε Δλ − y0 − t_N c1 (e^{α/r} − 1) − η t_N Δλ/Δt = 0,
    // then the new state's.
    void slipStep(const LawState& st, const ReturnMapResult& r, double dt, const ExtendedLaw::ExpCache& cache, double a,
                  double s, double c1) {
        const EffectSet& fx = law_.fx;
        const RateStateParams& b = law_.base;
        const double eps = law_.eps_N_per_m, x = r.slipIncrement_m;
        const double a0 = st.alpha, a1 = r.state.alpha, Dc = b.Dc_m, C2 = b.C2();
        // α_{n+1}(Δλ; α_n, C2, D_c) and its partial derivatives (extended_model.hpp, StateStep).
        double aA0, aC2, aDc, ax;
        if (law_.stateStep == StateStep::ConstantRate) {
            const double E = expOrZero(-x / Dc), c = C2 / dt, q = a0 + c * x;
            aA0 = E;
            aC2 = x * (E - 1.0) / dt;
            aDc = q * E * x / (Dc * Dc);
            ax = c * (E - 1.0) - q * E / Dc;
        } else {
            const double den = Dc + x;
            aA0 = Dc / den;
            aC2 = -(x * x / dt) / den;
            aDc = (a0 * x + C2 * x * x / dt) / (den * den);
            ax = (-2.0 * C2 * x / dt - a1) / den;
        }
        for (size_t j = 0; j < p_; ++j) dAfx_[j] = aA0 * dA_[j] + aC2 * sd_.C2[j] + aDc * sd_.Dc[j];
        const double e = cache.alpha == a1 ? cache.e : std::exp(a1 / b.r);
        const double kC1 = tN_ * (e - 1.0), kA = tN_ * c1 * e / b.r, kR = kA * a1 / b.r;
        if (x == a / eps) {  // slid to zero force: Δλ = a/ε
            for (size_t j = 0; j < p_; ++j) dx_[j] = (s * dFtr_[j] - a * sd_.eps[j] / eps) / eps;
        } else {
            const double visc = b.eta_s_per_m * tN_ / dt;
            const double dR = -eps - visc - kA * ax;
            const double kEta = x * tN_ / dt;
            for (size_t j = 0; j < p_; ++j) {
                const double dRdTheta = s * dFtr_[j] - x * sd_.eps[j] - dy0_[j] - kC1 * dc1_[j] - kA * dAfx_[j] +
                                        kR * sd_.r[j] - kEta * sd_.eta[j];
                dx_[j] = -dRdTheta / dR;
            }
        }
        // θ after slip (StickHealing::ageAfterSlip): θ e^{−u} + Δt ρ(u), u = Δλ/D_h, ρ = (1 − e^{−u})/u.
        double gAge = 0, gU = 0, uDx = 0, uDh = 0;
        if (fx.stickHealing) {
            const double Dh = fx.stickHealing->Dh_m, u = x / Dh, E = expOrZero(-u);
            const double rho = u > 1e-12 ? -std::expm1(-u) / u : 1.0;
            const double drho = u > 1e-4 ? (E - rho) / u : -0.5 + u / 3.0;
            gAge = E;
            gU = -st.aux[1] * E + dt * drho;
            uDx = 1.0 / Dh;
            uDh = -x / (Dh * Dh);
        }
        for (size_t j = 0; j < p_; ++j) {
            const double dAlpha = ax * dx_[j] + dAfx_[j];
            dF_[j] = s * (s * dFtr_[j] - x * sd_.eps[j] - eps * dx_[j]);
            dS_[j] += dx_[j];
            if (fx.stickHealing) dAge_[j] = gAge * dAge_[j] + gU * (uDx * dx_[j] + uDh * sd_.Dh[j]);
            if (fx.frictionalLag) dY_[j] = dy0_[j] + kC1 * dc1_[j] + kA * dAlpha - kR * sd_.r[j];
            if (fx.backlash) dW_[j] += -s * dx_[j];
            dA_[j] = dAlpha;
        }
    }

    ExtendedLaw law_;
    const Seeds& sd_;
    double tN_;
    size_t p_;
    Column dF_, dA_, dS_, dAge_, dY_, dW_;          // the state's derivatives
    Column dFtr_, dx_, dAfx_, dMH_, dyLaw_, dy0_, dc1_, dyTrial_;  // one step's scratch

public:
    Eigen::MatrixXd dContact;  // n × p: ∂(contact force at sample i)/∂θ_j
};

}  // namespace

bool sensitivitySupported(const ExtendedModel& m, const std::vector<std::string>& names, std::string* why) {
    Seeds sd;
    return seedsOf(m, names, sd, why);
}

PrescribedSensitivity simulatePrescribedSensitivity(const ExtendedModel& m, const RunContext& ctx,
                                                    const std::vector<double>& t, const std::vector<double>& g,
                                                    const std::vector<double>* accel, int substeps,
                                                    const std::vector<std::string>& names, const RunControl& ctl,
                                                    const std::vector<double>* stepSlip) {
    PrescribedSensitivity out;
    Seeds sd;
    if (!seedsOf(m, names, sd, &out.message)) {
        out.status = RunStatus::Failed;
        return out;
    }
    Carrier carrier(m, ctx, sd, t.size());
    out.trace = simulateExtendedPrescribed(m, ctx, t, g, accel, substeps, ctl, stepSlip, &carrier);
    const ExtendedTrace& tr = out.trace;
    out.status = tr.status;
    out.message = tr.message;
    if (!tr.ok()) return out;
    // measured = F + c_p V + m_s a with c_p = ζ t_N (ViscousDamping::parallelDamping).
    out.dMeasured = std::move(carrier.dContact);
    for (size_t j = 0; j < names.size(); ++j)
        for (size_t i = 0; i < t.size(); ++i)
            out.dMeasured(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) +=
                sd.zeta[j] * ctx.normalForce_N * tr.relVel_mps[i] + sd.ms[j] * tr.sliderAccel_mps2[i];
    return out;
}

}  // namespace stickslip::identify
