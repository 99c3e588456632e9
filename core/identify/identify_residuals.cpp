// Residuals of a model on the prepared runs: the law channel (the extended law along the measured
// slip), the equation-of-motion channel, the segment residual, and the Jacobian the noise null uses.
#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <thread>

#include "../integrate/dynamics.hpp"
#include "prescribed_sensitivity.hpp"
#include "identify_internal.hpp"

namespace stickslip::identify::detail {

void applyLaw(RateStateParams& p, const std::string& name, double v) {
    if (double* f = RateStateLaw::field(p, name)) *f = v;
}

double lawValue(const RateStateParams& p, const std::string& name) {
    const double* f = RateStateLaw::field(const_cast<RateStateParams&>(p), name);
    return f ? *f : kNaN;
}

// Model from a flat map of values ("mu", "m", "frictional_lag.tau_s", …).
ExtendedModel buildModel(const Context& cx, const Spec& spec, const std::map<std::string, double>& vals, double& mass) {
    ExtendedModel m;
    m.law = cx.opt->start;
    for (const auto& [k, v] : vals) applyLaw(m.law, k, v);
    m.tNref_N = cx.tNref;
    m.stateStep = cx.opt->exactStateStep ? StateStep::ConstantRate : StateStep::BackwardEuler;
    for (const std::string& e : spec.effects) {
        EffectInfo info;
        findEffect(e, info);
        std::vector<double> pv;
        for (const auto& p : info.params) pv.push_back(vals.at(e + "." + p.name));
        setEffect(m.effects, e, pv);
    }
    // Dynamics: the rig's damping ratio within the baseline's "very small" range, unless the
    // viscous_damping effect (damping beyond it) is in the model.
    auto z = vals.find("zeta");
    if (z != vals.end() && !m.effects.viscousDamping) m.effects.viscousDamping = ViscousDamping{z->second};
    auto it = vals.find("m");
    mass = it != vals.end() ? it->second : kNaN;
    return m;
}

// Residuals of one run appended to `r`; per-run sum of squares and count; predicted force.
// Dynamics, Segments: re-initialised simulations (see DynamicsResidual in identify.hpp).
// Residuals: n slider-displacement then n force entries (0 outside the segments).
bool segmentResiduals(const Context& cx, const Prepared& p, const ExtendedModel& m, double mass, std::vector<double>& r,
                      double& ss, double& count, std::vector<double>* predicted, std::vector<char>* used,
                      std::vector<double>* frictionResidual) {
    const IdentifyRun& run = *p.run;
    const size_t n = p.size();
    const size_t base = r.size();
    r.resize(base + 2 * n, 0.0);
    if (predicted) predicted->assign(n, kNaN);
    if (used) used->assign(n, 0);
    if (frictionResidual) frictionResidual->assign(n, 0.0);
    if (n < 3) return true;
    const double mm = std::isfinite(mass) ? mass : run.nominalMass_kg;
    const double zeta = m.effects.viscousDamping ? m.effects.viscousDamping->zeta : cx.opt->zetaNominal;
    const double ms = m.effects.sensorInertia ? m.effects.sensorInertia->mass_kg : 0.0;
    const double tN = run.normalForce_N;
    RigParams rig;
    rig.normalForce_N = tN;
    rig.stiffness_N_per_m = run.stiffness_N_per_m;
    rig.mass_kg = mm;
    rig.damping_Ns_per_m = 2.0 * zeta * std::sqrt(run.stiffness_N_per_m * mm);
    const ExtendedLaw law = ExtendedLaw::make(m);
    const int sub = std::max(1, cx.opt->segmentSubsteps);
    const double h = (p.t[1] - p.t[0]) / sub;
    const stickslip::detail::NewmarkConstants K(rig, law.epsT(), h);
    const double C2 = m.law.C2();
    for (const auto& [i0, i1] : p.segments) {
        // Mid-slide start: slider state measured (smoothed), friction state at its sliding steady state.
        DynState s;
        s.t = p.t[i0];
        s.x = p.xs[i0];
        s.v = p.vs[i0];
        s.u = p.stageAt(s.t);
        const double V = p.Vs[i0], av = std::abs(V), sg = V >= 0 ? 1.0 : -1.0;
        LawState L = law.initialState(RunContext{tN, run.slipBefore_m + p.cumSlip[i0]});
        L.alpha = -C2 * av;
        L.aux[1] = av > 0 && m.effects.stickHealing ? m.effects.stickHealing->Dh_m / av : 0.0;  // steady age D_h/V
        const double y = law.lawStrength(L, sg, tN);
        L.force_N = sg * (y + m.law.eta_s_per_m * tN * av);
        L.aux[2] = y;
        if (m.effects.backlash) L.aux[3] = m.effects.backlash->loadedCoordinate(L.force_N, law.epsT());
        s.law = L;
        s.stuck = false;
        s.slipRate = av;
        s.a = (L.force_N - rig.damping_Ns_per_m * s.v - rig.stiffness_N_per_m * s.x) / mm;
        for (size_t i = i0 + 1; i <= i1; ++i) {
            for (int k = 0; k < sub; ++k) {
                int nIts = 0, lIts = 0;
                const char* why = nullptr;
                double bad = 0;
                const double u1 = p.stageAt(s.t + h);
                if (!stickslip::detail::newmarkStep(K, law, static_cast<int*>(nullptr), u1, s,
                                                    stickslip::Coupling::Newton, nIts, lIts, why, bad))
                    return false;
            }
            const double fSim = s.law.force_N + ms * s.a;
            const double ex = (s.x - p.x[i]) * p.invRmsX, ef = (fSim - p.F[i]) * p.invRmsF;
            r[base + i] = ex;
            r[base + n + i] = ef;
            ss += ex * ex + ef * ef;
            count += 2;
            if (predicted) (*predicted)[i] = fSim;
            if (used) (*used)[i] = 1;
            if (frictionResidual) (*frictionResidual)[i] = p.F[i] - fSim;
        }
    }
    return true;
}

bool lawParameter(const std::string& name) {
    return !(name == "m" || name == "zeta" || name.rfind("viscous_damping.", 0) == 0 ||
             name.rfind("sensor_inertia.", 0) == 0);
}

ExtendedModel lawChannelModel(const Prepared& p, const ExtendedModel& m) {
    ExtendedModel lawOnly = m;
    if (p.run->setup == SetupKind::Dynamics) lawOnly.effects.viscousDamping.reset();
    return lawOnly;
}

namespace {

// Each law step of the run split into `refinement` equal steps, the slip linear within a step
// (between its recorded end points where the run has them).
std::vector<double> refinedStepSlip(const Prepared& p, int substeps, int refinement) {
    std::vector<double> out;
    if (p.stepSlip.empty() || refinement <= 1) return out;
    out.reserve(p.stepSlip.size() * static_cast<size_t>(refinement));
    for (size_t i = 1; i < p.size(); ++i) {
        for (int k = 0; k < substeps; ++k) {
            const size_t j = (i - 1) * static_cast<size_t>(substeps) + static_cast<size_t>(k);
            const double a = k > 0 ? p.stepSlip[j - 1] : p.g[i - 1], b = p.stepSlip[j];
            for (int q = 1; q <= refinement; ++q) out.push_back(a + (b - a) * q / refinement);
        }
    }
    return out;
}

}  // namespace

namespace {

RunContext lawRunContext(const Prepared& p) {
    RunContext ctx{p.run->normalForce_N, p.run->slipBefore_m};
    // A run cut out of a longer recording (IdentifyRun::cutFromRecording) is loaded at its first
    // sample: the law starts from the measured force there, not from rest, which would
    // mispredict the first half-stroke by up to 2 μ t_N.
    if (p.run->cutFromRecording && !p.F.empty()) ctx.initialForce_N = p.F.front();
    return ctx;
}

}  // namespace

bool simulateLawRunSensitivity(const Context& cx, const Prepared& p, const ExtendedModel& m,
                               const std::vector<std::string>& names, LawRun& out, Eigen::MatrixXd& dMeasured) {
    PrescribedSensitivity s = simulatePrescribedSensitivity(lawChannelModel(p, m), lawRunContext(p), p.t, p.g,
                                                            p.a.empty() ? nullptr : &p.a, cx.opt->substeps, names, {},
                                                            p.stepSlip.empty() ? nullptr : &p.stepSlip);
    if (!s.ok()) return false;
    out.contactForce_N = std::move(s.trace.contactForce_N);
    out.relVel_mps = std::move(s.trace.relVel_mps);
    out.accel_mps2 = std::move(s.trace.sliderAccel_mps2);
    dMeasured = std::move(s.dMeasured);
    return true;
}

bool simulateLawRun(const Context& cx, const Prepared& p, const ExtendedModel& m, LawRun& out, int refinement) {
    refinement = std::max(1, refinement);
    const RunContext ctx = lawRunContext(p);
    const int sub = cx.opt->substeps;
    const std::vector<double> fine = refinedStepSlip(p, sub, refinement);
    const std::vector<double>* steps = refinement > 1 ? (fine.empty() ? nullptr : &fine)
                                                      : (p.stepSlip.empty() ? nullptr : &p.stepSlip);
    ExtendedTrace tr = simulateExtendedPrescribed(lawChannelModel(p, m), ctx, p.t, p.g, p.a.empty() ? nullptr : &p.a,
                                                  sub * refinement, {}, steps);
    if (!tr.ok()) return false;
    out.contactForce_N = std::move(tr.contactForce_N);
    out.relVel_mps = std::move(tr.relVel_mps);
    out.accel_mps2 = std::move(tr.sliderAccel_mps2);
    return true;
}

bool runResiduals(const Context& cx, const Prepared& p, const ExtendedModel& m, double mass, std::vector<double>& r,
                  double& ss, double& count, std::vector<double>* predicted, std::vector<char>* used,
                  std::vector<double>* frictionResidual, bool segments, const LawRun* law) {
    const IdentifyRun& run = *p.run;
    const size_t n = p.size();
    ss = 0;
    count = 0;
    if (predicted) predicted->assign(n, 0.0);
    if (used) used->assign(n, 0);
    if (frictionResidual) frictionResidual->assign(n, 0.0);
    if (segments && run.setup == SetupKind::Dynamics)
        return segmentResiduals(cx, p, m, mass, r, ss, count, predicted, used, frictionResidual);
    // The force the sensor sees: contact force + parallel dashpot + sensor inertia, formed as
    // simulateExtendedPrescribed forms it.
    LawRun own;
    if (!law) {
        if (!simulateLawRun(cx, p, m, own)) return false;
        law = &own;
    }
    const ExtendedModel lm = lawChannelModel(p, m);
    const double tN = run.normalForce_N;
    const double cp = lm.effects.viscousDamping ? lm.effects.viscousDamping->parallelDamping(tN) : 0.0;
    const double ms = m.effects.sensorInertia ? m.effects.sensorInertia->mass_kg : 0.0;  // sensed in both channels
    std::vector<double> measured(n);
    for (size_t i = 0; i < n; ++i)
        measured[i] = law->contactForce_N[i] + cp * law->relVel_mps[i] + ms * law->accel_mps2[i];
    if (run.setup == SetupKind::Prescribed) {
        const std::vector<double> Fp = p.filtered(measured);
        for (size_t i = 0; i < n; ++i) {
            const double e = (Fp[i] - p.F[i]) * p.invRmsF;
            r.push_back(e);
            ss += e * e;
            count += 1;
            if (predicted) (*predicted)[i] = Fp[i];
            if (used) (*used)[i] = 1;
            if (frictionResidual) (*frictionResidual)[i] = p.F[i] - Fp[i];
        }
        return true;
    }
    // Dynamics: law channel + equation-of-motion channel. The law channel runs the extended law
    // (return map with ε_T and every effect, Eqs. 1–4) along the measured slip g = u − x, as in
    // the prescribed set-up, and compares its force while the contact slides (|V| >= vStick, a
    // set fixed by the data, not by the parameters). The law keeps its state through stick
    // (elastic loading over ε_T, play, healing), so a compliant contact, a dead band or a
    // healed strength shape the force after each reversal; inside stick the measured slip's
    // noise times ε_T would swamp the comparison, and there the rig channel speaks instead.
    const double mm = std::isfinite(mass) ? mass : run.nominalMass_kg;
    const double zeta = m.effects.viscousDamping ? m.effects.viscousDamping->zeta : cx.opt->zetaNominal;
    const double c = 2.0 * zeta * std::sqrt(run.stiffness_N_per_m * mm);
    // The equation of motion's force: what the model says the sensor shows in stick.
    std::vector<double> rig(n);
    for (size_t i = 0; i < n; ++i) rig[i] = (mm + ms) * p.a[i] + c * p.xd[i] + run.stiffness_N_per_m * p.x[i];
    const std::vector<double> Fp = cx.opt->stickRigPrediction ? p.filtered(measured, p.slides, rig)
                                                              : p.filtered(measured, &p.slides);
    for (size_t i = 0; i < n; ++i) {
        double e = 0;
        const bool compared = p.compared[i];
        if (compared) {
            e = (Fp[i] - p.F[i]) * p.invRmsF;
            ss += e * e;
            count += 1;
            if (frictionResidual) (*frictionResidual)[i] = p.F[i] - Fp[i];
        }
        r.push_back(e);
        if (predicted) (*predicted)[i] = compared ? Fp[i] : kNaN;
        if (used) (*used)[i] = compared;
    }
    for (size_t i = 0; i < n; ++i) {
        const double e = (rig[i] - p.F[i]) * p.invRmsF;
        r.push_back(e);
        ss += e * e;
        count += 1;
    }
    return true;
}

size_t residualCount(const Context& cx, const std::vector<size_t>& idx) {
    size_t n = 0;
    for (size_t i : idx) n += cx.runs[i].size() * (cx.runs[i].run->setup == SetupKind::Dynamics ? 2 : 1);
    return n;
}

// The residual vector of a model over the runs idx (false if a run fails); `used` (optional)
// marks the entries a channel compares.
bool residualVector(const Context& cx, const Spec& spec, const std::map<std::string, double>& vals,
                    const std::vector<size_t>& idx, std::vector<double>& r, std::vector<NoiseBlock>* blocks) {
    double mass = kNaN;
    const ExtendedModel m = buildModel(cx, spec, vals, mass);
    r.clear();
    if (blocks) blocks->clear();
    for (size_t i : idx) {
        const size_t off = r.size();
        double ss = 0, n = 0;
        std::vector<char> used;
        if (!runResiduals(cx, cx.runs[i], m, mass, r, ss, n, nullptr, &used, nullptr, spec.segments)) return false;
        if (!blocks) continue;
        // One block per channel: the run's n samples each (law/force, then rig or displacement).
        const size_t nRun = cx.runs[i].size(), channels = (r.size() - off) / std::max<size_t>(nRun, 1);
        for (size_t ch = 0; ch < channels; ++ch) {
            NoiseBlock b;
            b.offset = off + ch * nRun;
            b.length = nRun;
            // The equation-of-motion channel compares every sample; the others where `used`.
            const bool eom = cx.runs[i].run->setup == SetupKind::Dynamics && !spec.segments && ch == 1;
            b.used = eom || used.size() != nRun ? std::vector<char>(nRun, 1) : used;
            const std::vector<double> blockR(r.begin() + static_cast<long>(b.offset),
                                             r.begin() + static_cast<long>(b.offset + nRun));
            fitAr1(blockR, b.used, b.phi, b.sigma);
            blocks->push_back(std::move(b));
        }
    }
    return true;
}

bool numericsOffset(const Context& cx, const Spec& spec, const std::map<std::string, double>& vals,
                    const std::vector<size_t>& idx, const std::vector<double>& r0, std::vector<double>& d) {
    // The finer prediction: at the recorded rate, else with more law (Newmark) steps per sample.
    const bool fullRate = cx.fullRate && !spec.segments;
    IdentifyOptions fineOpt = *cx.opt;
    fineOpt.substeps = std::max(1, fineOpt.substeps) * kNumericsRefinement;
    fineOpt.segmentSubsteps = std::max(1, fineOpt.segmentSubsteps) * kNumericsRefinement;
    Context sub;
    if (!fullRate) {
        sub = cx;
        sub.opt = &fineOpt;
        sub.fullRate = nullptr;
        for (size_t i : idx)
            if (!sub.runs[i].stepSlip.empty()) prepareStepSlip(*sub.runs[i].run, sub.runs[i].dec, fineOpt.substeps, sub.runs[i]);
    }
    const Context& fc = fullRate ? *cx.fullRate : sub;
    std::vector<double> rf;
    if (!residualVector(fc, spec, vals, idx, rf)) return false;
    // Row of the fine residual that each of r0's entries compares with (sample k of a decimated
    // run is its recorded sample k·dec).
    std::vector<size_t> row;
    row.reserve(r0.size());
    size_t offF = 0;
    for (size_t i : idx) {
        const size_t nC = cx.runs[i].size(), nF = fc.runs[i].size(), dec = fullRate ? cx.runs[i].dec : 1;
        const size_t channels = cx.runs[i].run->setup == SetupKind::Dynamics ? 2 : 1;
        if (nC == 0 || nF < (nC - 1) * dec + 1) return false;
        for (size_t ch = 0; ch < channels; ++ch)
            for (size_t k = 0; k < nC; ++k) row.push_back(offF + ch * nF + k * dec);
        offF += channels * nF;
    }
    if (row.size() != r0.size() || offF != rf.size()) return false;
    // The fine model refitted to the same samples (linearised at vals): the coarse fit's parameters
    // have taken up the part of its numerical error they can, so the comparison is between the
    // two models' best fits, not at one point. Without it the fine model's misfit at the coarse
    // optimum leaks into the candidate's direction through the difference of the two Jacobians.
    // Parameters on a bound of their range stay there: the coarse fit could not move them either
    // (an active constraint), and a refit through one would take up structure the bound keeps
    // out, e.g. the rig's ζ at its baseline maximum would absorb a viscous damping beyond it.
    const std::vector<FitParameter> ps = parameters(cx, spec, vals);
    std::vector<std::string> names;
    for (const FitParameter& p : ps)
        if (p.free && boundSide(p, vals.count(p.name) ? vals.at(p.name) : p.value) == 0) names.push_back(p.name);
    const Eigen::Index n = static_cast<Eigen::Index>(r0.size());
    Eigen::VectorXd rs(n);
    for (Eigen::Index k = 0; k < n; ++k) rs[k] = rf[row[static_cast<size_t>(k)]];
    if (!names.empty()) {
        const Eigen::MatrixXd Jf = residualJacobian(fc, spec, vals, idx, ps, names, rf.size());
        Eigen::MatrixXd Js(n, Jf.cols());
        for (Eigen::Index k = 0; k < n; ++k) Js.row(k) = Jf.row(static_cast<Eigen::Index>(row[static_cast<size_t>(k)]));
        Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(Js);
        qr.setThreshold(1e-9);
        rs -= Js * qr.solve(rs);
    }
    d.resize(r0.size());
    for (Eigen::Index k = 0; k < n; ++k) d[static_cast<size_t>(k)] = r0[static_cast<size_t>(k)] - rs[k];
    return true;
}

// Jacobian of the residual vector in the solver's coordinates (log for log-scaled parameters,
// the range for linear ones) at `vals`, for the free parameters whose names are in `which`: from
// forward sensitivities with IdentifyOptions::analyticJacobian, else by central differences (a
// column whose step would leave the bounds uses a one-sided step).
Eigen::MatrixXd residualJacobian(const Context& cx, const Spec& spec, const std::map<std::string, double>& vals,
                                 const std::vector<size_t>& idx, const std::vector<FitParameter>& params,
                                 const std::vector<std::string>& which, size_t rows) {
    Eigen::MatrixXd J(static_cast<Eigen::Index>(rows), static_cast<Eigen::Index>(which.size()));
    J.setZero();
    // From forward sensitivities when the options ask for them and every column's parameter is
    // in vals: in the solver's coordinates, ∂r/∂z = ∂r/∂v · dv/dz (v e^z on a log scale).
    if (cx.opt->analyticJacobian && !spec.segments &&
        std::all_of(which.begin(), which.end(), [&](const std::string& k) { return vals.count(k) > 0; })) {
        Eigen::MatrixXd Jv;
        if (analyticResidualJacobian(cx, spec, vals, idx, which, Jv) && static_cast<size_t>(Jv.rows()) == rows) {
            for (size_t c = 0; c < which.size(); ++c) {
                const auto it = std::find_if(params.begin(), params.end(), [&](const FitParameter& p) { return p.name == which[c]; });
                if (it == params.end()) continue;
                const double v = vals.at(it->name);
                J.col(static_cast<Eigen::Index>(c)) =
                    Jv.col(static_cast<Eigen::Index>(c)) * (it->scale == ParamScale::Log ? v : it->upper - it->lower);
            }
            return J;
        }
        J.setZero();
    }
    constexpr double h = 1e-4;
    parallelFor(which.size(), [&](size_t c) {
        const auto it = std::find_if(params.begin(), params.end(), [&](const FitParameter& p) { return p.name == which[c]; });
        if (it == params.end()) return;
        const FitParameter& p = *it;
        const double v = vals.count(p.name) ? vals.at(p.name) : p.value;
        auto shifted = [&](double dz) {
            return p.scale == ParamScale::Log ? v * std::exp(dz) : v + dz * (p.upper - p.lower);
        };
        double up = h, dn = -h;
        if (shifted(up) > p.upper) up = 0.0;
        if (shifted(dn) < p.lower) dn = 0.0;
        if (up == dn) return;
        std::map<std::string, double> a = vals, b = vals;
        a[p.name] = shifted(up);
        b[p.name] = shifted(dn);
        std::vector<double> ra, rb;
        if (!residualVector(cx, spec, a, idx, ra) || !residualVector(cx, spec, b, idx, rb) || ra.size() != rows ||
            rb.size() != rows)
            return;
        for (size_t k = 0; k < rows; ++k) J(static_cast<Eigen::Index>(k), static_cast<Eigen::Index>(c)) = (ra[k] - rb[k]) / (up - dn);
    });
    return J;
}

// The residuals of model m over the runs idx, appended run after run to r (cleared first), and
// their sum of squares and count added to ss and n; false where a run cannot be evaluated.
bool residualsOver(const Context& cx, const Spec& spec, const std::vector<size_t>& idx, const ExtendedModel& m,
                   double mass, std::vector<double>& r, double& ss, double& n) {
    r.clear();
    for (size_t i : idx) {
        double ssRun = 0, nRun = 0;
        if (!runResiduals(cx, cx.runs[i], m, mass, r, ssRun, nRun, nullptr, nullptr, nullptr, spec.segments)) return false;
        ss += ssRun;
        n += nRun;
    }
    return true;
}

// Sum of squared residuals of a model over the runs idx (inf if a run fails).
double evalSS(const Context& cx, const Spec& spec, const std::map<std::string, double>& vals, const std::vector<size_t>& idx) {
    double mass = kNaN, ss = 0, n = 0;
    const ExtendedModel m = buildModel(cx, spec, vals, mass);
    std::vector<double> r;
    return residualsOver(cx, spec, idx, m, mass, r, ss, n) ? ss : std::numeric_limits<double>::infinity();
}

int lowestSS(const Context& cx, const Spec& spec, const std::vector<std::map<std::string, double>>& points,
             const std::vector<size_t>& idx, double below, std::vector<double>* sums) {
    const size_t n = points.size();
    constexpr double kInf = std::numeric_limits<double>::infinity();
    std::vector<double> ss(n, kInf);
    std::vector<size_t> runsDone(n, 0);
    std::vector<ExtendedModel> models(n);
    std::vector<double> masses(n, kNaN);
    // Adds run j's sum to point k's (in idx order, as evalSS adds them); false if it fails.
    auto addRun = [&](size_t k, size_t j) {
        double ssRun = 0, nRun = 0;
        std::vector<double> r;
        if (!runResiduals(cx, cx.runs[idx[j]], models[k], masses[k], r, ssRun, nRun, nullptr, nullptr, nullptr, spec.segments)) {
            ss[k] = kInf;
            runsDone[k] = idx.size();
            return false;
        }
        ss[k] = (j == 0 ? 0.0 : ss[k]) + ssRun;
        runsDone[k] = j + 1;
        return true;
    };
    std::atomic<double> lowest{below};
    auto offer = [&](double v) {
        for (double seen = lowest.load(); v < seen && !lowest.compare_exchange_weak(seen, v);) {
        }
    };
    parallelFor(n, [&](size_t k) {
        models[k] = buildModel(cx, spec, points[k], masses[k]);
        if (idx.empty()) ss[k] = 0.0, runsDone[k] = 0;
        else if (addRun(k, 0) && idx.size() == 1) offer(ss[k]);
    });
    std::vector<size_t> order(n);
    std::iota(order.begin(), order.end(), size_t{0});
    std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return ss[a] < ss[b]; });
    parallelFor(n, [&](size_t o) {
        const size_t k = order[o];
        while (runsDone[k] < idx.size() && !(ss[k] > lowest.load()))
            if (!addRun(k, runsDone[k])) return;
        if (runsDone[k] == idx.size()) offer(ss[k]);
    });
    int best = -1;
    for (size_t k = 0; k < n; ++k)
        if (runsDone[k] == idx.size() && ss[k] < below && (best < 0 || ss[k] < ss[static_cast<size_t>(best)]))
            best = static_cast<int>(k);
    if (sums) *sums = ss;
    return best;
}

}  // namespace stickslip::identify::detail
