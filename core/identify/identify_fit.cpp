// Fitting a model of the loop (baseline or with candidates) on the prepared runs and the
// diagnostics of its residual (its held-out errors: held_out_errors.cpp).
#include <algorithm>
#include <atomic>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <numeric>
#include <thread>

#include "../dsp/stats.hpp"
#include "../integrate/dynamics.hpp"
#include "curve_coordinates.hpp"
#include "identify_internal.hpp"

namespace stickslip::identify::detail {

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
        FitParameter p;
        defaultParameter("m", SetupKind::Dynamics, p);
        auto it = start.find("m");
        if (it != start.end()) p.value = std::clamp(it->second, p.lower, p.upper);
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
        for (const EffectParam& q0 : info.params) {
            const EffectParam q = scaledParam(q0, cx.muScale);
            FitParameter p{e + "." + q.name, q.initial, q.lower, q.upper, true, q.logScale ? ParamScale::Log : ParamScale::Linear};
            auto it = start.find(p.name);
            if (it != start.end()) p.value = it->second;
            // A fitted value on a log-scaled bound comes back as exp(log(bound)), which may lie an
            // ulp outside it; the engine would then refuse the warm start (D16: every
            // leave-one-run-out refit of stick_healing failed on D_h = 0.01).
            p.value = std::clamp(p.value, p.lower, p.upper);
            ps.push_back(p);
        }
    }
    return ps;
}

std::map<std::string, double> withoutEffect(const Context& cx, const Spec& without, const std::string& e,
                                            std::map<std::string, double> vals) {
    EffectInfo info;
    findEffect(e, info);
    for (const EffectParam& q : info.params) {
        const auto it = vals.find(e + "." + q.name);
        if (it == vals.end()) continue;
        const double v = it->second;
        vals.erase(it);
        if (!q.continues) continue;
        for (const FitParameter& p : parameters(cx, without, vals))
            if (p.name == q.continues) vals[p.name] = std::clamp(v, p.lower, p.upper);
    }
    return vals;
}

// The baseline's scans: the contact stiffness and the state distance set where the force turns
// after a reversal and how fast it settles; their costs have narrow valleys a local solver does
// not leave, so each is scanned on a log grid over its physical bounds first (fit.hpp).
static std::vector<ParameterScan> stiffnessScans(const std::vector<FitParameter>& params) {
    std::vector<ParameterScan> scans;
    for (const FitParameter& fp : params) {
        if (!fp.free || (fp.name != "epsT" && fp.name != "Dc")) continue;
        const double lo = fp.name == "epsT" ? std::max(fp.lower, 1e3) : std::max(fp.lower, 1e-7);
        const double hi = fp.name == "epsT" ? std::min(fp.upper, 1e8) : std::min(fp.upper, 1e-2);
        const int nGrid = fp.name == "epsT" ? 26 : 11;
        ParameterScan sc{fp.name, {}};
        for (int k = 0; k < nGrid; ++k) sc.values.push_back(lo * std::pow(hi / lo, k / (nGrid - 1.0)));
        scans.push_back(sc);
    }
    // A second pass: the first D_c scan runs at the start's ε_T, which may be far off (it is the
    // scan after it that finds ε_T), and the two set the same feature of the force (how it turns
    // after a reversal), so D_c's best value depends on ε_T. One pass left the baseline in a
    // minimum with D_c in millimetres, C1 → 0 and η on its bound on two of 35 sets (docs/
    // identify-results.md, session 46); the second pass costs 37 residual evaluations.
    const size_t firstPass = scans.size();
    for (size_t i = 0; i < firstPass; ++i) scans.push_back(scans[i]);
    return scans;
}

// The law's values of a point in the solver's coordinates; false outside C1's or η's bounds
// (the box in κ, s, v_c is not the box in C1, η, v_c).
using LawValues = std::function<bool(const std::vector<double>&, std::map<std::string, double>&)>;

// The 2p points of a numeric Jacobian as (point, run) tasks over the cores; each task writes
// its own slice, so the result does not depend on the scheduling.
static BatchResidualFunction batchResiduals(const Context& cx, const Spec& spec, const std::vector<size_t>& idx,
                                                  const std::vector<std::string>& names, const LawValues& lawValues) {
    std::vector<size_t> offsets;
    {
        size_t o = 0;
        for (size_t i : idx) {
            offsets.push_back(o);
            o += cx.runs[i].size() * (cx.runs[i].run->setup == SetupKind::Dynamics ? 2 : 1);
        }
    }
    return [&cx = cx, &spec = spec, &idx = idx, names, offsets, lawValues](const std::vector<std::vector<double>>& points,
                                                                         std::vector<std::vector<double>>& rs,
                                                                         std::vector<char>& okOut) {
        const size_t nRuns = idx.size(), nTasks = points.size() * nRuns;
        std::vector<ExtendedModel> models(points.size());
        std::vector<double> masses(points.size(), kNaN);
        std::vector<char> inBounds(points.size(), 1);
        for (size_t pt = 0; pt < points.size(); ++pt) {
            std::map<std::string, double> vals;
            inBounds[pt] = lawValues(points[pt], vals) ? 1 : 0;
            models[pt] = buildModel(cx, spec, vals, masses[pt]);
        }
        rs.resize(points.size());
        // Points that differ only in parameters the law run along the measured slip does not see
        // (the Jacobian columns of m, ζ, a sensor's dashpot or mass) share one law run per run:
        // the law runs first, one task per distinct law and run, then every point's residuals.
        std::vector<size_t> lawOf(points.size()), distinct;
        if (!spec.segments)
            for (size_t pt = 0; pt < points.size(); ++pt) {
                lawOf[pt] = pt;
                for (size_t q : distinct) {
                    bool same = true;
                    for (size_t i = 0; i < names.size() && same; ++i)
                        same = !(lawParameter(names[i]) || CurveCoordinates::isCoordinate(names[i])) ||
                               points[q][i] == points[pt][i];
                    if (same) { lawOf[pt] = q; break; }
                }
                if (lawOf[pt] == pt) distinct.push_back(pt);
            }
        std::vector<LawRun> laws(spec.segments ? 0 : points.size() * nRuns);
        std::vector<char> lawOk(laws.size(), 0);
        parallelFor(distinct.size() * nRuns, [&](size_t t) {
            const size_t pt = distinct[t / nRuns], k = t % nRuns;
            if (!inBounds[pt]) return;
            lawOk[pt * nRuns + k] = simulateLawRun(cx, cx.runs[idx[k]], models[pt], laws[pt * nRuns + k]) ? 1 : 0;
        });
        std::vector<char> ok(nTasks, 0);
        parallelFor(nTasks, [&](size_t t) {
            const size_t pt = t / nRuns, k = t % nRuns;
            if (!inBounds[pt]) return;
            const LawRun* law = nullptr;
            if (!spec.segments) {
                const size_t l = lawOf[pt] * nRuns + k;
                if (!lawOk[l]) return;
                law = &laws[l];
            }
            std::vector<double> r;
            double ss = 0, n = 0;
            if (!runResiduals(cx, cx.runs[idx[k]], models[pt], masses[pt], r, ss, n, nullptr, nullptr, nullptr, spec.segments,
                              law))
                return;
            std::copy(r.begin(), r.end(), rs[pt].begin() + static_cast<long>(offsets[k]));
            ok[t] = 1;
        });
        okOut.assign(points.size(), 1);
        for (size_t t = 0; t < nTasks; ++t)
            if (!ok[t]) okOut[t / nRuns] = 0;
    };
}

// The solver's Jacobian from forward sensitivities (analyticResidualJacobian), in the problem's
// parameters: in the steady-state curve's coordinates the law's C1 and η are functions of κ, s
// and v_c (curve_coordinates.hpp), whose derivatives are differenced here (no model run).
static JacobianFunction analyticJacobian(const Context& cx, const Spec& spec, const std::vector<size_t>& idx,
                                         const std::vector<FitParameter>& params, const CurveCoordinates& curve) {
    std::vector<std::string> names;
    std::vector<char> free;
    for (const FitParameter& p : params) names.push_back(p.name), free.push_back(p.free ? 1 : 0);
    return [&cx, &spec, &idx, names, free, curve](const std::vector<double>& pv, std::vector<double>& jac) {
        auto lawAt = [&](const std::vector<double>& v) {
            std::map<std::string, double> vals;
            for (size_t i = 0; i < names.size(); ++i) vals[names[i]] = v[i];
            if (curve.active()) curve.toLaw(v, vals);
            return vals;
        };
        const std::map<std::string, double> vals = lawAt(pv);
        if (curve.active() && !curve.withinLawBounds(vals)) return false;
        // T(k, j) = ∂ law value k / ∂ problem parameter j, over the free parameters.
        std::vector<std::string> lawNames;
        std::map<std::string, std::vector<double>> T;
        for (size_t j = 0; j < names.size(); ++j) {
            if (!free[j]) continue;
            if (!curve.active()) {
                T[names[j]].assign(names.size(), 0.0);
                T[names[j]][j] = 1.0;
                continue;
            }
            std::vector<double> up = pv, dn = pv;
            const double h = 1e-6 * std::max(std::abs(pv[j]), 1e-12);
            up[j] += h;
            dn[j] -= h;
            const std::map<std::string, double> a = lawAt(up), b = lawAt(dn);
            for (const auto& [k, v] : a) {
                if (CurveCoordinates::isCoordinate(k)) continue;
                const double d = (v - b.at(k)) / (2 * h);
                if (d != 0.0) T[k].resize(names.size(), 0.0), T[k][j] = d;
            }
        }
        for (const auto& [k, row] : T) lawNames.push_back(k);
        Eigen::MatrixXd J;
        if (!analyticResidualJacobian(cx, spec, vals, idx, lawNames, J)) return false;
        const size_t P = names.size(), m = static_cast<size_t>(J.rows());
        jac.assign(m * P, 0.0);
        for (size_t c = 0; c < lawNames.size(); ++c) {
            const std::vector<double>& row = T.at(lawNames[c]);
            for (size_t j = 0; j < P; ++j) {
                if (row[j] == 0.0) continue;
                for (size_t i = 0; i < m; ++i) jac[i * P + j] += J(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(c)) * row[j];
            }
        }
        return true;
    };
}

// The outcome of a finished fit: its values and estimates in the law's coordinates and, for
// FitOutput::Full, its residual sum of squares over the fitted runs.
static FitOutcome outcomeOf(const Context& cx, const Spec& spec, const std::vector<size_t>& idx, FitResult fit,
                            const CurveCoordinates& curve, FitOutput output) {
    FitOutcome out;
    out.fit = std::move(fit);
    if (curve.active()) curve.restore(out.fit);
    out.ok = true;
    for (size_t i = 0; i < out.fit.names.size(); ++i) {
        out.values[out.fit.names[i]] = out.fit.values[i];
        if (out.fit.free[i]) {
            out.estimates.push_back({out.fit.names[i], out.fit.values[i], out.fit.stderrs[i]});
            ++out.nFree;
        }
    }
    if (output == FitOutput::ValuesOnly) {
        out.ss = kNaN;
        return out;
    }
    double mass = kNaN;
    const ExtendedModel m = buildModel(cx, spec, out.values, mass);
    std::vector<double> r;
    residualsOver(cx, spec, idx, m, mass, r, out.ss, out.count);
    return out;
}

FitOutcome fitSpecOnce(const Context& cx, const Spec& spec, const std::map<std::string, double>& start,
                            const std::vector<size_t>& idx, int multistarts, long& fits, bool scanStiffness, FitStart from,
                            FitOutput output, double retryTolerance, bool curveAllowed, bool& usedCurve) {
    FitProblem prob;
    prob.parameters = parameters(cx, spec, start);
    // Baseline: scans of ε_T and D_c first (stiffnessScans).
    if (scanStiffness) prob.scans = stiffnessScans(prob.parameters);
    // Warm-started fits move in the steady-state curve's coordinates (κ = C1/v_c², s = η −
    // C1/v_c; curve_coordinates.hpp), as `fit --setup dynamics` does: in C1, η, v_c the cost has
    // a long curved valley along which the solver crawls to its iteration cap. In both set-ups:
    // the valley is the steady-state curve's, whichever way the slip is imposed (the damper's
    // leave-one-run-out refits reached the cap 26 times in 48 in C1, η, v_c; 11 in κ, s, v_c).
    // Only from a start CurveCoordinates::startInside accepts (its header says why).
    CurveCoordinates curve;
    if (curveAllowed && !scanStiffness && CurveCoordinates::startInside(prob.parameters))
        curve = CurveCoordinates::install(prob.parameters, prob.scans);
    usedCurve = curve.active();
    prob.residualCount = residualCount(cx, idx);
    prob.multistarts = multistarts;
    prob.seed = cx.opt->seed;
    prob.cancel = cx.opt->cancel;
    // Warm-started refits (a candidate on top of the current model, a leave-one-run-out fit)
    // start next to their optimum: 20 iterations. The cost tolerance 1e-6 is far below what the
    // selection resolves in a fit's cost (the noise null's quantile is ~1e-4 of it on the
    // synthetic sets), but not below what a left-out run changes (~1e-7 of it): a leave-one-run-out
    // refit may stop before its first step (IdentifyOptions::looFunctionTolerance).
    prob.maxIterations = scanStiffness ? 40 : 20;
    prob.functionTolerance = retryTolerance > 0 ? retryTolerance
                             : from == FitStart::NearOptimum ? cx.opt->looFunctionTolerance
                                                             : 1e-6;
    prob.parameterTolerance = retryTolerance > 0 ? retryTolerance : 1e-6;
    prob.maxLineSearchSteps = cx.opt->lineSearchSteps;
    prob.jacobian = cx.opt->forwardJacobian && from == FitStart::Far ? JacobianKind::Forward : JacobianKind::Central;
    prob.uncertainty = output == FitOutput::Full;
    const auto names = [&] {
        std::vector<std::string> v;
        for (const auto& p : prob.parameters) v.push_back(p.name);
        return v;
    }();
    // Counted from batchResiduals' threads; `prob` and with it every copy of the lambda lives
    // only until fitLeastSquares returns below.
    std::atomic<long> outside{0};
    const LawValues lawValues = [names, curve, &outside](const std::vector<double>& pv, std::map<std::string, double>& vals) {
        vals.clear();
        for (size_t i = 0; i < names.size(); ++i) vals[names[i]] = pv[i];
        if (!curve.active()) return true;
        curve.toLaw(pv, vals);
        if (curve.withinLawBounds(vals)) return true;
        outside.fetch_add(1, std::memory_order_relaxed);
        return false;
    };
    prob.residuals = [&cx, &spec, &idx, lawValues](const std::vector<double>& pv, std::vector<double>& r) {
        std::map<std::string, double> vals;
        if (!lawValues(pv, vals)) return false;
        double mass = kNaN, ss = 0, n = 0;
        const ExtendedModel m = buildModel(cx, spec, vals, mass);
        return residualsOver(cx, spec, idx, m, mass, r, ss, n);
    };
    prob.batchResiduals = batchResiduals(cx, spec, idx, names, lawValues);
    if (cx.opt->analyticJacobian && !spec.segments) prob.analyticJacobian = analyticJacobian(cx, spec, idx, prob.parameters, curve);
    ++fits;
    FitResult fit = fitLeastSquares(prob);
    FitOutcome out;
    if (!fit.ok()) {
        out.message = fit.message;
        out.fit = std::move(fit);
    } else {
        out = outcomeOf(cx, spec, idx, std::move(fit), curve, output);
    }
    out.outsideLawBounds = outside.load();
    return out;
}

FitOutcome fitSpec(const Context& cx, const Spec& spec, const std::map<std::string, double>& start,
                   const std::vector<size_t>& idx, int multistarts, long& fits, bool scanStiffness, FitStart from,
                   FitOutput output, double retryTolerance) {
    bool usedCurve = false;
    FitOutcome out = fitSpecOnce(cx, spec, start, idx, multistarts, fits, scanStiffness, from, output, retryTolerance,
                               cx.opt->curveCoordinates, usedCurve);
    if (!usedCurve || cx.cancelled()) return out;
    // A fit in the curve coordinates that fails (its optimum in a corner where a box bound of
    // v_c meets a bound of C1 or η, which is not a box bound there: no side of a difference can
    // be evaluated; the damper's 30 lb runs, backlash) is done again in C1, η, v_c from the
    // same start, where such a corner is a box corner.
    if (!out.ok) {
        FitOutcome law = fitSpecOnce(cx, spec, start, idx, multistarts, fits, scanStiffness, from, output, retryTolerance,
                                     false, usedCurve);
        FitOutcome& kept = law.ok ? law : out;
        kept.lawPasses = 1;
        return kept;
    }
    // So is one that never left its start next to such a corner: every difference step crosses
    // the bound and no step is taken (a synthesized set with a load effect, C1 1e-5 below its
    // bound: the baseline's refit and all nine candidates ended at the start, normal_load_mu
    // missed at held-out NRMSE 0.134; docs/identify-results.md, session 39). A fit that never
    // left its start without asking for a point outside those bounds started at a stationary
    // point, where C1, η, v_c find the same (session 51: 15 such refits on D13 and D05, every
    // one at the same sum of squares).
    if (neverMoved(out) && out.outsideLawBounds > 0) {
        FitOutcome law = continueInLawCoordinates(cx, spec, out, idx, fits, from, output, retryTolerance);
        FitOutcome& kept = lawFitIsBetter(out, law) ? law : out;
        kept.lawPasses = 1;
        return kept;
    }
    return out;
}

FitOutcome continueInLawCoordinates(const Context& cx, const Spec& spec, const FitOutcome& curveFit,
                                    const std::vector<size_t>& idx, long& fits, FitStart from, FitOutput output,
                                    double retryTolerance) {
    bool usedCurve = false;
    FitOutcome law = fitSpecOnce(cx, spec, curveFit.values, idx, 1, fits, false, from, output, retryTolerance, false,
                                 usedCurve);
    if (law.ok) law.fit.initialCost = curveFit.fit.initialCost;  // where the whole fit began, for neverMoved
    return law;
}

bool lawFitIsBetter(const FitOutcome& curveFit, const FitOutcome& lawFit) {
    return lawFit.ok && (!curveFit.ok || lawFit.fit.cost < curveFit.fit.cost);
}

bool neverMoved(const FitOutcome& f) { return f.ok && !(f.fit.cost < f.fit.initialCost * (1.0 - 1e-12)); }

// Diagnostics of a fitted model's force residual (friction channel, samples compared).
Diagnostics diagnoseModel(const Context& cx, const Spec& spec, const FitOutcome& f, std::vector<std::vector<double>>* preds,
                          StructureCheck structure) {
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
    Diagnostics d = diagnose(dr, dec, cx.opt->stickVelocity_mps, structure);
    if (cx.anyDynamics) {
        // Equation-of-motion channel: its residual against the slider velocity and acceleration
        // (where rig damping and sensor inertia show).
        std::vector<double> rr, xd, xa;
        std::vector<StructureRun> eom;
        const double zeta = m.effects.viscousDamping ? m.effects.viscousDamping->zeta : cx.opt->zetaNominal;
        const double ms = m.effects.sensorInertia ? m.effects.sensorInertia->mass_kg : 0.0;
        for (const Prepared& p : cx.runs) {
            if (p.run->setup != SetupKind::Dynamics) continue;
            const double mm = std::isfinite(mass) ? mass : p.run->nominalMass_kg;
            const double c = 2.0 * zeta * std::sqrt(p.run->stiffness_N_per_m * mm);
            StructureRun run{{}, {p.xd, p.a}};
            for (size_t i = 0; i < p.size(); ++i)
                run.residual.push_back(p.F[i] - ((mm + ms) * p.a[i] + c * p.xd[i] + p.run->stiffness_N_per_m * p.x[i]));
            rr.insert(rr.end(), run.residual.begin(), run.residual.end());
            xd.insert(xd.end(), p.xd.begin(), p.xd.end());
            xa.insert(xa.end(), p.a.begin(), p.a.end());
            eom.push_back(std::move(run));
        }
        d.correlations.push_back({"eom_slider_velocity", pearson(rr, xd)});
        d.correlations.push_back({"eom_slider_accel", pearson(rr, xa)});
        if (structure == StructureCheck::Run) d.structureEom = residualStructure(eom, {"eom_slider_velocity", "eom_slider_accel"});
    }
    return d;
}

// Baseline start from the data: μ from the median |F|/t_N while sliding fast (|V| above half
// its peak), and the other coefficients of the starting law scaled with it (they are all
// "per unit normal load", so a device whose reference load is a band tension has them all
// large together).
std::map<std::string, double> baselineStart(const Context& cx, const std::vector<size_t>& fitIdx, const RateStateParams* from) {
    std::vector<double> ratio;
    for (size_t i : fitIdx) {
        const Prepared& p = cx.runs[i];
        double vmax = 0;
        for (double v : p.V) vmax = std::max(vmax, std::abs(v));
        for (size_t k = 0; k < p.size(); ++k)
            if (std::abs(p.V[k]) > 0.5 * vmax && p.run->normalForce_N > 0) ratio.push_back(std::abs(p.F[k]) / p.run->normalForce_N);
    }
    std::map<std::string, double> st;
    const RateStateParams& s0 = from ? *from : cx.opt->start;
    if (from)
        for (const std::string& n : cx.opt->freeLaw)
            if (const double v = lawValue(s0, n); std::isfinite(v)) st[n] = v;
    if (ratio.empty() || !(s0.mu > 0)) return st;
    const double mu0 = dsp::median(std::move(ratio));
    if (!(mu0 > 0) || !std::isfinite(mu0)) return st;
    const double scale = mu0 / s0.mu;
    st["mu"] = mu0;
    st["C1"] = s0.C1 * scale;
    st["eta"] = s0.eta_s_per_m * scale;
    return st;
}

std::string sizeBound(const Context& cx, const std::string& e, const std::map<std::string, double>& vals) {
    EffectInfo info;
    if (!findEffect(e, info) || info.params.empty()) return {};
    const EffectParam q = scaledParam(info.params.front(), cx.muScale);
    const auto it = vals.find(e + "." + q.name);
    const double v = it != vals.end() ? it->second : q.initial;
    const bool lo = q.logScale ? v <= q.lower * 1.01 : v <= q.lower + 1e-3 * (q.upper - q.lower);
    const bool hi = q.logScale ? v >= q.upper / 1.01 : v >= q.upper - 1e-3 * (q.upper - q.lower);
    if (hi) return "upper";
    if (lo && q.lower != 0.0) return "lower";
    return {};
}

std::map<std::string, double> retryStart(const Context& cx, const std::string& e, std::map<std::string, double> vals,
                                         const std::map<std::string, double>& scanned, const std::string& boundSide) {
    EffectInfo info;
    findEffect(e, info);
    for (const EffectParam& q0 : info.params) {
        const std::string key = e + "." + q0.name;
        if (scanned.count(key)) vals[key] = scanned.at(key);
    }
    if (info.params.empty()) return vals;
    const EffectParam q = scaledParam(info.params.front(), cx.muScale);
    const std::string key = e + "." + q.name;
    // Where the effect vanishes, inside the physical range (a stiffness: its upper bound).
    const double none = std::isinf(q.vanishing) ? q.upper : std::clamp(effectVanishes(cx, e, q), q.lower, q.upper);
    if (boundSide.empty()) {
        vals[key] = none;
        return vals;
    }
    const double b = boundSide == "upper" ? q.upper : q.lower;
    vals[key] = q.logScale ? std::sqrt(std::max(none, q.lower) * b) : 0.5 * (none + b);
    return vals;
}

// Start values of an effect's parameters on top of `cur`: each log-scale parameter in turn
// is scanned over 9 log-spaced values across its bounds (and its default start), the others
// held, and the fit starts at the lowest cost. A gradient fit from one default start
// otherwise stops in the local minimum next to it (a 0.2 mm dead band from a 50 µm start).
// The scan is joint with each free baseline contact parameter (D_c and ε_T, 11 log values each,
// and their current values): the baseline has already used them to mimic what the effect does
// — on D03 a state distance of 133 µm stood in for a 7 ms lag, and the lag scanned at that D_c
// ended on its lower bound — so the effect alone, from the baseline's point, finds nothing.
std::map<std::string, double> effectStart(const Context& cx, const std::string& effect, std::map<std::string, double> vals) {
    EffectInfo info;
    findEffect(effect, info);
    for (const EffectParam& q : info.params) {
        const auto from = q.continues ? vals.find(q.continues) : vals.end();
        vals[effect + "." + q.name] = from != vals.end() ? from->second : scaledParam(q, cx.muScale).initial;
    }
    return vals;
}

std::map<std::string, double> scannedStart(const Context& cx, const Spec& s2, const std::string& effect,
                                           std::map<std::string, double> vals, const std::vector<size_t>& idx,
                                           const std::map<std::string, double>* previous) {
    EffectInfo info;
    findEffect(effect, info);
    vals = effectStart(cx, effect, std::move(vals));
    const std::vector<FitParameter> ps = parameters(cx, s2, vals);
    double atVals = kNaN;  // the full sum of squares at vals, as the last scan computed it
    for (const EffectParam& q0 : info.params) {
        const EffectParam q = scaledParam(q0, cx.muScale);
        if (!q.logScale || !(q.lower > 0)) continue;
        const std::string key = effect + "." + q.name;
        // Points: (effect value, partner, partner value); partner "" = effect alone.
        struct Point { double v; std::string partner; double pv; };
        std::vector<Point> pts = {{vals[key], "", 0.0}};
        std::vector<double> grid;
        for (int k = 0; k < 9; ++k) grid.push_back(q.lower * std::pow(q.upper / q.lower, k / 8.0));
        for (double v : grid) pts.push_back({v, "", 0.0});
        for (const FitParameter& fp : ps) {
            if (!fp.free || (fp.name != "Dc" && fp.name != "epsT")) continue;
            const double lo = fp.name == "epsT" ? std::max(fp.lower, 1e3) : std::max(fp.lower, 1e-7);
            const double hi = fp.name == "epsT" ? std::min(fp.upper, 1e8) : std::min(fp.upper, 1e-2);
            for (int j = 0; j < 11; ++j)
                for (double v : grid) pts.push_back({v, fp.name, lo * std::pow(hi / lo, j / 10.0)});
        }
        std::vector<std::map<std::string, double>> points(pts.size(), vals);
        for (size_t k = 0; k < pts.size(); ++k) {
            points[k][key] = pts[k].v;
            if (!pts[k].partner.empty()) points[k][pts[k].partner] = pts[k].pv;
        }
        // The lowest wins (ties: the first, i.e. the current point); none evaluable: the current.
        std::vector<double> sums;
        const int lowest = lowestSS(cx, s2, points, idx, std::numeric_limits<double>::infinity(), &sums);
        const size_t best = static_cast<size_t>(std::max(0, lowest));
        atVals = lowest >= 0 ? sums[best] : kNaN;
        vals[key] = pts[best].v;
        if (!pts[best].partner.empty()) vals[pts[best].partner] = pts[best].pv;
    }
    if (!previous) return vals;
    // The earlier fit only when strictly lower (ties: the scanned point). The scan already has
    // the scanned point's sum; without a scan (no log-scaled parameter) both are evaluated.
    if (std::isfinite(atVals)) return lowestSS(cx, s2, {*previous}, idx, atVals) == 0 ? *previous : vals;
    return lowestSS(cx, s2, {vals, *previous}, idx) == 1 ? *previous : vals;
}

}  // namespace stickslip::identify::detail
