#include "identify.hpp"

#include <algorithm>
#include <atomic>
#include <thread>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>

#include <Eigen/Dense>

#include "../integrate/dynamics.hpp"
#include "fit.hpp"
#include "noise_null.hpp"

namespace stickslip::identify {

bool makeIdentifyRun(const CleanRun& c, SetupKind setup, IdentifyRun& out, std::string* error) {
    using io::Signal;
    const io::Run& r = c.run;
    auto need = [&](Signal s, const char* what) {
        if (r.has(s)) return true;
        if (error) *error = r.file + ": no " + what + " signal (column " + io::defaultColumn(s) + ")";
        return false;
    };
    if (!need(Signal::Time, "time") || !need(Signal::Friction, "friction force") || !need(Signal::Slip, "slip") ||
        !need(Signal::RelVel, "relative velocity"))
        return false;
    if (setup == SetupKind::Dynamics && !need(Signal::SliderDisp, "slider displacement")) return false;
    const size_t b = std::min(c.begin, r.size()), e = std::min(c.end, r.size());
    if (e < b + 10) {
        if (error) *error = r.file + ": fewer than 10 samples left after trimming";
        return false;
    }
    auto cut = [&](Signal s) {
        if (!r.has(s)) return std::vector<double>{};
        return std::vector<double>(r[s].begin() + b, r[s].begin() + e);
    };
    IdentifyRun o;
    o.file = r.file;
    o.setup = setup;
    o.t_s = cut(Signal::Time);
    o.slip_m = cut(Signal::Slip);
    o.relVel_mps = cut(Signal::RelVel);
    o.force_N = cut(Signal::Friction);
    if (setup == SetupKind::Dynamics) {
        o.slider_m = cut(Signal::SliderDisp);
        o.sliderVel_mps = cut(Signal::SliderVel);
        o.accel_mps2 = cut(Signal::SliderAccel);
        if (o.sliderVel_mps.empty() || o.accel_mps2.empty()) {
            // ẋ and ẍ by Savitzky–Golay from x when not measured.
            const auto& x = r[Signal::SliderDisp];
            auto v = savitzkyGolay(x, c.dt_s, 7, 3, 1), a = savitzkyGolay(x, c.dt_s, 7, 3, 2);
            if (o.sliderVel_mps.empty()) o.sliderVel_mps.assign(v.begin() + b, v.begin() + e);
            if (o.accel_mps2.empty()) o.accel_mps2.assign(a.begin() + b, a.begin() + e);
        }
    } else {
        auto a = savitzkyGolay(r[Signal::Slip], c.dt_s, 7, 3, 2);
        o.accel_mps2.assign(a.begin() + b, a.begin() + e);
    }
    o.filtered = !c.filter.empty();
    o.filters = c.filterSettings;
    double v = 0;
    o.normalForce_N = r.setting("tN", v) ? v : 1.0;
    if (r.setting("k", v)) o.stiffness_N_per_m = v;
    if (r.setting("m", v)) o.nominalMass_kg = v;
    if (r.setting("f", v)) o.frequency_Hz = v;
    else if (c.period_s > 0) o.frequency_Hz = 1.0 / c.period_s;
    if (setup == SetupKind::Dynamics && !(o.stiffness_N_per_m > 0)) {
        if (error) *error = r.file + ": dynamics set-up needs the rig stiffness k (manifest or --run-set FILE:k=VALUE)";
        return false;
    }
    out = std::move(o);
    return true;
}

namespace {

using Clock = std::chrono::steady_clock;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// A run prepared for fast repeated evaluation: decimated samples, weights.
struct Prepared {
    const IdentifyRun* run = nullptr;
    std::vector<double> t, g, V, F, a, x, xd;
    double invRmsF = 1.0;
    Sos predictionFilter;  // the run's cleaning filters at the decimated rate (those below its Nyquist)
    // The prediction y as the cleaned measurement would show it: F + filter(mask·(y − F)), the
    // difference taken only where the prediction applies (mask; all samples when null), so the
    // stick phases that are not compared cannot leak into compared samples.
    std::vector<double> filtered(const std::vector<double>& y, const std::vector<char>* mask = nullptr) const {
        if (predictionFilter.empty()) return y;
        std::vector<double> d(y.size(), 0.0);
        for (size_t i = 0; i < y.size(); ++i)
            if (!mask || (*mask)[i]) d[i] = y[i] - F[i];
        d = filtfiltZeroExtended(predictionFilter, d);
        for (size_t i = 0; i < y.size(); ++i) d[i] += F[i];
        return d;
    }
    // Dynamics, segment residual: smoothed slider state, cleaned stage motion, slip so far,
    // segments [first, last] of samples (each starts mid-slide).
    std::vector<double> xs, vs, u, Vs, cumSlip;
    std::vector<std::pair<size_t, size_t>> segments;
    double invRmsX = 1.0;
    bool stageHarmonic = false;
    double uc0 = 0, ua = 0, ub = 0, omega = 0;  // u = uc0 + ua cos ωt + ub sin ωt when harmonic
    size_t size() const { return t.size(); }
    double stageAt(double tt) const {
        if (stageHarmonic) return uc0 + ua * std::cos(omega * tt) + ub * std::sin(omega * tt);
        const double dt = t[1] - t[0];
        const double q = std::clamp((tt - t.front()) / dt, 0.0, static_cast<double>(t.size() - 1));
        const size_t i = std::min(static_cast<size_t>(q), t.size() - 2);
        const double w = q - static_cast<double>(i);
        return u[i] * (1.0 - w) + u[i + 1] * w;
    }
};

// The model (effects, in order added) and how its dynamics residual is formed.
struct Spec {
    std::vector<std::string> effects;   // catalogue names, in order added
    bool segments = false;              // dynamics: segment simulation instead of equation error
};

bool actsInStick(const std::string& effect) {
    return effect == "backlash" || effect == "presliding_compliance" || effect == "stick_healing";
}

struct Context {
    std::vector<Prepared> runs;
    const IdentifyOptions* opt = nullptr;
    bool anyDynamics = false;
    double tNref = 1.0;
};

void applyLaw(RateStateParams& p, const std::string& name, double v) {
    if (name == "mu") p.mu = v;
    else if (name == "C1") p.C1 = v;
    else if (name == "eta") p.eta_s_per_m = v;
    else if (name == "Dc") p.Dc_m = v;
    else if (name == "vc") p.vc_mps = v;
    else if (name == "epsT") p.epsT_N_per_m = v;
    else if (name == "r") p.r = v;
}

double lawValue(const RateStateParams& p, const std::string& name) {
    if (name == "mu") return p.mu;
    if (name == "C1") return p.C1;
    if (name == "eta") return p.eta_s_per_m;
    if (name == "Dc") return p.Dc_m;
    if (name == "vc") return p.vc_mps;
    if (name == "epsT") return p.epsT_N_per_m;
    if (name == "r") return p.r;
    return kNaN;
}

// Model from a flat map of values ("mu", "m", "frictional_lag.tau_s", …).
ExtendedModel buildModel(const Context& cx, const Spec& spec, const std::map<std::string, double>& vals, double& mass) {
    ExtendedModel m;
    m.law = cx.opt->start;
    for (const auto& [k, v] : vals) applyLaw(m.law, k, v);
    m.tNref_N = cx.tNref;
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
        const double y = tN * (law.muEffective(L, sg, tN) + law.K1(L.alpha));
        L.force_N = sg * (y + m.law.eta_s_per_m * tN * av);
        L.aux[1] = 0.0;
        L.aux[2] = y;
        if (m.effects.backlash)  // play taken up on the side the force acts on: ε dz(w) = F
            L.aux[3] = L.force_N / law.epsT() + (L.force_N >= 0 ? 1.0 : -1.0) * m.effects.backlash->halfWidth_m;
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

bool runResiduals(const Context& cx, const Prepared& p, const ExtendedModel& m, double mass, std::vector<double>& r,
                  double& ss, double& count, std::vector<double>* predicted, std::vector<char>* used,
                  std::vector<double>* frictionResidual, bool segments) {
    const IdentifyRun& run = *p.run;
    RunContext ctx{run.normalForce_N, run.slipBefore_m};
    const size_t n = p.size();
    ss = 0;
    count = 0;
    if (predicted) predicted->assign(n, 0.0);
    if (used) used->assign(n, 0);
    if (frictionResidual) frictionResidual->assign(n, 0.0);
    if (run.setup == SetupKind::Prescribed) {
        const ExtendedTrace tr = simulateExtendedPrescribed(m, ctx, p.t, p.g, p.a.empty() ? nullptr : &p.a,
                                                            cx.opt->substeps);
        if (!tr.ok()) return false;
        const std::vector<double> Fp = p.filtered(tr.measuredForce_N);
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
    if (segments) return segmentResiduals(cx, p, m, mass, r, ss, count, predicted, used, frictionResidual);
    // Dynamics: law channel + equation-of-motion channel. The law channel runs the extended law
    // (return map with ε_T and every effect, Eqs. 1–4) along the measured slip g = u − x, as in
    // the prescribed set-up, and compares its force while the contact slides (|V| >= vStick, a
    // set fixed by the data, not by the parameters). The law keeps its state through stick
    // (elastic loading over ε_T, play, healing), so a compliant contact, a dead band or a
    // healed strength shape the force after each reversal; inside stick the measured slip's
    // noise times ε_T would swamp the comparison, and there the rig channel speaks instead.
    ExtendedModel lawOnly = m;
    lawOnly.effects.viscousDamping.reset();  // a rig effect here, in the equation of motion
    const ExtendedTrace tr = simulateExtendedPrescribed(lawOnly, ctx, p.t, p.g, p.a.empty() ? nullptr : &p.a,
                                                        cx.opt->substeps);
    if (!tr.ok()) return false;
    const double vStick = cx.opt->stickVelocity_mps;
    std::vector<char> mask(n, 0);
    for (size_t i = 0; i < n; ++i) mask[i] = std::abs(p.V[i]) >= vStick;
    const std::vector<double> Fp = p.filtered(tr.measuredForce_N, &mask);
    const double mm = std::isfinite(mass) ? mass : run.nominalMass_kg;
    const double zeta = m.effects.viscousDamping ? m.effects.viscousDamping->zeta : cx.opt->zetaNominal;
    const double c = 2.0 * zeta * std::sqrt(run.stiffness_N_per_m * mm);
    const double ms = m.effects.sensorInertia ? m.effects.sensorInertia->mass_kg : 0.0;
    for (size_t i = 0; i < n; ++i) {
        double e = 0;
        const bool compared = mask[i];
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
        const double fm = (mm + ms) * p.a[i] + c * p.xd[i] + run.stiffness_N_per_m * p.x[i];
        const double e = (fm - p.F[i]) * p.invRmsF;
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

struct FitOutcome {
    bool ok = false;
    std::string message;
    std::map<std::string, double> values;
    std::vector<ParamEstimate> estimates;
    double ss = 0, count = 0;   // over the fitted runs
    int nFree = 0;
    FitResult fit;
};

// Parameters of the model `spec`: baseline free law parameters, m* (dynamics), effect params.
std::vector<FitParameter> parameters(const Context& cx, const Spec& spec, const std::map<std::string, double>& start) {
    std::vector<FitParameter> ps;
    const SetupKind setup = cx.anyDynamics ? SetupKind::Dynamics : SetupKind::Prescribed;
    // The segment residual resolves stick, where the contact stiffness ε_T acts: ε_T is then
    // part of the baseline (held fixed, every stick-phase candidate would be credited with
    // the baseline's wrong stiffness).
    std::vector<std::string> freeLaw = cx.opt->freeLaw;
    if (spec.segments && std::find(freeLaw.begin(), freeLaw.end(), "epsT") == freeLaw.end()) freeLaw.push_back("epsT");
    for (const std::string& n : freeLaw) {
        FitParameter p;
        if (!defaultParameter(n, setup, p)) continue;
        auto it = start.find(n);
        p.value = it != start.end() ? it->second : lawValue(cx.opt->start, n);
        p.value = std::clamp(p.value, p.lower, p.upper);
        ps.push_back(p);
    }
    if (cx.anyDynamics && cx.opt->fitMass) {
        FitParameter p{"m", 0.53, 0.05, 5.0, true, ParamScale::Log};
        auto it = start.find("m");
        if (it != start.end()) p.value = it->second;
        ps.push_back(p);
    }
    const bool dampingEffect = std::find(spec.effects.begin(), spec.effects.end(), "viscous_damping") != spec.effects.end();
    if (cx.anyDynamics && !dampingEffect) {
        FitParameter p{"zeta", cx.opt->zetaNominal, ViscousDamping::kBaselineMin, ViscousDamping::kBaselineMax, true,
                       ParamScale::Log};
        auto it = start.find("zeta");
        if (it != start.end()) p.value = it->second;
        p.value = std::clamp(p.value, p.lower, p.upper);
        ps.push_back(p);
    }
    for (const std::string& e : spec.effects) {
        EffectInfo info;
        findEffect(e, info);
        for (const EffectParam& q : info.params) {
            FitParameter p{e + "." + q.name, q.initial, q.lower, q.upper, true, q.logScale ? ParamScale::Log : ParamScale::Linear};
            auto it = start.find(p.name);
            if (it != start.end()) p.value = it->second;
            ps.push_back(p);
        }
    }
    return ps;
}

FitOutcome fitSpec(const Context& cx, const Spec& spec, const std::map<std::string, double>& start,
                   const std::vector<size_t>& idx, int multistarts, long& fits, bool scanStiffness = false) {
    FitOutcome out;
    FitProblem prob;
    prob.parameters = parameters(cx, spec, start);
    // Baseline: the contact stiffness and the state distance set where the force turns after a
    // reversal and how fast it settles; their costs have narrow valleys a local solver does not
    // leave, so each is scanned on a log grid over its physical bounds first (fit.hpp).
    if (scanStiffness)
        for (const FitParameter& fp : prob.parameters) {
            if (!fp.free || (fp.name != "epsT" && fp.name != "Dc")) continue;
            const double lo = fp.name == "epsT" ? std::max(fp.lower, 1e3) : std::max(fp.lower, 1e-7);
            const double hi = fp.name == "epsT" ? std::min(fp.upper, 1e8) : std::min(fp.upper, 1e-2);
            const int nGrid = fp.name == "epsT" ? 26 : 11;
            ParameterScan sc{fp.name, {}};
            for (int k = 0; k < nGrid; ++k) sc.values.push_back(lo * std::pow(hi / lo, k / (nGrid - 1.0)));
            prob.scans.push_back(sc);
        }
    prob.residualCount = residualCount(cx, idx);
    prob.multistarts = multistarts;
    prob.seed = cx.opt->seed;
    prob.cancel = cx.opt->cancel;
    prob.maxIterations = 40;
    prob.functionTolerance = 1e-7;
    prob.parameterTolerance = 1e-7;
    const auto names = [&] {
        std::vector<std::string> v;
        for (const auto& p : prob.parameters) v.push_back(p.name);
        return v;
    }();
    prob.residuals = [&cx, &spec, &idx, names](const std::vector<double>& pv, std::vector<double>& r) {
        std::map<std::string, double> vals;
        for (size_t i = 0; i < names.size(); ++i) vals[names[i]] = pv[i];
        double mass = kNaN;
        const ExtendedModel m = buildModel(cx, spec, vals, mass);
        r.clear();
        for (size_t i : idx) {
            double ss = 0, n = 0;
            if (!runResiduals(cx, cx.runs[i], m, mass, r, ss, n, nullptr, nullptr, nullptr, spec.segments)) return false;
        }
        return true;
    };
    // The 2p points of a numeric Jacobian as (point, run) tasks over the cores; each task writes
    // its own slice, so the result does not depend on the scheduling.
    std::vector<size_t> offsets;
    {
        size_t o = 0;
        for (size_t i : idx) {
            offsets.push_back(o);
            o += cx.runs[i].size() * (cx.runs[i].run->setup == SetupKind::Dynamics ? 2 : 1);
        }
    }
    prob.batchResiduals = [&cx, &spec, &idx, names, offsets](const std::vector<std::vector<double>>& points,
                                                             std::vector<std::vector<double>>& rs, std::vector<char>& okOut) {
        const size_t nRuns = idx.size(), nTasks = points.size() * nRuns;
        std::vector<ExtendedModel> models(points.size());
        std::vector<double> masses(points.size(), kNaN);
        for (size_t pt = 0; pt < points.size(); ++pt) {
            std::map<std::string, double> vals;
            for (size_t i = 0; i < names.size(); ++i) vals[names[i]] = points[pt][i];
            models[pt] = buildModel(cx, spec, vals, masses[pt]);
        }
        rs.resize(points.size());
        std::vector<char> ok(nTasks, 0);
        std::atomic<size_t> next{0};
        auto work = [&]() {
            for (size_t t = next.fetch_add(1); t < nTasks; t = next.fetch_add(1)) {
                const size_t pt = t / nRuns, k = t % nRuns;
                std::vector<double> r;
                double ss = 0, n = 0;
                if (!runResiduals(cx, cx.runs[idx[k]], models[pt], masses[pt], r, ss, n, nullptr, nullptr, nullptr,
                                  spec.segments))
                    continue;
                std::copy(r.begin(), r.end(), rs[pt].begin() + static_cast<long>(offsets[k]));
                ok[t] = 1;
            }
        };
        const size_t workers = std::min<size_t>(std::max(1u, std::thread::hardware_concurrency()), nTasks);
        std::vector<std::thread> pool;
        for (size_t w = 1; w < workers; ++w) pool.emplace_back(work);
        work();
        for (std::thread& th : pool) th.join();
        okOut.assign(points.size(), 1);
        for (size_t t = 0; t < nTasks; ++t)
            if (!ok[t]) okOut[t / nRuns] = 0;
    };
    ++fits;
    out.fit = fitLeastSquares(prob);
    if (!out.fit.ok()) {
        out.message = out.fit.message;
        return out;
    }
    out.ok = true;
    for (size_t i = 0; i < out.fit.names.size(); ++i) {
        out.values[out.fit.names[i]] = out.fit.values[i];
        if (out.fit.free[i]) {
            out.estimates.push_back({out.fit.names[i], out.fit.values[i], out.fit.stderrs[i]});
            ++out.nFree;
        }
    }
    double mass = kNaN;
    const ExtendedModel m = buildModel(cx, spec, out.values, mass);
    std::vector<double> r;
    for (size_t i : idx) {
        double ss = 0, n = 0;
        runResiduals(cx, cx.runs[i], m, mass, r, ss, n, nullptr, nullptr, nullptr, spec.segments);
        out.ss += ss;
        out.count += n;
    }
    return out;
}

// Per-run errors of a fitted model: in-sample for the fit runs, prediction for validation
// runs; held-out errors by leave-one-run-out (fit runs) when there are no validation runs.
// `loo` (optional): the parameter values of each leave-one-run-out fit (for the jackknife).
ModelErrors errorsOf(const Context& cx, const Spec& spec, const FitOutcome& full, const std::vector<size_t>& fitIdx,
                     const std::vector<size_t>& valIdx, long& fits,
                     std::vector<std::map<std::string, double>>* loo = nullptr) {
    ModelErrors me;
    double mass = kNaN;
    const ExtendedModel m = buildModel(cx, spec, full.values, mass);
    double fitSS = 0, fitN = 0, valSS = 0, valN = 0;
    for (size_t i = 0; i < cx.runs.size(); ++i) {
        const bool isVal = std::find(valIdx.begin(), valIdx.end(), i) != valIdx.end();
        std::vector<double> r, fr;
        std::vector<char> used;
        double ss = 0, n = 0;
        runResiduals(cx, cx.runs[i], m, mass, r, ss, n, nullptr, &used, &fr, spec.segments);
        RunError e;
        e.file = cx.runs[i].run->file;
        e.role = isVal ? "validation" : "fit";
        e.nrmse = n > 0 ? std::sqrt(ss / n) : 0.0;
        double fs = 0, fn = 0;
        for (size_t k = 0; k < fr.size(); ++k)
            if (used[k]) { fs += fr[k] * fr[k]; fn += 1; }
        e.rms_N = fn > 0 ? std::sqrt(fs / fn) : 0.0;
        if (isVal) {
            e.heldOutNrmse = e.nrmse;
            valSS += ss; valN += n;
        } else {
            fitSS += ss; fitN += n;
        }
        me.runs.push_back(e);
    }
    me.fitNrmse = fitN > 0 ? std::sqrt(fitSS / fitN) : 0.0;
    if (valIdx.empty() && fitIdx.size() >= 2) {
        // Leave one run out in turn, warm-started from the full fit.
        for (size_t h : fitIdx) {
            if (cx.opt->cancel && cx.opt->cancel->load()) break;
            std::vector<size_t> rest;
            for (size_t i : fitIdx) if (i != h) rest.push_back(i);
            const FitOutcome f = fitSpec(cx, spec, full.values, rest, 1, fits);
            if (!f.ok) continue;
            if (loo) loo->push_back(f.values);
            double mh = kNaN;
            const ExtendedModel mo = buildModel(cx, spec, f.values, mh);
            std::vector<double> r;
            double ss = 0, n = 0;
            if (!runResiduals(cx, cx.runs[h], mo, mh, r, ss, n, nullptr, nullptr, nullptr, spec.segments)) continue;
            me.runs[h].heldOutNrmse = n > 0 ? std::sqrt(ss / n) : 0.0;
            valSS += ss; valN += n;
        }
    }
    me.validationNrmse = valN > 0 ? std::sqrt(valSS / valN) : kNaN;
    return me;
}

// Diagnostics of a fitted model's force residual (friction channel, samples compared).
Diagnostics diagnoseModel(const Context& cx, const Spec& spec, const FitOutcome& f, std::vector<std::vector<double>>* preds) {
    double mass = kNaN;
    const ExtendedModel m = buildModel(cx, spec, f.values, mass);
    std::vector<DiagnosticRun> dr;
    for (size_t i = 0; i < cx.runs.size(); ++i) {
        const Prepared& p = cx.runs[i];
        std::vector<double> r, fr, pred;
        std::vector<char> used;
        double ss = 0, n = 0;
        runResiduals(cx, p, m, mass, r, ss, n, &pred, &used, &fr, spec.segments);
        if (preds) preds->push_back(pred);
        DiagnosticRun d;
        d.t_s = p.t;
        d.residual = fr;
        d.slip_m = p.g;
        d.relVel_mps = p.V;
        d.accel_mps2 = p.a;
        d.normalForce_N = p.run->normalForce_N;
        d.forcingFrequency_Hz = p.run->frequency_Hz;
        d.accumulatedSlipStart_m = p.run->slipBefore_m;
        d.runIndex = static_cast<int>(i);
        dr.push_back(std::move(d));
    }
    const double fs = cx.runs.empty() || cx.runs[0].size() < 2 ? 1.0 : 1.0 / (cx.runs[0].t[1] - cx.runs[0].t[0]);
    // Decimate to about 2× the 100 Hz measurement bandwidth before the whiteness test.
    const int dec = std::max(1, static_cast<int>(std::floor(fs / 200.0)));
    Diagnostics d = diagnose(dr, dec, cx.opt->stickVelocity_mps);
    if (cx.anyDynamics) {
        // Equation-of-motion channel: its residual against the slider velocity and acceleration
        // (where rig damping and sensor inertia show).
        std::vector<double> rr, xd, xa;
        const double zeta = m.effects.viscousDamping ? m.effects.viscousDamping->zeta : cx.opt->zetaNominal;
        const double ms = m.effects.sensorInertia ? m.effects.sensorInertia->mass_kg : 0.0;
        for (const Prepared& p : cx.runs) {
            if (p.run->setup != SetupKind::Dynamics) continue;
            const double mm = std::isfinite(mass) ? mass : p.run->nominalMass_kg;
            const double c = 2.0 * zeta * std::sqrt(p.run->stiffness_N_per_m * mm);
            for (size_t i = 0; i < p.size(); ++i) {
                rr.push_back(p.F[i] - ((mm + ms) * p.a[i] + c * p.xd[i] + p.run->stiffness_N_per_m * p.x[i]));
                xd.push_back(p.xd[i]);
                xa.push_back(p.a[i]);
            }
        }
        d.correlations.push_back({"eom_slider_velocity", pearson(rr, xd)});
        d.correlations.push_back({"eom_slider_accel", pearson(rr, xa)});
    }
    return d;
}

// Stage motion u = g + x, cleaned: a least-squares harmonic at the run's forcing frequency
// when it fits to 10 % of its amplitude (the usual drive), else Savitzky–Golay smoothed.
// Slider x and ẋ smoothed over ±7 samples; relative velocity u̇ − ẋ; segments start at the
// largest |u̇ − ẋ| of each half forcing period (mid-slide), end at the next start (≤ 1 period).
void prepareSegments(const IdentifyRun& r, size_t dec, const IdentifyOptions& opt, Prepared& p) {
    const size_t N = r.t_s.size();
    const double dt = (r.t_s.back() - r.t_s.front()) / static_cast<double>(N - 1);
    std::vector<double> u(N);
    for (size_t i = 0; i < N; ++i) u[i] = r.slip_m[i] + r.slider_m[i];
    std::vector<double> ud;
    if (r.frequency_Hz > 0) {
        const double w = 2.0 * M_PI * r.frequency_Hz;
        Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
        Eigen::Vector3d b = Eigen::Vector3d::Zero();
        for (size_t i = 0; i < N; ++i) {
            const Eigen::Vector3d phi(1.0, std::cos(w * r.t_s[i]), std::sin(w * r.t_s[i]));
            A += phi * phi.transpose();
            b += phi * u[i];
        }
        const Eigen::Vector3d c = A.ldlt().solve(b);
        double ss = 0;
        for (size_t i = 0; i < N; ++i) {
            const double e = u[i] - (c[0] + c[1] * std::cos(w * r.t_s[i]) + c[2] * std::sin(w * r.t_s[i]));
            ss += e * e;
        }
        const double amp = std::hypot(c[1], c[2]);
        if (amp > 0 && std::sqrt(ss / N) < 0.1 * amp) {
            p.stageHarmonic = true;
            p.uc0 = c[0]; p.ua = c[1]; p.ub = c[2]; p.omega = w;
        }
    }
    const std::vector<double> us = savitzkyGolay(u, dt, 7, 3, 0), usd = savitzkyGolay(u, dt, 7, 3, 1);
    const std::vector<double> xs = savitzkyGolay(r.slider_m, dt, 7, 3, 0), vs = savitzkyGolay(r.slider_m, dt, 7, 3, 1);
    double cum = 0, ssx = 0;
    for (size_t i = 0; i < N; ++i) {
        if (i > 0) cum += std::abs(r.slip_m[i] - r.slip_m[i - 1]);
        ssx += r.slider_m[i] * r.slider_m[i];
        if (i % dec) continue;
        const double tt = r.t_s[i];
        p.u.push_back(p.stageHarmonic ? p.stageAt(tt) : us[i]);
        const double uDot = p.stageHarmonic ? p.omega * (-p.ua * std::sin(p.omega * tt) + p.ub * std::cos(p.omega * tt)) : usd[i];
        p.xs.push_back(xs[i]);
        p.vs.push_back(vs[i]);
        p.Vs.push_back(uDot - vs[i]);
        p.cumSlip.push_back(cum);
    }
    p.invRmsX = ssx > 0 ? 1.0 / std::sqrt(ssx / N) : 1.0;
    const size_t n = p.size();
    if (n < 4) return;
    const double half = r.frequency_Hz > 0 ? 0.5 / r.frequency_Hz : 0.1;
    const double dts = p.t[1] - p.t[0];
    std::vector<size_t> starts;
    for (size_t i = 0; i < n;) {
        size_t j = i, bi = n;
        double best = 0;
        for (; j < n && p.t[j] < p.t[i] + half; ++j)
            if (std::abs(p.Vs[j]) > best) { best = std::abs(p.Vs[j]); bi = j; }
        if (bi < n && best >= 2.0 * opt.stickVelocity_mps) starts.push_back(bi);
        i = std::max(j, i + 1);
    }
    const size_t maxLen = static_cast<size_t>(std::ceil(2.0 * half / dts));
    std::vector<std::pair<size_t, size_t>> segs;
    for (size_t k = 0; k < starts.size(); ++k) {
        const size_t i0 = starts[k];
        size_t i1 = k + 1 < starts.size() ? starts[k + 1] : n - 1;
        i1 = std::min(i1, i0 + maxLen);
        if (i1 > i0 + 1) segs.push_back({i0, i1});
    }
    const size_t maxSeg = static_cast<size_t>(std::max(opt.maxSegmentsPerRun, 1));
    if (segs.size() > maxSeg) {
        std::vector<std::pair<size_t, size_t>> kept;
        for (size_t q = 0; q < maxSeg; ++q) kept.push_back(segs[(q * segs.size()) / maxSeg]);
        segs = std::move(kept);
    }
    p.segments = std::move(segs);
}

// Baseline start from the data: μ from the median |F|/t_N while sliding fast (|V| above half
// its peak), and the other coefficients of the starting law scaled with it (they are all
// "per unit normal load", so a device whose reference load is a band tension has them all
// large together).
std::map<std::string, double> baselineStart(const Context& cx, const std::vector<size_t>& fitIdx) {
    std::vector<double> ratio;
    for (size_t i : fitIdx) {
        const Prepared& p = cx.runs[i];
        double vmax = 0;
        for (double v : p.V) vmax = std::max(vmax, std::abs(v));
        for (size_t k = 0; k < p.size(); ++k)
            if (std::abs(p.V[k]) > 0.5 * vmax && p.run->normalForce_N > 0) ratio.push_back(std::abs(p.F[k]) / p.run->normalForce_N);
    }
    std::map<std::string, double> st;
    const RateStateParams& s0 = cx.opt->start;
    if (ratio.empty() || !(s0.mu > 0)) return st;
    std::nth_element(ratio.begin(), ratio.begin() + static_cast<long>(ratio.size() / 2), ratio.end());
    const double mu0 = ratio[ratio.size() / 2];
    if (!(mu0 > 0) || !std::isfinite(mu0)) return st;
    const double scale = mu0 / s0.mu;
    st["mu"] = mu0;
    st["C1"] = s0.C1 * scale;
    st["eta"] = s0.eta_s_per_m * scale;
    return st;
}

// The residual vector of a model over the runs idx (false if a run fails); `used` (optional)
// marks the entries a channel compares.
bool residualVector(const Context& cx, const Spec& spec, const std::map<std::string, double>& vals,
                    const std::vector<size_t>& idx, std::vector<double>& r, std::vector<NoiseBlock>* blocks = nullptr) {
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

// Central-difference Jacobian of the residual vector in the solver's coordinates (log for
// log-scaled parameters, the range for linear ones) at `vals`, for the free parameters whose
// names are in `which`; a column whose step would leave the bounds uses a one-sided step.
Eigen::MatrixXd residualJacobian(const Context& cx, const Spec& spec, const std::map<std::string, double>& vals,
                                 const std::vector<size_t>& idx, const std::vector<FitParameter>& params,
                                 const std::vector<std::string>& which, size_t rows) {
    Eigen::MatrixXd J(static_cast<Eigen::Index>(rows), static_cast<Eigen::Index>(which.size()));
    J.setZero();
    constexpr double h = 1e-4;
    for (size_t c = 0; c < which.size(); ++c) {
        const auto it = std::find_if(params.begin(), params.end(), [&](const FitParameter& p) { return p.name == which[c]; });
        if (it == params.end()) continue;
        const FitParameter& p = *it;
        const double v = vals.count(p.name) ? vals.at(p.name) : p.value;
        auto shifted = [&](double dz) {
            return p.scale == ParamScale::Log ? v * std::exp(dz) : v + dz * (p.upper - p.lower);
        };
        double up = h, dn = -h;
        if (shifted(up) > p.upper) up = 0.0;
        if (shifted(dn) < p.lower) dn = 0.0;
        if (up == dn) continue;
        std::map<std::string, double> a = vals, b = vals;
        a[p.name] = shifted(up);
        b[p.name] = shifted(dn);
        std::vector<double> ra, rb;
        if (!residualVector(cx, spec, a, idx, ra) || !residualVector(cx, spec, b, idx, rb) || ra.size() != rows ||
            rb.size() != rows)
            continue;
        for (size_t k = 0; k < rows; ++k) J(static_cast<Eigen::Index>(k), static_cast<Eigen::Index>(c)) = (ra[k] - rb[k]) / (up - dn);
    }
    return J;
}

// Sum of squared residuals of a model over the runs idx (inf if a run fails).
double evalSS(const Context& cx, const Spec& spec, const std::map<std::string, double>& vals, const std::vector<size_t>& idx) {
    double mass = kNaN;
    const ExtendedModel m = buildModel(cx, spec, vals, mass);
    std::vector<double> r;
    double tot = 0;
    for (size_t i : idx) {
        double ss = 0, n = 0;
        if (!runResiduals(cx, cx.runs[i], m, mass, r, ss, n, nullptr, nullptr, nullptr, spec.segments))
            return std::numeric_limits<double>::infinity();
        tot += ss;
    }
    return tot;
}

// Start values of an effect's parameters on top of `cur`: each log-scale parameter in turn
// is scanned over 9 log-spaced values across its bounds (and its default start), the others
// held, and the fit starts at the lowest cost. A gradient fit from one default start
// otherwise stops in the local minimum next to it (a 0.2 mm dead band from a 50 µm start).
std::map<std::string, double> scannedStart(const Context& cx, const Spec& s2, const std::string& effect,
                                           std::map<std::string, double> vals, const std::vector<size_t>& idx) {
    EffectInfo info;
    findEffect(effect, info);
    for (const EffectParam& q : info.params) vals[effect + "." + q.name] = q.initial;
    for (const EffectParam& q : info.params) {
        if (!q.logScale || !(q.lower > 0)) continue;
        const std::string key = effect + "." + q.name;
        double bestV = q.initial, bestC = evalSS(cx, s2, vals, idx);
        for (int k = 0; k < 9; ++k) {
            const double v = q.lower * std::pow(q.upper / q.lower, k / 8.0);
            vals[key] = v;
            const double c = evalSS(cx, s2, vals, idx);
            if (c < bestC) { bestC = c; bestV = v; }
        }
        vals[key] = bestV;
    }
    return vals;
}

// Penalised criterion with the effective number of independent residuals n_eff. The residual
// of a model that is slightly wrong repeats from one slip episode to the next, so samples
// within an episode are not independent: n_eff = min(n/τ_int, number of slip episodes).
double bic(double ss, double n, double neffCap, int p) {
    const double neff = std::max(std::min(n, neffCap), 2.0);
    return neff * std::log(std::max(ss, 1e-300) / std::max(n, 1.0)) + p * std::log(neff);
}

// The held-out and identifiability tests of the selection (tests 2 and 3 of the selection rule,
// IdentifyOptions in identify.hpp).
// `units`: the runs whose held-out errors are compared (leave-one-run-out: the fit runs;
// else the validation runs). Fills the candidate's test figures; false with sc.reason set
// when a test fails.
constexpr int kMinUnitsForTests = 3;  // runs needed for the paired test and the jackknife (≥ 2 degrees of freedom)

bool passesSelection(const Context& cx, CandidateScore& sc, const FitOutcome& fit, const ModelErrors& ref,
                     const ModelErrors& with, const std::vector<std::map<std::string, double>>& loo,
                     const std::vector<size_t>& units, double tauInt) {
    const IdentifyOptions& opt = *cx.opt;
    // (2) Held-out error, pooled and paired over runs.
    if (std::isfinite(ref.validationNrmse) && std::isfinite(with.validationNrmse) &&
        !(with.validationNrmse < ref.validationNrmse)) {
        sc.reason = "lowers the fit error (dBIC " + std::to_string(sc.deltaBic) + ") but not the held-out error (" +
                    std::to_string(with.validationNrmse) + " vs " + std::to_string(ref.validationNrmse) + ")";
        return false;
    }
    std::vector<double> b, a;
    for (size_t i : units) {
        if (i >= ref.runs.size() || i >= with.runs.size()) continue;
        b.push_back(ref.runs[i].heldOutNrmse * ref.runs[i].heldOutNrmse);
        a.push_back(with.runs[i].heldOutNrmse * with.runs[i].heldOutNrmse);
    }
    const PairedTest pt = pairedLogRatioTest(b, a);
    sc.heldOutUnits = pt.units;
    sc.heldOutMeanLogRatio = pt.meanLogRatio;
    sc.heldOutT = pt.t;
    sc.heldOutP = pt.pValue;
    // With fewer than 3 held-out runs the paired t-test has at most one degree of freedom (the
    // spread of two log ratios; t_{0.95,1} = 6.31) and no power: every held-out run must then
    // improve instead (a weaker guard, reported as such).
    if (pt.units < kMinUnitsForTests) {
        sc.heldOutP = kNaN;
        for (size_t k = 0; k < b.size(); ++k)
            if (b[k] > 0 && a[k] > 0 && !(a[k] < b[k])) {
                sc.reason = "held-out error lower pooled but not in every one of the " + std::to_string(pt.units) +
                            " held-out runs (too few runs for a paired test)";
                return false;
            }
    } else if (!(pt.pValue < opt.heldOutAlpha)) {
        sc.reason = "held-out error lower pooled (" + std::to_string(with.validationNrmse) + " vs " +
                    std::to_string(ref.validationNrmse) + ") but not consistently over the " + std::to_string(pt.units) +
                    " held-out runs: paired t = " + std::to_string(pt.t) + ", one-sided p = " + std::to_string(pt.pValue) +
                    " >= " + std::to_string(opt.heldOutAlpha) + " (mean log MSE ratio " + std::to_string(pt.meanLogRatio) + ")";
        return false;
    }
    // (3) The size parameter differs from the value at which the effect vanishes by more than
    // t_{K−1, 1−α/2} jackknife standard errors over the leave-one-run-out fits.
    EffectInfo info;
    findEffect(sc.name, info);
    if (info.params.empty()) return true;
    const EffectParam& q = info.params.front();
    const std::string key = sc.name + "." + q.name;
    const bool inverse = std::isinf(q.vanishing);  // e.g. a stiffness: test its compliance 1/k
    const double none = sc.name == "viscous_damping" && cx.anyDynamics ? ViscousDamping::kBaselineMax
                                                                        : (inverse ? 0.0 : q.vanishing);
    auto size = [&](double v) { return inverse ? 1.0 / v : v; };
    const double value = fit.values.count(key) ? size(fit.values.at(key)) : kNaN;
    std::vector<double> jk;
    for (const auto& m : loo)
        if (m.count(key)) jk.push_back(size(m.at(key)));
    double se = kNaN, crit = kNaN;
    if (jk.size() >= static_cast<size_t>(kMinUnitsForTests)) {
        se = jackknifeStderr(jk);
        crit = studentTQuantile(1.0 - 0.5 * opt.identifiabilityAlpha, static_cast<double>(jk.size()) - 1.0);
        sc.sizeStderrKind = "jackknife over " + std::to_string(jk.size()) + " leave-one-run-out fits";
    } else {
        // Fewer than 3 leave-one-run-out fits (validation runs given, or 2 runs): the Jacobian
        // standard error made honest for autocorrelated residuals (× sqrt(τ_int)), normal quantile.
        double jse = kNaN;
        for (const ParamEstimate& p : fit.estimates)
            if (p.name == key) jse = p.stderr_;
        if (std::isfinite(jse) && inverse && fit.values.count(key)) jse /= fit.values.at(key) * fit.values.at(key);
        se = jse * std::sqrt(std::max(tauInt, 1.0));
        crit = studentTQuantile(1.0 - 0.5 * opt.identifiabilityAlpha, 1e9);
        sc.sizeStderrKind = "Jacobian x sqrt(tau_int)";
    }
    sc.sizeParam = inverse ? "1/" + q.name : q.name;
    sc.sizeValue = value;
    sc.sizeNull = none;
    sc.sizeStderr = se;
    sc.sizeCritical = crit;
    if (std::isfinite(value) && std::isfinite(se) && !(std::abs(value - none) > crit * se)) {
        sc.reason = "lowers the fit and held-out errors but its size " + sc.sizeParam + " = " + std::to_string(value) +
                    " is not identified: |value - " + std::to_string(none) + "| <= " + std::to_string(crit) + " x " +
                    std::to_string(se) + " (" + sc.sizeStderrKind + ")";
        return false;
    }
    return true;
}

}  // namespace

IdentifyResult identifyEffects(std::vector<IdentifyRun> runs, const IdentifyOptions& opt) {
    const auto t0 = Clock::now();
    IdentifyResult res;
    auto progress = [&](const std::string& s, double f) { if (opt.progress) opt.progress(s, f); };
    if (runs.empty()) { res.message = "no runs"; return res; }
    Context cx;
    cx.opt = &opt;
    // Slip accumulated before each run, in the order given (runs recorded on one specimen).
    double slip = 0, tNsum = 0;
    for (IdentifyRun& r : runs) {
        if (r.t_s.size() < 10 || r.force_N.size() != r.t_s.size() || r.slip_m.size() != r.t_s.size() ||
            r.relVel_mps.size() != r.t_s.size()) {
            res.message = r.file + ": run needs >= 10 samples of time, slip, velocity and force of equal length";
            return res;
        }
        if (r.setup == SetupKind::Dynamics &&
            (r.slider_m.size() != r.t_s.size() || r.sliderVel_mps.size() != r.t_s.size() || r.accel_mps2.size() != r.t_s.size())) {
            res.message = r.file + ": dynamics run needs slider displacement, velocity and acceleration";
            return res;
        }
        r.slipBefore_m = slip;
        for (size_t i = 1; i < r.slip_m.size(); ++i) slip += std::abs(r.slip_m[i] - r.slip_m[i - 1]);
        tNsum += r.normalForce_N;
        if (r.setup == SetupKind::Dynamics) cx.anyDynamics = true;
    }
    res.setup = cx.anyDynamics ? "dynamics" : "prescribed";
    cx.tNref = tNsum / runs.size();
    size_t dec = static_cast<size_t>(std::max(opt.decimate, 0));
    if (dec == 0) {
        const IdentifyRun& r0 = runs.front();
        const double fs = 1.0 / ((r0.t_s.back() - r0.t_s.front()) / (r0.t_s.size() - 1));
        double fmax = 0;
        for (const IdentifyRun& r : runs) fmax = std::max(fmax, r.frequency_Hz);
        // Dynamics: 500 Hz, so that the cleaning filters (60 Hz band-stop, 100 Hz low-pass) can
        // be applied to the prediction well below the decimated Nyquist frequency and the law's
        // steps resolve slip onsets: at 250 Hz the error of the prediction's own resolution was
        // systematic enough for a sensor mass of 5.7 g to absorb it on D05 (gain 0.50 against
        // 0.004 of the noise null; at 500 Hz the gain is gone, ΔBIC +4.6).
        const double target = cx.anyDynamics ? 500.0 : 128.0 * (fmax > 0 ? fmax : 1.0);
        dec = static_cast<size_t>(std::max(1.0, std::floor(fs / target)));
    }
    res.decimation = static_cast<int>(dec);
    for (const IdentifyRun& r : runs) {
        Prepared p;
        p.run = &r;
        double ss = 0;
        for (double f : r.force_N) ss += f * f;
        p.invRmsF = ss > 0 ? 1.0 / std::sqrt(ss / r.force_N.size()) : 1.0;
        for (size_t i = 0; i < r.t_s.size(); i += dec) {
            p.t.push_back(r.t_s[i]);
            p.g.push_back(r.slip_m[i]);
            p.V.push_back(r.relVel_mps[i]);
            p.F.push_back(r.force_N[i]);
            if (!r.accel_mps2.empty()) p.a.push_back(r.accel_mps2[i]);
            if (r.setup == SetupKind::Dynamics) {
                p.x.push_back(r.slider_m[i]);
                p.xd.push_back(r.sliderVel_mps[i]);
            }
        }
        if (r.filtered && p.size() > 16) {
            // The cleaning filters redesigned at the decimated rate; one whose band reaches the
            // new Nyquist frequency is left out (the decimated samples cannot carry its effect).
            const double fsDec = 1.0 / (p.t[1] - p.t[0]), ny = 0.45 * fsDec;
            const FilterSettings& fs = r.filters;
            if (fs.bandStop && fs.bandStopCenter_Hz + 0.5 * fs.bandStopWidth_Hz < ny) {
                const Sos bs = butterworthBandstop(fs.bandStopOrder, fs.bandStopCenter_Hz - 0.5 * fs.bandStopWidth_Hz,
                                                   fs.bandStopCenter_Hz + 0.5 * fs.bandStopWidth_Hz, fsDec);
                p.predictionFilter.insert(p.predictionFilter.end(), bs.begin(), bs.end());
            }
            if (fs.lowPass && fs.lowPass_Hz < ny) {
                const Sos lp = butterworthLowpass(fs.lowPassOrder, fs.lowPass_Hz, fsDec);
                p.predictionFilter.insert(p.predictionFilter.end(), lp.begin(), lp.end());
            }
        }
        if (r.setup == SetupKind::Dynamics) prepareSegments(r, dec, opt, p);
        cx.runs.push_back(std::move(p));
    }
    std::vector<size_t> fitIdx, valIdx;
    for (size_t i = 0; i < runs.size(); ++i) (runs[i].validation ? valIdx : fitIdx).push_back(i);
    if (fitIdx.empty()) { res.message = "every run is a validation run: nothing to fit"; return res; }

    std::vector<std::string> cands = opt.candidates;
    if (cands.empty())
        for (const EffectInfo& e : effectCatalogue()) cands.push_back(e.name);
    for (const std::string& c : cands) {
        EffectInfo info;
        if (!findEffect(c, info)) { res.message = "unknown effect '" + c + "'"; return res; }
    }

    // Slip episodes in the fit runs (the independent units of the penalised criterion).
    double episodes = 0;
    for (size_t i : fitIdx) {
        double last = 0;
        episodes += 1;
        for (double v : cx.runs[i].V) {
            if (std::abs(v) < opt.stickVelocity_mps) continue;
            const double sg = v > 0 ? 1 : -1;
            if (last != 0 && sg != last) episodes += 1;
            last = sg;
        }
    }
    res.slipEpisodes = episodes;
    res.heldOutAlpha = opt.heldOutAlpha;
    res.nullAlpha = opt.nullAlpha;
    res.nullReplicas = opt.nullReplicas;
    res.bicMargin = opt.bicMargin;
    res.identifiabilityAlpha = opt.identifiabilityAlpha;
    if (!(opt.nullAlpha > 0 && opt.nullAlpha < 1) || opt.nullReplicas < 0 || opt.nullReplicas > 100000) {
        res.message = "nullAlpha = " + std::to_string(opt.nullAlpha) + " must be in (0, 1) and nullReplicas = " +
                      std::to_string(opt.nullReplicas) + " in [0, 100000]";
        return res;
    }
    if (!(opt.heldOutAlpha > 0 && opt.heldOutAlpha < 1) || !(opt.identifiabilityAlpha > 0 && opt.identifiabilityAlpha < 1)) {
        res.message = "heldOutAlpha = " + std::to_string(opt.heldOutAlpha) + ", identifiabilityAlpha = " +
                      std::to_string(opt.identifiabilityAlpha) + ": both must be in (0, 1)";
        return res;
    }
    // Baseline.
    progress("baseline", 0.0);
    Spec spec;
    spec.segments = cx.anyDynamics && opt.dynamicsResidual == DynamicsResidual::Segments;
    std::map<std::string, double> start = baselineStart(cx, fitIdx);
    if (cx.anyDynamics) start["m"] = runs[fitIdx[0]].nominalMass_kg;
    FitOutcome cur = fitSpec(cx, spec, start, fitIdx, opt.multistarts, res.fits, true);
    if (!cur.ok) {
        res.cancelled = opt.cancel && opt.cancel->load();
        res.message = "baseline fit failed: " + cur.message;
        return res;
    }
    res.baseline = cur.estimates;
    res.before = errorsOf(cx, spec, cur, fitIdx, valIdx, res.fits);
    std::vector<std::vector<double>> predBefore;
    res.diagnosticsBefore = diagnoseModel(cx, spec, cur, &predBefore);
    Diagnostics curDiag = res.diagnosticsBefore;
    res.tauInt = curDiag.integratedAcfTime;
    double curHeldOut = res.before.validationNrmse;
    ModelErrors curErrors = res.before;
    // Segments: the independent units are the segments (each one reversal, stick and breakaway).
    double segEpisodes = 0;
    for (size_t i : fitIdx) segEpisodes += static_cast<double>(cx.runs[i].segments.size());
    res.segmentsUsed = segEpisodes;
    auto bicOf = [&](const FitOutcome& f, const Spec& s, double tauInt) {
        const double cap = std::min(f.count / std::max(tauInt, 1.0), s.segments ? std::max(segEpisodes, 2.0) : episodes);
        return bic(f.ss, f.count, cap, f.nFree);
    };
    auto residualName = [&](const Spec& s) {
        return !cx.anyDynamics ? std::string("prescribed") : s.segments ? std::string("segments") : std::string("equation_error");
    };
    res.residual = residualName(spec);

    std::map<std::string, CandidateScore> scores;
    for (int round = 1; round <= opt.maxEffects; ++round) {
        if (opt.cancel && opt.cancel->load()) { res.cancelled = true; break; }
        const double bicCur = bicOf(cur, spec, curDiag.integratedAcfTime);
        // Auto: the current model refitted with the segment residual, for the stick-phase
        // candidates (lazily, once per round).
        Spec segSpec = spec;
        segSpec.segments = true;
        FitOutcome segBase;
        bool segBaseTried = false;
        auto segBaseline = [&]() -> const FitOutcome& {
            if (!segBaseTried) {
                segBaseTried = true;
                progress("round " + std::to_string(round) + ": baseline with the segment residual", 0.0);
                segBase = fitSpec(cx, segSpec, cur.values, fitIdx, 1, res.fits);
            }
            return segBase;
        };
        struct Tried {
            CandidateScore sc;
            FitOutcome fit;
            Spec spec;
        };
        std::vector<Tried> tried;
        size_t k = 0;
        for (const std::string& c : cands) {
            ++k;
            if (std::find(spec.effects.begin(), spec.effects.end(), c) != spec.effects.end()) continue;
            if (opt.cancel && opt.cancel->load()) break;
            progress("round " + std::to_string(round) + ": " + c, (k - 1.0) / cands.size());
            CandidateScore sc;
            sc.name = c;
            sc.round = round;
            Spec s2 = spec;
            s2.effects.push_back(c);
            const FitOutcome* base = &cur;
            double bicBase = bicCur;
            if (cx.anyDynamics && !spec.segments && actsInStick(c) && opt.dynamicsResidual == DynamicsResidual::Auto) {
                const FitOutcome& sb = segBaseline();
                if (!sb.ok) {
                    sc.reason = "baseline fit with the segment residual failed: " + sb.message;
                    scores[c] = sc;
                    continue;
                }
                s2.segments = true;
                base = &sb;
                bicBase = bicOf(sb, segSpec, 1.0);
            }
            sc.residual = residualName(s2);
            const auto st = scannedStart(cx, s2, c, base->values, fitIdx);
            const FitOutcome f = fitSpec(cx, s2, st, fitIdx, 1, res.fits);
            if (!f.ok) {
                sc.reason = "fit failed: " + f.message;
                scores[c] = sc;
                continue;
            }
            sc.deltaBic = bicOf(f, s2, s2.segments == spec.segments ? curDiag.integratedAcfTime : 1.0) - bicBase;
            sc.fitNrmse = f.count > 0 ? std::sqrt(f.ss / f.count) : 0.0;
            for (const ParamEstimate& p : f.estimates)
                if (p.name.rfind(c + ".", 0) == 0) sc.params.push_back({p.name.substr(c.size() + 1), p.value, p.stderr_});
            // An effect whose size parameter (the first in its catalogue entry) ends on a physical
            // bound has not been identified (the fit wants it outside the physical range, or the
            // effect has vanished): the improvement it brings is not evidence for this effect.
            // (Time constants and distances of the other parameters may rightly sit on a bound:
            // "faster than the data resolve".)
            {
                EffectInfo info;
                findEffect(c, info);
                std::string atBound;
                for (const EffectParam& q : std::vector<EffectParam>(info.params.begin(), info.params.begin() + 1)) {
                    const double v = f.values.count(c + "." + q.name) ? f.values.at(c + "." + q.name) : q.initial;
                    const bool lo = q.logScale ? v <= q.lower * 1.01 : v <= q.lower + 1e-3 * (q.upper - q.lower);
                    const bool hi = q.logScale ? v >= q.upper / 1.01 : v >= q.upper - 1e-3 * (q.upper - q.lower);
                    if ((lo && q.lower != 0.0) || hi) atBound = q.name;
                }
                if (!atBound.empty()) {
                    sc.reason = "parameter " + atBound + " ended on its physical bound: not identified (dBIC " +
                                std::to_string(sc.deltaBic) + " not credited)";
                    scores[c] = sc;
                    continue;
                }
            }
            tried.push_back({sc, f, s2});
        }
        if (tried.empty()) break;
        std::sort(tried.begin(), tried.end(), [](const auto& a, const auto& b) { return a.sc.deltaBic < b.sc.deltaBic; });
        // Selection (the rule at IdentifyOptions in identify.hpp): in order of ΔBIC, the first candidate
        // that passes all three tests is added; the others are reported with the test they failed.
        int chosen = -1;
        ModelErrors me, segBaseErrors;
        bool segBaseErrorsDone = false;
        double heldOutRef = curHeldOut;
        for (size_t ti = 0; ti < tried.size(); ++ti) {
            CandidateScore& sc = tried[ti].sc;
            if (!(sc.deltaBic < -opt.bicMargin)) {
                sc.reason = std::string(ti == 0 ? "best candidate of round " + std::to_string(round) + " but " : "") + "dBIC = " +
                            std::to_string(sc.deltaBic) + " is not below -" + std::to_string(opt.bicMargin) +
                            ": improvement within what noise explains";
                continue;
            }
            if (chosen >= 0) {
                sc.reason = "dBIC = " + std::to_string(sc.deltaBic) + " but " + tried[chosen].sc.name + " was added in round " +
                            std::to_string(round);
                continue;
            }
            // (1b) The gain against what noise alone gives on these runs (noise_null.hpp).
            if (opt.nullReplicas > 0) {
                progress("round " + std::to_string(round) + ": noise null of " + sc.name, 1.0);
                const Spec& cs = tried[ti].spec;
                const FitOutcome& base = (cs.segments != spec.segments) ? segBase : cur;
                std::vector<double> r0;
                std::vector<NoiseBlock> blocks;
                const std::vector<FitParameter> ps = parameters(cx, cs, tried[ti].fit.values);
                std::vector<std::string> baseNames, effNames;
                for (const FitParameter& fp : ps) {
                    if (!fp.free) continue;
                    (fp.name.rfind(sc.name + ".", 0) == 0 ? effNames : baseNames).push_back(fp.name);
                }
                if (residualVector(cx, cs.segments != spec.segments ? segSpec : spec, base.values, fitIdx, r0, &blocks)) {
                    const Eigen::MatrixXd J0 = residualJacobian(cx, cs, tried[ti].fit.values, fitIdx, ps, baseNames, r0.size());
                    const Eigen::MatrixXd Jc = residualJacobian(cx, cs, tried[ti].fit.values, fitIdx, ps, effNames, r0.size());
                    const NullGains ng = projectionGainNull(J0, Jc, blocks, opt.nullReplicas, opt.seed + 7919u * round);
                    sc.gain = base.ss - tried[ti].fit.ss;
                    sc.nullGain = ng.quantile(1.0 - opt.nullAlpha);
                    sc.nullReplicas = static_cast<int>(ng.gains.size());
                    if (!(sc.gain > sc.nullGain)) {
                        sc.reason = "gain in the sum of squares " + std::to_string(sc.gain) + " is within the " +
                                    std::to_string(100.0 * (1.0 - opt.nullAlpha)) + " % quantile of " +
                                    std::to_string(sc.nullReplicas) + " noise replicas of these runs (" +
                                    std::to_string(sc.nullGain) + "): noise alone gives as much";
                        continue;
                    }
                }
            }
            const bool sw = tried[ti].spec.segments != spec.segments;
            const ModelErrors* ref = &curErrors;
            if (sw) {
                if (!segBaseErrorsDone) {
                    progress("round " + std::to_string(round) + ": held-out check of the segment baseline", 1.0);
                    segBaseErrors = errorsOf(cx, segSpec, segBase, fitIdx, valIdx, res.fits);
                    segBaseErrorsDone = true;
                }
                ref = &segBaseErrors;
            }
            progress("round " + std::to_string(round) + ": held-out check of " + sc.name, 1.0);
            std::vector<std::map<std::string, double>> loo;
            ModelErrors e = errorsOf(cx, tried[ti].spec, tried[ti].fit, fitIdx, valIdx, res.fits, &loo);
            sc.heldOutNrmse = e.validationNrmse;
            if (!passesSelection(cx, sc, tried[ti].fit, *ref, e, loo, valIdx.empty() ? fitIdx : valIdx,
                                 curDiag.integratedAcfTime))
                continue;
            chosen = static_cast<int>(ti);
            me = std::move(e);
            heldOutRef = ref->validationNrmse;
        }
        for (const Tried& t : tried) scores[t.sc.name] = t.sc;
        if (chosen < 0) break;
        CandidateScore& best = tried[chosen].sc;
        const FitOutcome& bestFit = tried[chosen].fit;
        const Spec s2 = tried[chosen].spec;
        const bool switching = s2.segments != spec.segments;
        best.accepted = true;
        scores[best.name] = best;
        if (switching) {
            // From here on the model is scored with the segment residual: "before" is the
            // baseline under that residual, so before and after compare like with like.
            res.before = segBaseErrors;
            predBefore.clear();
            res.diagnosticsBefore = diagnoseModel(cx, segSpec, segBase, &predBefore);
            curDiag = res.diagnosticsBefore;
            res.residual = "segments";
        }
        AddedEffect ae;
        ae.name = best.name;
        ae.params = best.params;
        ae.deltaBic = best.deltaBic;
        ae.heldOutBefore = heldOutRef;
        ae.heldOutAfter = me.validationNrmse;
        EffectInfo info;
        findEffect(best.name, info);
        for (const std::string& sname : info.pointers)
            for (const SignalCorrelation& c : curDiag.correlations)
                if (c.signal == sname) ae.pointedBy.push_back(c);
        res.effectsAdded.push_back(ae);
        spec = s2;
        cur = bestFit;
        curHeldOut = me.validationNrmse;
        res.after = me;
        curErrors = me;
        curDiag = diagnoseModel(cx, spec, cur, nullptr);
    }
    for (const std::string& c : cands)
        if (scores.count(c)) res.candidates.push_back(scores[c]);
    if (res.effectsAdded.empty()) res.after = res.before;
    // Final parameters (effect parameters kept under "effect.param" names).
    res.final = cur.estimates;
    std::vector<std::vector<double>> predAfter;
    res.diagnosticsAfter = diagnoseModel(cx, spec, cur, &predAfter);
    res.unexplained = res.diagnosticsAfter.whiteness.structured;
    if (res.unexplained) {
        const auto& cs = res.diagnosticsAfter.correlations;
        auto top = std::max_element(cs.begin(), cs.end(), [](const auto& a, const auto& b) {
            return std::abs(a.correlation) < std::abs(b.correlation);
        });
        res.unexplainedReason = "residual is not white after the loop (Ljung-Box p = " +
                                std::to_string(res.diagnosticsAfter.whiteness.pValue) + ") and the structure is large (variance / "
                                "successive-difference noise variance - 1 = " +
                                std::to_string(res.diagnosticsAfter.whiteness.structureRatio) + "); largest correlation: " +
                                (top != cs.end() ? top->signal + " r = " + std::to_string(top->correlation) : "none") +
                                "; no catalogue candidate lowered the penalised and held-out error further";
    }
    for (size_t i = 0; i < cx.runs.size(); ++i) {
        const Prepared& p = cx.runs[i];
        RunTrace t;
        t.file = p.run->file;
        t.t_s = p.t;
        t.relVel_mps = p.V;
        t.measured_N = p.F;
        t.before_N = predBefore[i];
        t.after_N = predAfter[i];
        t.used.assign(p.size(), 1);
        for (size_t k = 0; k < p.size(); ++k) t.used[k] = std::isfinite(t.before_N[k]) && std::isfinite(t.after_N[k]);
        res.traces.push_back(std::move(t));
    }
    res.ok = true;
    res.cancelled = res.cancelled || (opt.cancel && opt.cancel->load());
    res.wallTime_s = std::chrono::duration<double>(Clock::now() - t0).count();
    progress("done", 1.0);
    return res;
}

namespace {

nlohmann::json num(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

nlohmann::json toJson(const std::vector<ParamEstimate>& ps) {
    nlohmann::json j = nlohmann::json::object();
    for (const ParamEstimate& p : ps) j[p.name] = {{"value", num(p.value)}, {"stderr", num(p.stderr_)}};
    return j;
}

nlohmann::json toJson(const ModelErrors& e) {
    nlohmann::json runs = nlohmann::json::array();
    for (const RunError& r : e.runs)
        runs.push_back({{"file", r.file}, {"role", r.role}, {"rms_N", num(r.rms_N)}, {"nrmse", num(r.nrmse)},
                        {"held_out_nrmse", num(r.heldOutNrmse)}});
    return {{"fit_nrmse", num(e.fitNrmse)}, {"validation_nrmse", num(e.validationNrmse)}, {"runs", runs}};
}

}  // namespace

nlohmann::json toJson(const Diagnostics& d, bool withSeries) {
    nlohmann::json corr = nlohmann::json::object();
    for (const SignalCorrelation& c : d.correlations) corr[c.signal] = num(c.correlation);
    nlohmann::json j = {{"rms", num(d.rms)},
                        {"correlations", corr},
                        {"whiteness",
                         {{"test", "Ljung-Box"},
                          {"lags", d.whiteness.lags},
                          {"decimation", d.whiteness.decimation},
                          {"Q", num(d.whiteness.ljungBoxQ)},
                          {"p_value", num(d.whiteness.pValue)},
                          {"white", d.whiteness.white},
                          {"structure_ratio", num(d.whiteness.structureRatio)},
                          {"structure_ratio_limit", Whiteness::kStructureRatioLimit},
                          {"structured", d.whiteness.structured}}},
                        {"integrated_acf_time_samples", num(d.integratedAcfTime)},
                        {"spectrum_harmonic_fraction", num(d.spectrum.harmonicFraction)},
                        {"forcing_harmonics_Hz", d.spectrum.harmonics_Hz}};
    if (withSeries) {
        j["acf"] = d.whiteness.acf;
        // Spectrum up to 150 Hz (the measurement bandwidth).
        nlohmann::json f = nlohmann::json::array(), p = nlohmann::json::array();
        for (size_t k = 0; k < d.spectrum.frequency_Hz.size() && d.spectrum.frequency_Hz[k] <= 150.0; ++k) {
            f.push_back(d.spectrum.frequency_Hz[k]);
            p.push_back(d.spectrum.power[k]);
        }
        j["spectrum"] = {{"frequency_Hz", f}, {"power", p}};
    }
    return j;
}

nlohmann::json toJson(const IdentifyResult& r) {
    nlohmann::json j;
    j["ok"] = r.ok;
    if (!r.message.empty()) j["message"] = r.message;
    j["setup"] = r.setup;
    j["baseline"] = {{"model", "rate-state"}, {"parameters", toJson(r.baseline)}};
    j["before"] = toJson(r.before);
    j["after"] = toJson(r.after);
    j["final_parameters"] = toJson(r.final);
    nlohmann::json added = nlohmann::json::array();
    for (const AddedEffect& e : r.effectsAdded) {
        nlohmann::json pointed = nlohmann::json::object();
        for (const SignalCorrelation& c : e.pointedBy) pointed[c.signal] = num(c.correlation);
        added.push_back({{"name", e.name},
                         {"parameters", toJson(e.params)},
                         {"diagnostics", {{"correlations_before", pointed}}},
                         {"delta_bic", num(e.deltaBic)},
                         {"held_out_nrmse_before", num(e.heldOutBefore)},
                         {"held_out_nrmse_after", num(e.heldOutAfter)}});
    }
    j["effects_added"] = added;
    nlohmann::json cands = nlohmann::json::array();
    for (const CandidateScore& c : r.candidates)
        cands.push_back({{"name", c.name},
                         {"round", c.round},
                         {"applicable", c.applicable},
                         {"accepted", c.accepted},
                         {"score", {{"delta_bic", num(c.deltaBic)}, {"fit_nrmse", num(c.fitNrmse)},
                                    {"held_out_nrmse", c.heldOutNrmse >= 0 ? num(c.heldOutNrmse) : nlohmann::json(nullptr)}}},
                         {"residual", c.residual},
                         {"held_out_test", c.heldOutUnits == 0 ? nlohmann::json(nullptr)
                                                               : nlohmann::json{{"runs", c.heldOutUnits},
                                                                                {"mean_log_mse_ratio", num(c.heldOutMeanLogRatio)},
                                                                                {"t", num(c.heldOutT)},
                                                                                {"p_one_sided", num(c.heldOutP)}}},
                         {"noise_null", c.nullReplicas == 0 ? nlohmann::json(nullptr)
                                                            : nlohmann::json{{"gain", num(c.gain)},
                                                                             {"null_quantile", num(c.nullGain)},
                                                                             {"replicas", c.nullReplicas}}},
                         {"size_test", c.sizeParam.empty() ? nlohmann::json(nullptr)
                                                           : nlohmann::json{{"parameter", c.sizeParam},
                                                                            {"value", num(c.sizeValue)},
                                                                            {"vanishes_at", num(c.sizeNull)},
                                                                            {"stderr", num(c.sizeStderr)},
                                                                            {"stderr_kind", c.sizeStderrKind},
                                                                            {"critical_t", num(c.sizeCritical)}}},
                         {"parameters", toJson(c.params)},
                         {"rejected_because", c.accepted ? nlohmann::json(nullptr) : nlohmann::json(c.reason)}});
    j["candidates"] = cands;
    j["diagnostics"] = {{"before", toJson(r.diagnosticsBefore, true)}, {"after", toJson(r.diagnosticsAfter, true)}};
    j["unexplained"] = r.unexplained;
    if (r.unexplained) j["unexplained_reason"] = r.unexplainedReason;
    j["selection"] = {{"criterion", "BIC with n_eff = min(n / tau_int, slip episodes); an effect must lower it by more than "
                                    "the margin AND lower the sum of squares by more than the (1 - null_alpha) quantile of "
                                    "what noise replicas of these runs give (AR(1) per run and channel from the current "
                                    "residual, linearised candidate model) AND lower the held-out NRMSE (leave-one-run-out, or the --validate-on runs) "
                                    "consistently over the held-out runs (one-sided paired t-test on ln MSE ratios, p < alpha) "
                                    "AND its size parameter must differ from its vanishing value by more than t_(K-1,1-alpha/2) "
                                    "jackknife standard errors over the leave-one-run-out fits"},
                      {"null_alpha", num(r.nullAlpha)}, {"null_replicas", r.nullReplicas}, {"bic_margin", num(r.bicMargin)},
                      {"held_out_alpha", num(r.heldOutAlpha)}, {"identifiability_alpha", num(r.identifiabilityAlpha)},
                      {"tau_int_samples", num(r.tauInt)},
                      {"slip_episodes", r.slipEpisodes}, {"decimation", r.decimation},
                      {"residual", r.residual}, {"segments", r.segmentsUsed}};
    j["wall_time_s"] = r.wallTime_s;
    j["fits"] = r.fits;
    return j;
}

}  // namespace stickslip::identify
