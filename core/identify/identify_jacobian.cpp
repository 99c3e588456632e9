// The residuals' Jacobian from forward sensitivities (IdentifyOptions::analyticJacobian): the law
// channel's columns carried through the return map along each run (prescribed_sensitivity.hpp)
// and filtered as its residual is; the equation-of-motion channel's in closed form.
#include <algorithm>
#include <cmath>

#include "identify_internal.hpp"
#include "prescribed_sensitivity.hpp"

namespace stickslip::identify::detail {

namespace {

// How a parameter enters one run's residuals.
enum class Enters { Law, Mass, RigDamping, Nowhere };

// Rows [off, off + channels·n) of r and J for run p; false when the run fails or a name is
// covered by neither channel.
bool runJacobian(const Context& cx, const Spec& spec, const Prepared& p, const ExtendedModel& m, double mass,
                 const std::vector<std::string>& names, size_t off, std::vector<double>* r, Eigen::MatrixXd& J) {
    const IdentifyRun& run = *p.run;
    const size_t n = p.size();
    const bool dyn = run.setup == SetupKind::Dynamics;
    const bool viscousEffect = std::find(spec.effects.begin(), spec.effects.end(), "viscous_damping") != spec.effects.end();
    // buildModel: the rig's "zeta" is the model's viscous damping unless the effect is on.
    std::vector<Enters> how(names.size(), Enters::Law);
    std::vector<std::string> lawNames;
    std::vector<Eigen::Index> lawCols;
    for (size_t j = 0; j < names.size(); ++j) {
        const std::string& k = names[j];
        const bool rigZeta = (k == "zeta" && !viscousEffect) || (k == "viscous_damping.zeta" && viscousEffect);
        if (k == "m") how[j] = dyn ? Enters::Mass : Enters::Nowhere;
        else if (k == "zeta" && viscousEffect) how[j] = Enters::Nowhere;
        else if (rigZeta && dyn) how[j] = Enters::RigDamping;
        else {
            // Prescribed: the model's viscous damping is the sensor's parallel dashpot.
            lawNames.push_back(rigZeta ? "viscous_damping.zeta" : k);
            lawCols.push_back(static_cast<Eigen::Index>(j));
        }
    }
    LawRun law;
    Eigen::MatrixXd dM;
    if (!simulateLawRunSensitivity(cx, p, m, lawNames, law, dM)) return false;
    if (r) {
        std::vector<double> rr;
        double ss = 0, count = 0;
        if (!runResiduals(cx, p, m, mass, rr, ss, count, nullptr, nullptr, nullptr, false, &law)) return false;
        if (rr.size() != (dyn ? 2 : 1) * n) return false;
        std::copy(rr.begin(), rr.end(), r->begin() + static_cast<long>(off));
    }
    const Eigen::Index o = static_cast<Eigen::Index>(off);
    // The equation of motion ((m + m_s) a + c ẋ + k x, c = 2 ζ √(k m)): its derivative per column.
    const double mm = std::isfinite(mass) ? mass : run.nominalMass_kg;
    const double zeta = m.effects.viscousDamping ? m.effects.viscousDamping->zeta : cx.opt->zetaNominal;
    const double k = run.stiffness_N_per_m;
    auto rigDerivative = [&](size_t j, size_t i) {
        if (!dyn) return 0.0;
        if (how[j] == Enters::Mass) return p.a[i] + zeta * std::sqrt(k / mm) * p.xd[i];
        if (how[j] == Enters::RigDamping) return 2.0 * std::sqrt(k * mm) * p.xd[i];
        if (names[j] == "sensor_inertia.mass_kg") return p.a[i];
        return 0.0;
    };
    // The law channel: (filtered(measured) − F)/rms, filtered(y) = F + filter(mask·(y − F)) or,
    // with stickRigPrediction, filter(mask·y + (1 − mask)·rig) (Prepared::filtered): affine in y
    // and rig, so its derivative is the filtered derivative of what the mask picks.
    const bool rigInStick = dyn && cx.opt->stickRigPrediction;
    std::vector<Eigen::Index> lawColOf(names.size(), -1);
    for (size_t c = 0; c < lawCols.size(); ++c) lawColOf[static_cast<size_t>(lawCols[c])] = static_cast<Eigen::Index>(c);
    std::vector<double> d(n);
    for (size_t j = 0; j < names.size(); ++j) {
        const Eigen::Index lc = lawColOf[j];
        if (lc < 0 && !rigInStick) continue;
        for (size_t i = 0; i < n; ++i) {
            if (!dyn || p.slides[i]) d[i] = lc >= 0 ? dM(static_cast<Eigen::Index>(i), lc) : 0.0;
            else d[i] = rigInStick ? rigDerivative(j, i) : 0.0;
        }
        if (!p.predictionFilter.empty()) d = dsp::filtfiltZeroExtended(p.predictionFilter, d);
        for (size_t i = 0; i < n; ++i)
            J(o + static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) = (!dyn || p.compared[i]) ? d[i] * p.invRmsF : 0.0;
    }
    if (!dyn) return true;
    const Eigen::Index e = o + static_cast<Eigen::Index>(n);
    for (size_t j = 0; j < names.size(); ++j)
        for (size_t i = 0; i < n; ++i)
            J(e + static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) = rigDerivative(j, i) * p.invRmsF;
    return true;
}

}  // namespace

bool analyticResidualJacobian(const Context& cx, const Spec& spec, const std::map<std::string, double>& vals,
                              const std::vector<size_t>& idx, const std::vector<std::string>& names, Eigen::MatrixXd& J,
                              std::vector<double>* r) {
    if (spec.segments) return false;
    double mass = kNaN;
    const ExtendedModel m = buildModel(cx, spec, vals, mass);
    std::vector<size_t> offsets;
    size_t total = 0;
    for (size_t i : idx) {
        offsets.push_back(total);
        total += cx.runs[i].size() * (cx.runs[i].run->setup == SetupKind::Dynamics ? 2 : 1);
    }
    if (r) r->assign(total, 0.0);
    J.setZero(static_cast<Eigen::Index>(total), static_cast<Eigen::Index>(names.size()));
    std::vector<char> ok(idx.size(), 0);
    parallelFor(idx.size(), [&](size_t k) {
        ok[k] = runJacobian(cx, spec, cx.runs[idx[k]], m, mass, names, offsets[k], r, J) ? 1 : 0;
    });
    return std::all_of(ok.begin(), ok.end(), [](char c) { return c != 0; });
}

}  // namespace stickslip::identify::detail
