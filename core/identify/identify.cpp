#include "identify.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <optional>

#include "fit_internal.hpp"
#include "identify_internal.hpp"
#include "identify_loop.hpp"
#include "simulated_null.hpp"

namespace stickslip::identify {

using namespace detail;

namespace {

// Slip episodes in the fit runs (the independent units of the penalised criterion): one per
// run plus one per reversal of the slip direction.
double slipEpisodes(const Context& cx, const std::vector<size_t>& fitIdx, double stickVelocity_mps) {
    double episodes = 0;
    for (size_t i : fitIdx) {
        double last = 0;
        episodes += 1;
        for (double v : cx.runs[i].V) {
            if (std::abs(v) < stickVelocity_mps) continue;
            const double sg = v > 0 ? 1 : -1;
            if (last != 0 && sg != last) episodes += 1;
            last = sg;
        }
    }
    return episodes;
}

// Fits the baseline (the law alone) and records "before". False with res.message on failure.
bool fitBaseline(Loop& L, const std::vector<IdentifyRun>& runs) {
    L.progress("baseline", 0.0);
    L.spec.segments = L.cx.anyDynamics && L.opt.dynamicsResidual == DynamicsResidual::Segments;
    std::map<std::string, double> start = baselineStart(L.cx, L.fitIdx);
    if (L.cx.anyDynamics) start["m"] = runs[L.fitIdx[0]].nominalMass_kg;
    L.cur = fitSpec(L.cx, L.spec, start, L.fitIdx, L.opt.multistarts, L.res.fits, true);
    L.res.baselineFirstFit = L.cur.fit;
    if (!L.cur.ok) {
        L.res.cancelled = L.cancelled();
        L.res.message = "baseline fit failed: " + L.cur.message;
        return false;
    }
    // A baseline that explains none of the force (fit NRMSE ≥ 1: no better than no force) has
    // stopped where the law predicts none and its Jacobian vanishes: a solver failure, not an
    // answer. Tried again from the library's default law (μ from the data, as the first start).
    std::string note;
    if (!(L.cur.nrmse() < 1.0)) {
        const RateStateParams defaults;
        std::map<std::string, double> alt = baselineStart(L.cx, L.fitIdx, &defaults);
        if (L.cx.anyDynamics) alt["m"] = start["m"];
        L.progress("baseline from the default law", 0.0);
        const FitOutcome g = fitSpec(L.cx, L.spec, alt, L.fitIdx, L.opt.multistarts, L.res.fits, true);
        note = "the fit from the given start explained none of the force (fit NRMSE " + fmt(L.cur.nrmse()) +
               ": the law predicts no force there and the solver cannot leave), ";
        if (g.ok && g.ss < L.cur.ss) {
            L.cur = g;
            note += "refitted from the default law (fit NRMSE " + fmt(g.nrmse()) + ")";
        } else {
            note += "and the default law's start did no better";
        }
        if (!(L.cur.nrmse() < 1.0)) {
            L.res.message = "baseline fit failed: " + note;
            return false;
        }
    }
    if (L.opt.heldOutRestart) {
        const std::string bounds = checkBaselineBounds(L);
        if (!bounds.empty()) note += (note.empty() ? "" : "; ") + bounds;
    }
    adoptBaseline(L, note);
    // Segments: the independent units are the segments (each one reversal, stick and breakaway).
    for (size_t i : L.fitIdx) L.segEpisodes += static_cast<double>(L.cx.runs[i].segments.size());
    L.res.segmentsUsed = L.segEpisodes;
    return true;
}

// (1b) The candidate's gain against what noise alone gives on these runs (noise_null.hpp).
// False, with the reason in t.sc, when noise alone gives as much.
bool beatsNoiseNull(Loop& L, Round& R, Tried& t) {
    CandidateScore& sc = t.sc;
    L.progress(R.label() + ": noise null of " + sc.name, 1.0);
    const bool sw = t.spec.segments != L.spec.segments;
    const FitOutcome& base = sw ? R.segBase : L.cur;
    std::vector<double> r0;
    std::vector<NoiseBlock> blocks;
    const std::vector<FitParameter> ps = parameters(L.cx, t.spec, t.fit.values);
    std::vector<std::string> baseNames, effNames;
    for (const FitParameter& fp : ps) {
        if (!fp.free) continue;
        (fp.name.rfind(sc.name + ".", 0) == 0 ? effNames : baseNames).push_back(fp.name);
    }
    if (!residualVector(L.cx, sw ? R.segSpec : L.spec, base.values, L.fitIdx, r0, &blocks)) return true;
    const Eigen::MatrixXd J0 = residualJacobian(L.cx, t.spec, t.fit.values, L.fitIdx, ps, baseNames, r0.size());
    const Eigen::MatrixXd Jc = residualJacobian(L.cx, t.spec, t.fit.values, L.fitIdx, ps, effNames, r0.size());
    const std::vector<double>& d = R.numerics[sw];
    int& made = R.numericsMade[sw];
    if (L.opt.nullNumerics && made == 0)
        made = numericsOffset(L.cx, sw ? R.segSpec : L.spec, base.values, L.fitIdx, r0, R.numerics[sw]) ? 1 : -1;
    const bool numerics = L.opt.nullNumerics && made == 1;
    const NullGains ng = projectionGainNull(projectionBases(J0, Jc), blocks, r0.size(), L.opt.nullReplicas,
                                            L.opt.seed + 7919u * R.number, numerics ? &d : nullptr);
    // The effect's own gain: over the better of the current model's fit and the current model at
    // the candidate's point with the effect removed. A candidate fit that also moved the current
    // model's parameters into a better minimum of that model is not credited with that part (a
    // viscous_damping fit ending with ζ inside the rig's baseline range is the baseline itself).
    const Spec& curSpec = sw ? R.segSpec : L.spec;
    const double ssWithout = evalSS(L.cx, curSpec, withoutEffect(L.cx, curSpec, sc.name, t.fit.values), L.fitIdx);
    sc.ownMinimumGain = std::isfinite(ssWithout) ? std::max(0.0, base.ss - ssWithout) : 0.0;
    sc.gain = base.ss - sc.ownMinimumGain - t.fit.ss;
    sc.nullGain = ng.quantile(1.0 - L.opt.nullAlpha);
    sc.nullReplicas = static_cast<int>(ng.gains.size());
    if (numerics) sc.numericsGain = ng.offsetGain;
    if (sc.gain > sc.nullGain) return true;
    sc.reason = "gain in the sum of squares " + fmt(sc.gain) + " is within the " +
                fmt(100.0 * (1.0 - L.opt.nullAlpha)) + " % quantile of " + std::to_string(sc.nullReplicas) +
                " noise replicas of these runs (" + fmt(sc.nullGain) + ")" +
                (numerics ? " carrying the prediction's numerical error (alone it gives " + fmt(ng.offsetGain) + ")"
                          : std::string()) +
                ": noise alone gives as much" +
                (sc.ownMinimumGain > 0.0 ? " (the current model at the candidate's point without the effect already "
                                           "lowers the sum of squares by " + fmt(sc.ownMinimumGain) +
                                           ": that part is the current model's own, not the effect's)"
                                         : std::string());
    return false;
}

// (4) The candidate's own gain against what replicas of the fit runs, simulated from the current
// model and cleaned and fitted as the data were, give (simulated_null.hpp). False, with the
// reason in t.sc, when they give as much. A null that cannot run (runs given cleaned, prescribed
// runs) leaves the verdict to tests (1)-(3) and says so.
bool beatsSimulatedNull(Loop& L, Round& R, Tried& t) {
    CandidateScore& sc = t.sc;
    L.progress(R.label() + ": simulated null of " + sc.name, 1.0);
    const SimulatedNull sn = simulatedGainNull(L.cx, L.spec, L.cur.values, t.spec, t.fit.values, L.fitIdx,
                                               L.opt.simulatedNullReplicas, L.opt.seed + 104729u * R.number, L.res.fits);
    if (!sn.ran) {
        sc.simulatedNullNote = sn.note;
        return !L.cancelled();
    }
    sc.simulatedGains = sn.gains;
    sc.simulatedNullModel = sn.model;
    sc.simulatedNullGain = momentMatchedGammaQuantile(sn.gains, 1.0 - L.opt.nullAlpha);
    const double gain = sc.gain != CandidateScore::kNoTest ? sc.gain : L.cur.ss - t.fit.ss;
    if (gain > sc.simulatedNullGain) return true;
    sc.reason = "gain in the sum of squares " + fmt(gain) + " is within the " +
                fmt(100.0 * (1.0 - L.opt.nullAlpha)) + " % quantile (" + fmt(sc.simulatedNullGain) +
                ") of what " + std::to_string(sn.gains.size()) +
                " replicas of these runs simulated from the current model, with their noise, give after the same "
                "cleaning and fits (mean " +
                fmt(std::accumulate(sn.gains.begin(), sn.gains.end(), 0.0) / sn.gains.size()) +
                "): the chain alone gives as much";
    return false;
}

// The selection rule (IdentifyOptions in identify.hpp): in order of ΔBIC, the first candidate that
// passes every test is chosen; the others get the test they failed as their reason. Returns the
// chosen index (-1: none) with its held-out errors and the held-out error it is compared with.
int selectCandidate(Loop& L, Round& R, std::vector<Tried>& tried, ModelErrors& me, double& heldOutRef) {
    int chosen = -1;
    heldOutRef = L.curHeldOut;
    for (size_t ti = 0; ti < tried.size(); ++ti) {
        CandidateScore& sc = tried[ti].sc;
        if (!(sc.deltaBic < -L.opt.bicMargin)) {
            // The margin cannot tell noise from a real gain the runs support weakly: say how much
            // evidence they could give (n_eff), not that noise explains it.
            sc.reason = std::string(ti == 0 ? "best candidate of " + R.label() + " but " : "") + "dBIC = " +
                        fmt(sc.deltaBic) + " is not below -" + fmt(L.opt.bicMargin) +
                        " with n_eff = " + std::to_string(static_cast<long>(std::lround(sc.neff))) + " (" + sc.neffLimit +
                        "): its fit NRMSE " + fmt(sc.fitNrmse) +
                        " is not strong evidence for it on these runs";
            continue;
        }
        if (chosen >= 0) {
            sc.reason = "dBIC = " + fmt(sc.deltaBic) + " but " + tried[chosen].sc.name + " was added in " +
                        R.label();
            continue;
        }
        // (0) Confounded with an effect already in the model: the two trade off in the joint fit.
        if (const std::string with = confoundedWith(sc, L.spec.effects, L.opt.confoundedVif); !with.empty()) {
            const double r = sc.sizeCorrelation.at(with);
            sc.confoundedWith = with;
            sc.reason = "confounded with " + with + ": their sizes trade off in the joint fit (correlation " +
                        fmt(r) + ", variance inflation " + fmt(1.0 / std::max(1.0 - r * r, 1e-300)) +
                        " > " + fmt(L.opt.confoundedVif) + "): the data cannot tell the two apart; dBIC " +
                        fmt(sc.deltaBic) + " not credited";
            continue;
        }
        if (L.opt.nullReplicas > 0 && !beatsNoiseNull(L, R, tried[ti])) continue;
        const bool sw = tried[ti].spec.segments != L.spec.segments;
        const ModelErrors& ref = sw ? R.segBaselineErrors(L) : L.curErrors;
        L.progress(R.label() + ": held-out check of " + sc.name, 1.0);
        std::vector<std::map<std::string, double>> loo;
        ModelErrors e = errorsOf(L.cx, tried[ti].spec, tried[ti].fit, L.fitIdx, L.valIdx, L.res.fits, &loo);
        // The model about to be judged gets the baseline's convergence guard: it is judged
        // (and, if added, extended) from its own minimum, not from where a start stopped.
        std::string note;
        const double ssFirst = tried[ti].fit.ss;
        if (L.opt.heldOutRestart && restartFromHeldOut(L, tried[ti].spec, tried[ti].fit, loo, note)) {
            scoreFit(L, tried[ti]);
            creditRestartGain(sc, ssFirst, tried[ti].fit.ss);
            sc.startNote += note + ". ";
            e = errorsOf(L.cx, tried[ti].spec, tried[ti].fit, L.fitIdx, L.valIdx, L.res.fits, &loo);
        }
        sc.heldOutNrmse = e.validationNrmse;
        if (!passesSelection(L.cx, sc, tried[ti].fit, ref, e, loo, L.valIdx.empty() ? L.fitIdx : L.valIdx,
                             L.curDiag.integratedAcfTime))
            continue;
        if (L.opt.simulatedNullReplicas > 0 && !beatsSimulatedNull(L, R, tried[ti])) continue;
        chosen = static_cast<int>(ti);
        me = std::move(e);
        heldOutRef = ref.validationNrmse;
    }
    return chosen;
}

// Makes the chosen candidate the current model and reports it as added.
void addEffect(Loop& L, Round& R, Tried& chosen, const ModelErrors& me, double heldOutRef) {
    CandidateScore& best = chosen.sc;
    best.accepted = true;
    L.scores[best.name] = best;
    if (chosen.spec.segments != L.spec.segments) {
        // From here on the model is scored with the segment residual: "before" is the
        // baseline under that residual, so before and after compare like with like.
        L.res.before = R.segBaseErrors;
        L.predBefore.clear();
        L.res.diagnosticsBefore = diagnoseModel(L.cx, R.segSpec, R.segBase, &L.predBefore);
        L.curDiag = L.res.diagnosticsBefore;
        L.res.residual = "segments";
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
        for (const SignalCorrelation& c : L.curDiag.correlations)
            if (c.signal == sname) ae.pointedBy.push_back(c);
    if (!L.spec.segments && !chosen.spec.segments) {
        ae.lawStep.refinement = kLawResolutionRefinement;
        ae.lawStep.ssBefore = evalSSRefined(L.cx, L.spec, L.cur.values, L.fitIdx, 1);
        ae.lawStep.ssBeforeRefined = evalSSRefined(L.cx, L.spec, L.cur.values, L.fitIdx, kLawResolutionRefinement);
        ae.lawStep.ssAfter = evalSSRefined(L.cx, chosen.spec, chosen.fit.values, L.fitIdx, 1);
        ae.lawStep.ssAfterRefined = evalSSRefined(L.cx, chosen.spec, chosen.fit.values, L.fitIdx, kLawResolutionRefinement);
    }
    L.res.effectsAdded.push_back(ae);
    L.spec = chosen.spec;
    L.cur = chosen.fit;
    L.curHeldOut = me.validationNrmse;
    L.res.after = me;
    L.curErrors = me;
    L.curDiag = diagnoseModel(L.cx, L.spec, L.cur, nullptr, StructureCheck::Skip);
}

// One round: every candidate not yet in the model is fitted and scored; the best that passes
// the selection is added. False when nothing was added (the loop ends). `previous`: the round's
// candidate fits before the current model was refitted (fitCandidate).
bool runRound(Loop& L, int number, const std::vector<std::string>& cands, const std::vector<Tried>& previous = {}) {
    Round R;
    R.number = number;
    R.bicCur = L.bicOf(L.cur, L.spec, L.curDiag.integratedAcfTime);
    R.segSpec = L.spec;
    R.segSpec.segments = true;
    std::vector<Tried> tried = fitCandidates(L, R, cands, previous);
    if (tried.empty()) {
        L.lastOnBound = std::move(R.onBound);
        return false;
    }
    // The current model's guard against its own local minimum (in round 1 the baseline's).
    // Each restart lowers the current model's BIC by more than the margin; at most
    // kRestarts per round, a bound on the cost only. The round's scores are dropped: it is
    // fitted again on the refitted model.
    constexpr int kRestarts = 3;
    if (L.opt.heldOutRestart && L.roundRestarts < kRestarts && restartFromCandidates(L, tried)) {
        ++L.roundRestarts;
        for (const std::string& c : cands)
            if (std::find(L.spec.effects.begin(), L.spec.effects.end(), c) == L.spec.effects.end()) L.scores.erase(c);
        return runRound(L, number, cands, tried);
    }
    L.roundRestarts = 0;
    std::sort(tried.begin(), tried.end(), [](const auto& a, const auto& b) { return a.sc.deltaBic < b.sc.deltaBic; });
    ModelErrors me;
    double heldOutRef = 0;
    const int chosen = selectCandidate(L, R, tried, me, heldOutRef);
    for (const Tried& t : tried) {
        L.scores[t.sc.name] = t.sc;
        for (AddedEffect& ae : L.res.effectsAdded)
            if (ae.name == t.sc.confoundedWith) ae.confoundedWith.push_back(t.sc.name);
    }
    if (chosen < 0) {
        L.lastOnBound = std::move(R.onBound);
        return false;
    }
    addEffect(L, R, tried[static_cast<size_t>(chosen)], me, heldOutRef);
    return true;
}

// The final model's diagnostics, the "unexplained" verdict with the diagnostic behind it, and
// the per-run traces before and after.
void finishReport(Loop& L) {
    IdentifyResult& res = L.res;
    if (res.effectsAdded.empty()) res.after = res.before;
    res.final = L.cur.estimates;  // effect parameters under "effect.param" names
    std::vector<std::vector<double>> predAfter;
    res.diagnosticsAfter = diagnoseModel(L.cx, L.spec, L.cur, &predAfter);
    // Both channels (the equation of motion's where there are dynamics runs), each as an effect's
    // held-out gain is judged.
    std::string lawWhy, eomWhy;
    const Diagnostics& da = res.diagnosticsAfter;
    const bool law = structureRemains(da.structure, L.opt, lawWhy);
    const bool eom = da.structureEom.runs > 0 && structureRemains(da.structureEom, L.opt, eomWhy);
    res.unexplained = law || eom;
    res.structureNote = "law channel: " + lawWhy + (eomWhy.empty() ? "" : "; equation of motion: " + eomWhy);
    if (!L.spec.segments) {
        double mass = kNaN;
        res.lawResolution = checkLawResolution(L.cx, buildModel(L.cx, L.spec, L.cur.values, mass), mass,
                                               kLawResolutionRefinement);
    }
    if (res.unexplained) {
        const auto& cs = res.diagnosticsAfter.correlations;
        auto top = std::max_element(cs.begin(), cs.end(), [](const auto& a, const auto& b) {
            return std::abs(a.correlation) < std::abs(b.correlation);
        });
        res.unexplainedReason = std::string("the residual left after the loop ") +
                                (law && eom ? "in both channels" : law ? "in the law channel" : "in the equation of motion") +
                                " is predicted from run to run by the runs' own state (" + res.structureNote + "); largest correlation: " +
                                (top != cs.end() ? top->signal + " r = " + fmt(top->correlation) : "none") +
                                "; no catalogue candidate lowered the penalised and held-out error further";
        if (const std::string t = lawResolutionText(res.lawResolution); !t.empty()) res.unexplainedReason += "; " + t;
    }
    for (size_t i = 0; i < L.cx.runs.size(); ++i) {
        const Prepared& p = L.cx.runs[i];
        RunTrace t;
        t.file = p.run->file;
        t.t_s = p.t;
        t.relVel_mps = p.V;
        t.measured_N = p.F;
        t.before_N = L.predBefore[i];
        t.after_N = predAfter[i];
        t.used.assign(p.size(), 1);
        for (size_t k = 0; k < p.size(); ++k) t.used[k] = std::isfinite(t.before_N[k]) && std::isfinite(t.after_N[k]);
        res.traces.push_back(std::move(t));
    }
}

// How the runs were prepared and fitted, as the report states it.
void describeSetup(const Context& cx, const IdentifyOptions& opt, int decimation, IdentifyResult& res) {
    res.decimation = decimation;
    for (const Prepared& p : cx.runs)
        if (p.run->setup == SetupKind::Dynamics) res.edgeGuard = std::max(res.edgeGuard, static_cast<int>(p.edgeGuard));
    res.jacobian = opt.analyticJacobian ? "sensitivities" : opt.forwardJacobian ? "forward" : "central";
    res.lineSearchSteps = opt.lineSearchSteps;
    res.looFunctionTolerance = opt.looFunctionTolerance;
    res.stateStep = opt.exactStateStep ? "constant_rate" : "backward_euler";
    // What the runs were prepared with (prepareContext decides per run), not a second rule.
    res.lawInput = std::any_of(cx.runs.begin(), cx.runs.end(), [](const Prepared& p) { return !p.stepSlip.empty(); })
                       ? "recorded_slip"
                       : "linear";
    res.setup = cx.anyDynamics ? "dynamics" : "prescribed";
    res.coordinates = opt.curveCoordinates ? "steady_state_curve" : "law";
}

// The candidates: the options' list or else the whole catalogue; false (message set) for a name
// the catalogue does not have.
bool candidateList(const IdentifyOptions& opt, std::vector<std::string>& cands, std::string& message) {
    cands = opt.candidates;
    if (cands.empty())
        for (const EffectInfo& e : effectCatalogue()) cands.push_back(e.name);
    for (const std::string& c : cands) {
        EffectInfo info;
        if (!findEffect(c, info)) {
            message = "unknown effect '" + c + "'";
            return false;
        }
    }
    return true;
}

// The loop on prepared runs: baseline, rounds, self-test and report (identifyEffects). Returns
// with L.res.ok unset (message set) when it cannot finish.
void runLoop(Loop& L, const std::vector<IdentifyRun>& runs) {
    const IdentifyOptions& opt = L.opt;
    IdentifyResult& res = L.res;
    Context& cx = L.cx;
    for (size_t i = 0; i < runs.size(); ++i) (runs[i].validation ? L.valIdx : L.fitIdx).push_back(i);
    if (L.fitIdx.empty()) {
        res.message = "every run is a validation run: nothing to fit";
        return;
    }
    std::vector<std::string> cands;
    if (!candidateList(opt, cands, res.message)) return;
    L.episodes = slipEpisodes(cx, L.fitIdx, opt.stickVelocity_mps);
    res.slipEpisodes = L.episodes;
    res.heldOutAlpha = opt.heldOutAlpha;
    res.heldOutMidP = opt.heldOutMidP;
    res.minHeldOutGain = opt.minHeldOutGain;
    res.nullAlpha = opt.nullAlpha;
    res.nullReplicas = opt.nullReplicas;
    res.bicMargin = opt.bicMargin;
    res.restartMargin = opt.restartMargin;
    res.nullNumerics = opt.nullNumerics && opt.nullReplicas > 0;
    res.identifiabilityAlpha = opt.identifiabilityAlpha;
    if (const ParamIssues bad = opt.validate(); !bad.empty()) {
        res.message = formatIssues(bad);
        return;
    }
    if (!fitBaseline(L, runs)) return;
    res.residual = L.residualName(L.spec);
    bool lastRoundAddedNothing = false;
    for (int round = 1; round <= opt.maxEffects; ++round) {
        if (L.cancelled()) {
            res.cancelled = true;
            break;
        }
        if (!runRound(L, round, cands)) {
            lastRoundAddedNothing = true;
            break;
        }
    }
    const int dropped = !L.res.effectsAdded.empty() && !L.cancelled() ? dropVanishedEffects(L) : 0;
    // The verdicts are made; the final model is reported at the best minimum the last round saw.
    if (L.opt.heldOutRestart && lastRoundAddedNothing && dropped == 0 && !L.cancelled()) polishFinalModel(L);
    // The self-test around the final baseline (round 1 may have refitted it, restartFromCandidates).
    if (opt.selfTest.replicas > 0 && !L.cancelled()) {
        L.progress("self-test", 0.0);
        res.selfTest = runSelfTest(cx, L.baseSpec, L.baseFit, L.fitIdx, cands,
                                   std::min(L.baseFit.count / std::max(res.tauInt, 1.0), L.episodes));
        if (!res.selfTest.ok && L.cancelled()) {
            res.cancelled = true;
            res.message = "cancelled during the self-test";
            return;
        }
    }
    for (const std::string& c : cands)
        if (L.scores.count(c)) res.candidates.push_back(L.scores[c]);
    L.progress("report", 1.0);
    finishReport(L);
    res.ok = true;
    res.cancelled = res.cancelled || L.cancelled();
}

}  // namespace

IdentifyResult identifyEffects(std::vector<IdentifyRun> runs, const IdentifyOptions& opt) {
    const auto t0 = Clock::now();
    IdentifyResult res;
    if (runs.empty()) {
        res.message = "no runs";
        return res;
    }
    Context cx;
    // The runs at their recorded rate, for the numerical part of the noise null (numericsOffset).
    IdentifyOptions fullOpt = opt;
    fullOpt.decimate = 1;
    Context full;
    {
        int dec = 0;
        std::string why;
        if (!prepareContext(runs, opt, cx, dec, why)) {
            res.message = why;
            return res;
        }
        describeSetup(cx, opt, dec, res);
        int one = 0;
        if (opt.nullNumerics && opt.nullReplicas > 0 && dec > 1 && prepareContext(runs, fullOpt, full, one, why))
            cx.fullRate = &full;
    }
    Loop L(cx, opt, res, t0);
    runLoop(L, runs);
    L.closeStage();
    res.wallTime_s = L.elapsed();
    if (res.ok && opt.progress) opt.progress("done", 1.0);
    return res;
}

}  // namespace stickslip::identify
