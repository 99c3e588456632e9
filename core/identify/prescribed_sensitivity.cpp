#include "prescribed_sensitivity.hpp"

#include <cmath>

#include "../friction/rate_state.hpp"
#include "../friction/slip_newton.hpp"

namespace stickslip::identify {

namespace {

// How parameter j moves the primitive quantities of a step: ε (the law's stiffness), μ, the
// load, wear and direction coefficients, η, D_c, C1, r and C2 = 1/v_c. Each parameter moves one
// or two of them, by these factors.
struct Seeds {
    std::vector<double> eps, mu, load, wear, dir, eta, Dc, C1, r, C2, zeta, ms;
    void resize(size_t p) {
        for (auto* v : {&eps, &mu, &load, &wear, &dir, &eta, &Dc, &C1, &r, &C2, &zeta, &ms}) v->assign(p, 0.0);
    }
};

// Seeds of `names` for model m; false with the first name it cannot differentiate by.
bool seedsOf(const ExtendedModel& m, const std::vector<std::string>& names, Seeds& sd, std::string* why) {
    const EffectSet& fx = m.effects;
    for (const char* e : {"frictional_lag", "stick_healing", "backlash"}) {
        std::vector<double> v;
        if (getEffect(fx, e, v)) {
            if (why) *why = std::string("forward sensitivities do not carry the state of ") + e + " yet";
            return false;
        }
    }
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

// Carries ∂F, ∂α and ∂s (accumulated slip) of the run's state along every law step.
class Carrier final : public PrescribedObserver {
public:
    Carrier(const ExtendedModel& m, const RunContext& ctx, const Seeds& sd, size_t n)
        : law_(ExtendedLaw::make(m)), sd_(sd), tN_(ctx.normalForce_N), p_(sd.mu.size()),
          dF_(p_, 0.0), dA_(p_, 0.0), dS_(p_, 0.0), dFtr_(p_), dx_(p_), dAfx_(p_), dContact(static_cast<Eigen::Index>(n),
                                                                                       static_cast<Eigen::Index>(p_)) {
        dContact.setZero();
    }

    void step(const LawState& st, double dg, double dt, const ReturnMapResult& r,
              const ExtendedLaw::ExpCache& cache) override {
        const double eps = law_.eps_N_per_m;
        for (size_t j = 0; j < p_; ++j) dFtr_[j] = dF_[j] + dg * sd_.eps[j];
        const double x = r.slipIncrement_m;
        if (x == 0.0) {  // stuck: F = F_n + ε Δg, α and s unchanged
            dF_.swap(dFtr_);
            return;
        }
        const RateStateParams& b = law_.base;
        const double trial = st.force_N + eps * dg, a = std::abs(trial), s = trial >= 0.0 ? 1.0 : -1.0;
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
        if (x == a / eps) {  // slid to zero force: Δλ = a/ε
            for (size_t j = 0; j < p_; ++j) dx_[j] = (s * dFtr_[j] - a * sd_.eps[j] / eps) / eps;
        } else {
            // R(Δλ) = a − ε Δλ − t_N μ_eff − t_N C1 (e^{α/r} − 1) − η t_N Δλ/Δt = 0.
            const double e = cache.alpha == a1 ? cache.e : std::exp(a1 / b.r);
            const double visc = b.eta_s_per_m * tN_ / dt;
            const double dR = -eps - visc - tN_ * b.C1 * e * ax / b.r;
            const double loadArm = tN_ - law_.tNref_N, slip = st.aux[0];
            const double wear = law_.fx.wearDrift ? law_.fx.wearDrift->dmu_ds_per_m : 0.0;
            const double dirSign = s < 0.0 ? -1.0 : 0.0;
            const double kC1 = tN_ * (e - 1.0), kA = tN_ * b.C1 * e / b.r, kR = kA * a1 / b.r, kEta = x * tN_ / dt;
            for (size_t j = 0; j < p_; ++j) {
                const double dMu =
                    sd_.mu[j] + loadArm * sd_.load[j] + slip * sd_.wear[j] + wear * dS_[j] + dirSign * sd_.dir[j];
                const double dRdTheta = s * dFtr_[j] - x * sd_.eps[j] - tN_ * dMu - kC1 * sd_.C1[j] - kA * dAfx_[j] +
                                        kR * sd_.r[j] - kEta * sd_.eta[j];
                dx_[j] = -dRdTheta / dR;
            }
        }
        for (size_t j = 0; j < p_; ++j) {
            dF_[j] = s * (s * dFtr_[j] - x * sd_.eps[j] - eps * dx_[j]);
            dA_[j] = ax * dx_[j] + dAfx_[j];
            dS_[j] += dx_[j];
        }
    }

    void sample(size_t i) override {
        for (size_t j = 0; j < p_; ++j) dContact(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) = dF_[j];
    }

private:
    ExtendedLaw law_;
    const Seeds& sd_;
    double tN_;
    size_t p_;
    std::vector<double> dF_, dA_, dS_, dFtr_, dx_, dAfx_;

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
    ExtendedTrace tr = simulateExtendedPrescribed(m, ctx, t, g, accel, substeps, ctl, stepSlip, &carrier);
    out.status = tr.status;
    out.message = tr.message;
    if (!tr.ok()) return out;
    // measured = F + c_p V + m_s a with c_p = ζ t_N (ViscousDamping::parallelDamping).
    out.dMeasured = std::move(carrier.dContact);
    for (size_t j = 0; j < names.size(); ++j)
        for (size_t i = 0; i < t.size(); ++i)
            out.dMeasured(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) +=
                sd.zeta[j] * ctx.normalForce_N * tr.relVel_mps[i] + sd.ms[j] * tr.sliderAccel_mps2[i];
    out.measuredForce_N = std::move(tr.measuredForce_N);
    return out;
}

}  // namespace stickslip::identify
