// Dataset-level fitting on top of the generic engine (fit.hpp). No Ceres here.
//
// Residuals: for each fit run and each scored sample i,
//   prescribed:  r = (F_pred − F_meas) / RMS(F_meas of the run)
//   dynamics:    r = (x_pred − x_meas) / RMS(x_meas),  r' = (F_pred − F_meas) / RMS(F_meas)
// so runs and channels of different size weigh alike and the standard errors (which use the
// residual variance at the optimum) do not depend on units.
#include <algorithm>
#include <atomic>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <string>
#include <thread>

#include "../dsp/stats.hpp"
#include "../friction/friction_law.hpp"
#include "curve_coordinates.hpp"
#include "fit.hpp"
#include "identify.hpp"

namespace stickslip::identify {

using io::Signal;

namespace {

// False only for a friction-law key the law does not have (the rig's keys belong to every law).
bool lawHas(LawKind law, const std::string& name) {
    const ParamDef* d = findParam(name);
    return !d || d->group != ParamGroup::FrictionLaw || lawHasParam(law, name);
}

double rmsOf(const std::vector<double>& v, const std::vector<size_t>& idx) {
    double s = 0;
    for (size_t i : idx) s += v[i] * v[i];
    return idx.empty() ? 0.0 : std::sqrt(s / static_cast<double>(idx.size()));
}

// μ start from the data: median |F|/t_N over samples sliding faster than half the peak speed.
double estimateMu(const CleanRun& c) {
    const io::Run& r = c.run;
    double tN = 0;
    if (!r.has(Signal::Friction) || !r.has(Signal::RelVel) || !r.setting("tN", tN) || !(tN > 0)) return -1;
    double vmax = 0;
    for (size_t i = c.begin; i < c.end; ++i) vmax = std::max(vmax, std::abs(r[Signal::RelVel][i]));
    std::vector<double> ratio;
    for (size_t i = c.begin; i < c.end; ++i)
        if (std::abs(r[Signal::RelVel][i]) > 0.5 * vmax) ratio.push_back(std::abs(r[Signal::Friction][i]) / tN);
    if (ratio.empty()) return -1;
    return dsp::median(std::move(ratio));
}

}  // namespace

RunScore scoreRun(const CleanRun& run, SetupKind setup, const ModelSpec& model, const PredictSettings& ps,
                  const std::string& role, Prediction* out) {
    RunScore sc;
    sc.file = run.run.file;
    sc.role = role;
    Prediction p = predictRun(run, setup, model, ps);
    if (!p.ok) {
        sc.message = p.message;
        sc.nrmse = sc.nrmseForce = std::numeric_limits<double>::quiet_NaN();
        if (out) *out = p;
        return sc;
    }
    const std::vector<double>& F = run.run[Signal::Friction];
    double eF = 0, mF = 0, eX = 0, mX = 0;
    for (size_t k = 0; k < p.index.size(); ++k) {
        const size_t i = p.index[k];
        eF += (p.force_N[k] - F[i]) * (p.force_N[k] - F[i]);
        mF += F[i] * F[i];
        if (setup == SetupKind::Dynamics) {
            const double x = run.run[Signal::SliderDisp][i];
            eX += (p.slider_m[k] - x) * (p.slider_m[k] - x);
            mX += x * x;
        }
    }
    const double n = static_cast<double>(p.index.size());
    sc.samples = p.index.size();
    sc.rms_N = std::sqrt(eF / n);
    sc.nrmseForce = mF > 0 ? std::sqrt(eF / mF) : std::numeric_limits<double>::quiet_NaN();
    if (setup == SetupKind::Dynamics) {
        sc.rms_m = std::sqrt(eX / n);
        sc.nrmseDisp = mX > 0 ? std::sqrt(eX / mX) : std::numeric_limits<double>::quiet_NaN();
        sc.nrmse = std::sqrt(0.5 * (sc.nrmseForce * sc.nrmseForce + sc.nrmseDisp * sc.nrmseDisp));
    } else {
        sc.nrmse = sc.nrmseForce;
    }
    sc.ok = true;
    if (out) *out = std::move(p);
    return sc;
}

std::pair<CleanRun, CleanRun> splitByTime(const CleanRun& run, double fraction) {
    CleanRun a = run, b = run;
    const size_t mid = run.begin + static_cast<size_t>(std::floor(fraction * static_cast<double>(run.end - run.begin)));
    a.end = mid;
    b.begin = mid;
    a.notes.push_back("time split: fit part");
    b.notes.push_back("time split: validation part");
    return {a, b};
}

std::string holdOutLaterParts(std::vector<CleanRun>& fitRuns, std::vector<CleanRun>& validationRuns, double fraction) {
    if (!(fraction > 0.0 && fraction < 1.0)) return "the time split must be in (0, 1)";
    std::vector<CleanRun> earlier;
    for (const CleanRun& c : fitRuns) {
        auto [a, b] = splitByTime(c, fraction);
        earlier.push_back(std::move(a));
        b.run.file += "#later";
        validationRuns.push_back(std::move(b));
    }
    fitRuns = std::move(earlier);
    return {};
}

namespace {

// The free parameters (those the law has) with their default bounds; `dropped`: the free names
// the law does not have. False with `error` for an unknown name.
bool freeParameters(const DatasetFitSettings& st, FitProblem& prob, std::vector<std::string>& dropped, std::string& error) {
    for (const std::string& name : st.free) {
        if (!lawHas(st.law, name)) { dropped.push_back(name); continue; }
        FitParameter fp;
        if (name == "zeta") fp = FitParameter{"zeta", 0.005, 1e-5, 1.0, true, ParamScale::Log};
        else if (!defaultParameter(name, st.setup, fp)) {
            error = "unknown free parameter '" + name + "' (known: " + fitParamKeys() + " zeta)";
            return false;
        }
        prob.parameters.push_back(fp);
    }
    return true;
}

// μ and C1 start at the median over the runs of estimateMu.
void startMuFromData(const std::vector<CleanRun>& fitRuns, FitProblem& prob) {
    std::vector<double> mus;
    for (const CleanRun& c : fitRuns) {
        const double m = estimateMu(c);
        if (m > 0) mus.push_back(m);
    }
    if (mus.empty()) return;
    std::sort(mus.begin(), mus.end());
    for (FitParameter& fp : prob.parameters)
        if (fp.name == "mu" || fp.name == "C1") fp.value = std::clamp(mus[mus.size() / 2], fp.lower, fp.upper);
}

// Starting values of the free sliding-law parameters and m* from the equation-error fit
// (identify.hpp; DatasetFitSettings::equationErrorStart). Returns the note for the solver
// summary: what was started where, or why the start was not used.
std::string equationErrorStart(const std::vector<CleanRun>& fitRuns, const DatasetFitSettings& st, FitProblem& prob) {
    std::vector<IdentifyRun> idRuns;
    std::string why;
    for (const CleanRun& c : fitRuns) {
        IdentifyRun ir;
        if (!makeIdentifyRun(c, SetupKind::Dynamics, ir, &why)) return "equation-error start not used: " + why;  // why names the file
        idRuns.push_back(std::move(ir));
    }
    auto isFree = [&](const char* n) {
        return std::any_of(prob.parameters.begin(), prob.parameters.end(), [&](const FitParameter& fp) { return fp.name == n; });
    };
    IdentifyOptions eo;
    eo.maxEffects = 0;
    eo.multistarts = 1;
    eo.freeLaw.clear();
    for (const char* n : {"mu", "C1", "eta", "vc"})
        if (isFree(n)) eo.freeLaw.push_back(n);
    eo.fitMass = isFree("m");
    eo.cancel = st.cancel;
    if (eo.freeLaw.empty() && !eo.fitMass) return {};
    const IdentifyResult ee = identifyEffects(idRuns, eo);
    if (!ee.ok) return "equation-error start not used: " + ee.message;
    std::string note;
    for (const ParamEstimate& pe : ee.baseline)
        for (FitParameter& fp : prob.parameters)
            if (fp.name == pe.name && std::isfinite(pe.value)) {
                fp.value = std::clamp(pe.value, fp.lower, fp.upper);
                note += (note.empty() ? "" : ", ") + pe.name + " " + std::to_string(fp.value);
            }
    return "equation-error start: " + note;
}

// DatasetFitSettings::start: a free parameter starts there; any other (that the law has) is
// passed as fixed, its bounds widened to hold the value.
void applyStart(const DatasetFitSettings& st, FitProblem& prob) {
    for (const auto& [name, v] : st.start) {
        if (!lawHas(st.law, name)) continue;
        bool found = false;
        for (FitParameter& fp : prob.parameters)
            if (fp.name == name) { fp.value = std::clamp(v, fp.lower, fp.upper); found = true; }
        if (!found) {
            FitParameter fp;
            if (!defaultParameter(name, st.setup, fp)) fp = FitParameter{name, v, v - 1.0, v + 1.0, false, ParamScale::Linear};
            fp.value = v;
            fp.lower = std::min(fp.lower, v);
            fp.upper = std::max(fp.upper, v);
            fp.free = false;
            prob.parameters.push_back(fp);
        }
    }
}

using SpecFor = std::function<ModelSpec(const std::vector<double>&)>;

// Where each run's residuals sit: its scored samples (from one prediction at the start; they
// do not depend on the parameters), its normalisations and its block's offset.
struct ResidualLayout {
    std::vector<std::vector<size_t>> index;
    std::vector<double> normF, normX;
    std::vector<size_t> offset;
    size_t count = 0;
    size_t channels = 1;  // 2 in the dynamics set-up: force and displacement interleaved
};

// False with `error` when a run cannot be simulated at the start.
bool layoutResiduals(const std::vector<CleanRun>& fitRuns, const DatasetFitSettings& st, const SpecFor& specFor,
                     FitProblem& prob, ResidualLayout& L, std::string& error) {
    std::vector<double> startVals;
    for (const FitParameter& fp : prob.parameters) startVals.push_back(fp.value);
    L.channels = st.setup == SetupKind::Dynamics ? 2 : 1;
    for (const CleanRun& c : fitRuns) {
        Prediction p = predictRun(c, st.setup, specFor(startVals), st.predict);
        if (!p.ok) {
            error = "cannot simulate at the starting values: " + p.message;
            return false;
        }
        L.normF.push_back(std::max(rmsOf(c.run[Signal::Friction], p.index), 1e-12));
        L.normX.push_back(st.setup == SetupKind::Dynamics ? std::max(rmsOf(c.run[Signal::SliderDisp], p.index), 1e-15) : 1.0);
        L.count += p.index.size() * L.channels;
        prob.profiledParameters += p.nuisanceParameters;
        L.index.push_back(p.index);
    }
    prob.residualCount = L.count;
    // Offset of each run's block in the residual vector, so that runs can be filled in any order.
    L.offset.assign(fitRuns.size(), 0);
    for (size_t k = 1; k < fitRuns.size(); ++k) L.offset[k] = L.offset[k - 1] + L.index[k - 1].size() * L.channels;
    return true;
}

// The problem's residual callbacks. Runs are independent, and so are the points of a numeric
// Jacobian: every (point, run) pair is one task, handed out to the workers in turn (each writes
// only its own block of its point's residual vector), so the numbers do not depend on the
// thread count. Everything captured must outlive the fit.
void installResiduals(FitProblem& prob, const std::vector<CleanRun>& fitRuns, const DatasetFitSettings& st,
                      const ResidualLayout& L, const SpecFor& specFor, const CurveCoordinates& curve) {
    const size_t threads = st.threads > 0 ? static_cast<size_t>(st.threads)
                                          : std::max<size_t>(1, std::thread::hardware_concurrency());
    prob.batchResiduals = [&fitRuns, &st, &L, &specFor, &curve, threads](const std::vector<std::vector<double>>& points,
                                                                       std::vector<std::vector<double>>& rs,
                                                                       std::vector<char>& okOut) {
        const size_t nRuns = fitRuns.size(), nTasks = points.size() * nRuns;
        std::vector<ModelSpec> specs;
        for (const std::vector<double>& v : points) specs.push_back(specFor(v));
        rs.resize(points.size());
        for (std::vector<double>& r : rs) r.assign(L.count, 0.0);
        std::vector<char> ok(nTasks, 0);
        std::vector<char> inBounds(points.size(), 1);
        for (size_t pt = 0; pt < points.size(); ++pt)
            if (curve.active()) inBounds[pt] = curve.withinLawBounds(specs[pt].values) ? 1 : 0;
        std::atomic<size_t> next{0};
        auto work = [&]() {
            for (size_t t = next.fetch_add(1); t < nTasks; t = next.fetch_add(1)) {
                const size_t pt = t / nRuns, k = t % nRuns;
                if (!inBounds[pt]) continue;
                // Cancelled: the remaining tasks of the batch fail at once instead of each
                // predicting a whole run (the cancel latency of a dynamics fit).
                if (cancelRequested(st.cancel)) continue;
                const Prediction p = predictRun(fitRuns[k], st.setup, specs[pt], st.predict);
                if (!p.ok || p.index.size() != L.index[k].size()) continue;
                const std::vector<double>& F = fitRuns[k].run[Signal::Friction];
                std::vector<double>& r = rs[pt];
                size_t o = L.offset[k];
                for (size_t j = 0; j < p.index.size(); ++j) {
                    r[o++] = (p.force_N[j] - F[p.index[j]]) / L.normF[k];
                    if (st.setup == SetupKind::Dynamics)
                        r[o++] = (p.slider_m[j] - fitRuns[k].run[Signal::SliderDisp][p.index[j]]) / L.normX[k];
                }
                ok[t] = 1;
            }
        };
        const size_t workers = std::min(threads, nTasks);
        if (workers <= 1) {
            work();
        } else {
            std::vector<std::thread> pool;
            for (size_t w = 1; w < workers; ++w) pool.emplace_back(work);
            work();
            for (std::thread& th : pool) th.join();
        }
        okOut.assign(points.size(), 0);
        for (size_t pt = 0; pt < points.size(); ++pt)
            okOut[pt] = std::all_of(ok.begin() + static_cast<long>(pt * nRuns), ok.begin() + static_cast<long>((pt + 1) * nRuns),
                                    [](char c) { return c != 0; });
    };
    prob.residuals = [&prob, &L](const std::vector<double>& vals, std::vector<double>& r) {
        std::vector<std::vector<double>> rs(1);
        std::vector<char> ok;
        prob.batchResiduals({vals}, rs, ok);
        if (ok.empty() || !ok[0]) return false;
        r = std::move(rs[0]);
        return r.size() == L.count;
    };
}

// The scans before the first start: the given ones, plus ε_T's (dynamics set-up) and v_c's (in
// the steady-state-curve coordinates) unless given (DatasetFitSettings::autoScan).
void addScans(const DatasetFitSettings& st, const CurveCoordinates& curve, FitProblem& prob) {
    prob.scans = st.scans;
    const bool epsTFree = std::any_of(prob.parameters.begin(), prob.parameters.end(),
                                      [](const FitParameter& fp) { return fp.free && fp.name == "epsT"; });
    const bool epsTScanned = std::any_of(prob.scans.begin(), prob.scans.end(), [](const ParameterScan& sc) { return sc.name == "epsT"; });
    if (st.autoScan && st.setup == SetupKind::Dynamics && epsTFree && !epsTScanned)
        prob.scans.push_back({"epsT", logGrid(kEpsTScanLower, kEpsTScanUpper, kEpsTScanPoints)});
    const bool vcScanned = std::any_of(prob.scans.begin(), prob.scans.end(), [](const ParameterScan& sc) { return sc.name == "vc"; });
    if (st.autoScan && curve.active() && !vcScanned)
        prob.scans.push_back({"vc", logGrid(kVcScanLower, kVcScanUpper, kVcScanPoints)});
}

// Integrated autocorrelation time of the residuals r at the optimum (fit.hpp): pooled over the
// runs and channels, each contiguous stretch of samples on its own, lags to 200 while ρ ≥ 0.05.
double residualTauInt(const std::vector<double>& r, const ResidualLayout& L) {
    const size_t nc = L.channels;
    const size_t maxLag = 200;
    std::vector<double> acc(maxLag + 1, 0.0);
    for (size_t k = 0; k < L.index.size(); ++k) {
        const std::vector<size_t>& ix = L.index[k];
        size_t step = std::numeric_limits<size_t>::max();
        for (size_t j = 1; j < ix.size(); ++j) step = std::min(step, ix[j] - ix[j - 1]);
        for (size_t c = 0; c < nc; ++c) {
            size_t b = 0;
            for (size_t j = 1; j <= ix.size(); ++j) {
                if (j < ix.size() && ix[j] - ix[j - 1] == step) continue;
                // contiguous stretch [b, j)
                for (size_t lag = 0; lag <= maxLag && b + lag < j; ++lag)
                    for (size_t i = b; i + lag < j; ++i)
                        acc[lag] += r[L.offset[k] + i * nc + c] * r[L.offset[k] + (i + lag) * nc + c];
                b = j;
            }
        }
    }
    double tau = 1.0;
    for (size_t lag = 1; lag <= maxLag && acc[0] > 0.0; ++lag) {
        const double rho = acc[lag] / acc[0];
        if (rho < 0.05) break;
        tau += 2.0 * rho;
    }
    return tau;
}

// Leave each run out in turn and repeat the whole procedure on the rest (fit.hpp); the
// jackknife standard errors, and the reported ones raised to them. `parts`: the progress
// fractions (the main fit was the first).
void jackknifeOverRuns(const std::vector<CleanRun>& fitRuns, const DatasetFitSettings& st, double parts, DatasetFit& out) {
    DatasetFitSettings js = st;
    js.jackknife = false;
    const size_t K = fitRuns.size();
    std::vector<std::vector<double>> est;
    for (size_t k = 0; k < K; ++k) {
        if (cancelRequested(st.cancel)) break;
        if (st.progress) js.progress = [&st, k, parts](double f) { st.progress((static_cast<double>(k + 1) + f) / parts); };
        std::vector<CleanRun> sub;
        for (size_t q = 0; q < K; ++q)
            if (q != k) sub.push_back(fitRuns[q]);
        const DatasetFit f = fitDataset(sub, {}, js);
        if (!f.ok) continue;
        std::vector<double> v;
        for (const std::string& n : out.fit.names) v.push_back(f.fit.value(n));
        est.push_back(std::move(v));
    }
    out.jackknifeFits = static_cast<int>(est.size());
    if (est.size() != K) return;
    for (size_t i = 0; i < out.fit.names.size(); ++i) {
        if (!out.fit.free[i]) continue;
        std::vector<double> column;
        for (const auto& v : est) column.push_back(v[i]);
        out.stderrsJackknife[i] = jackknifeStderr(column);
        if (std::isfinite(out.fit.stderrs[i])) out.fit.stderrs[i] = std::max(out.fit.stderrs[i], out.stderrsJackknife[i]);
    }
}

// Per-run scores of the fitted model and the pooled NRMSE of fit and validation runs: each
// run's error over its own measured RMS, pooled as n_k NRMSE_k² over n_k in both set-ups, as
// the fit's objective weighs it and identify's NRMSE counts it (so identify's "before" and
// fit's NRMSE are one quantity). Raw Σe²/ΣF² weighted the runs by their force level instead
// (damper: 0.271 against 0.266 for the same model).
void scoreRuns(const std::vector<CleanRun>& fitRuns, const std::vector<CleanRun>& valRuns, const DatasetFitSettings& st,
               DatasetFit& out) {
    double sseF = 0, ssF = 0, sseV = 0, ssV = 0;
    for (const CleanRun& c : fitRuns) {
        RunScore s = scoreRun(c, st.setup, out.model, st.predict, "fit");
        if (s.ok) { sseF += s.nrmse * s.nrmse * s.samples; ssF += s.samples; }
        out.runs.push_back(std::move(s));
    }
    for (const CleanRun& c : valRuns) {
        RunScore s = scoreRun(c, st.setup, out.model, st.predict, "validation");
        if (s.ok) { sseV += s.nrmse * s.nrmse * s.samples; ssV += s.samples; }
        out.runs.push_back(std::move(s));
    }
    out.fitNrmse = ssF > 0 ? std::sqrt(sseF / ssF) : std::numeric_limits<double>::quiet_NaN();
    out.validationNrmse = ssV > 0 ? std::sqrt(sseV / ssV) : std::numeric_limits<double>::quiet_NaN();
}

}  // namespace

namespace {

// The solver's settings of the dataset fit.
void copySolverSettings(const DatasetFitSettings& st, FitProblem& prob) {
    prob.multistarts = st.multistarts;
    prob.agreeingStarts = st.agreeingStarts;
    prob.loss = st.loss;
    prob.lossScale = st.lossScale;
    prob.seed = st.seed;
    prob.maxIterations = st.maxIterations;
    prob.relativeStep = st.relativeStep;
    prob.cancel = st.cancel;
}

// The notes a reader of the solver summary needs first: how the start was found, and which
// requested parameters the law does not have.
void prefixSolverNotes(const DatasetFitSettings& st, const std::string& startNote, const std::vector<std::string>& dropped,
                       FitResult& fit) {
    if (!startNote.empty()) fit.solverSummary = startNote + "\n" + fit.solverSummary;
    if (!dropped.empty()) {
        std::string d;
        for (const auto& n : dropped) d += (d.empty() ? "" : ", ") + n;
        fit.solverSummary = std::string("not in the ") + toString(st.law) + " law, not fitted: " + d + "\n" + fit.solverSummary;
    }
}

}  // namespace

DatasetFit fitDataset(const std::vector<CleanRun>& fitRuns, const std::vector<CleanRun>& valRuns, const DatasetFitSettings& st) {
    DatasetFit out;
    out.setup = st.setup;
    out.model.law = st.law;
    out.model.tieC1ToMu = st.tieC1ToMu;
    if (fitRuns.empty()) {
        out.message = "no runs to fit";
        return out;
    }
    const ParamIssues pbad = st.predict.validate();
    if (!pbad.empty()) {
        out.message = pbad.front().message();
        return out;
    }
    // Parameters: the free ones (that the law has) with default bounds, starts from the data
    // and from `start`; everything in `start` that is not free is passed as fixed.
    FitProblem prob;
    std::vector<std::string> dropped;
    if (!freeParameters(st, prob, dropped, out.message)) return out;
    if (st.estimateStart) startMuFromData(fitRuns, prob);
    std::string startNote;
    if (st.estimateStart && st.equationErrorStart && st.setup == SetupKind::Dynamics && st.law == LawKind::RateState)
        startNote = equationErrorStart(fitRuns, st, prob);
    applyStart(st, prob);
    // Steady-state-curve coordinates (DatasetFitSettings::curveCoordinates): the entries of C1
    // and η become κ = C1/v_c² and s = η − C1/v_c.
    CurveCoordinates curve;
    if (st.curveCoordinates && st.law == LawKind::RateState && st.setup == SetupKind::Dynamics)
        curve = CurveCoordinates::install(prob.parameters, st.scans);
    const SpecFor specFor = [&st, &prob, &curve](const std::vector<double>& vals) {
        ModelSpec m;
        m.law = st.law;
        m.tieC1ToMu = st.tieC1ToMu;
        for (size_t i = 0; i < prob.parameters.size(); ++i) m.values[prob.parameters[i].name] = vals[i];
        if (curve.active()) curve.toLaw(vals, m.values);
        return m;
    };
    ResidualLayout layout;
    if (!layoutResiduals(fitRuns, st, specFor, prob, layout, out.message)) return out;
    installResiduals(prob, fitRuns, st, layout, specFor, curve);
    addScans(st, curve, prob);
    copySolverSettings(st, prob);
    // With the jackknife the main fit is the first of K + 1 equal parts of the progress.
    const double parts = st.jackknife && fitRuns.size() >= 3 ? static_cast<double>(fitRuns.size() + 1) : 1.0;
    if (st.progress) prob.progress = [&st, parts](double f) { st.progress(f / parts); };
    out.fit = fitLeastSquares(prob);
    prefixSolverNotes(st, startNote, dropped, out.fit);
    if (!out.fit.ok()) {
        out.message = out.fit.message;
        return out;
    }
    out.model = specFor(out.fit.values);
    const std::vector<double> internalOptimum = out.fit.values;  // what prob.residuals takes
    if (curve.active()) curve.restore(out.fit);
    // The Jacobian's standard errors inflated by √τ_int of the residuals at the optimum (fit.hpp).
    std::vector<double> r(layout.count, 0.0);
    if (prob.residuals(internalOptimum, r)) out.tauInt = residualTauInt(r, layout);
    out.stderrsIid = out.fit.stderrs;
    const double inflate = std::sqrt(std::max(1.0, out.tauInt));
    for (double& se : out.fit.stderrs) se *= inflate;
    out.stderrsJacobian = out.fit.stderrs;
    out.stderrsJackknife.assign(out.fit.names.size(), std::numeric_limits<double>::quiet_NaN());
    if (st.jackknife && fitRuns.size() >= 3) jackknifeOverRuns(fitRuns, st, parts, out);
    if (curve.active() && out.jackknifeFits == 0)
        out.stderrWarning = "standard errors from the Jacobian only: with C1, eta and vc free the dynamics cost has several "
                            "minima along the steady-state curve's valley, and these errors are too small there (on the "
                            "synthetic D05 5-15x for C1, eta, vc, Dc and mu); use the jackknife over runs";
    scoreRuns(fitRuns, valRuns, st, out);
    out.ok = true;
    return out;
}

}  // namespace stickslip::identify
