#include "identify.hpp"

#include <algorithm>
#include <atomic>
#include <thread>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>

#include "identify_internal.hpp"

namespace stickslip::identify {

using namespace detail;
using Clock = std::chrono::steady_clock;

IdentifyResult identifyEffects(std::vector<IdentifyRun> runs, const IdentifyOptions& opt) {
    const auto t0 = Clock::now();
    IdentifyResult res;
    auto progress = [&](const std::string& s, double f) { if (opt.progress) opt.progress(s, f); };
    if (runs.empty()) { res.message = "no runs"; return res; }
    Context cx;
    {
        int dec = 0;
        std::string why;
        if (!prepareContext(runs, opt, cx, dec, why)) { res.message = why; return res; }
        res.decimation = dec;
        res.setup = cx.anyDynamics ? "dynamics" : "prescribed";
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
    if (!(opt.confoundedVif > 1.0)) {
        res.message = "confoundedVif = " + std::to_string(opt.confoundedVif) + " must be > 1";
        return res;
    }
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
    if (cur.values.count("mu")) cx.muScale = cur.values.at("mu");
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
    if (opt.selfTest.replicas > 0) {
        res.selfTest = runSelfTest(cx, spec, cur, fitIdx, cands,
                                   std::min(cur.count / std::max(curDiag.integratedAcfTime, 1.0), episodes));
        if (!res.selfTest.ok && opt.cancel && opt.cancel->load()) {
            res.cancelled = true;
            res.message = "cancelled during the self-test";
            return res;
        }
    }
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
            FitOutcome f = fitSpec(cx, s2, st, fitIdx, 1, res.fits);
            if (!f.ok) {
                sc.reason = "fit failed: " + f.message;
                scores[c] = sc;
                continue;
            }
            // The candidate contains the current model (its effect where it vanishes): a fit that
            // ends above the current model's sum of squares stopped in a worse local minimum — a
            // solver failure, retried from the current model's own point.
            std::string startNote;
            if (f.ss > base->ss * (1.0 + 1e-6)) {
                const FitOutcome g = fitSpec(cx, s2, retryStart(cx, c, base->values, st, ""), fitIdx, 1, res.fits);
                if (g.ok && g.ss < f.ss) {
                    f = g;
                    startNote = "the scanned start ended above the current model it contains (a solver failure); refitted "
                                "from the current model's point. ";
                }
            }
            // An effect whose size parameter (the first in its catalogue entry) ends on a physical
            // bound has not been identified (the fit wants it outside the physical range, or the
            // effect has vanished): the improvement it brings is not evidence for this effect.
            // Before giving up, one more start halfway between where the effect vanishes and that
            // bound: if it leaves the bound with a lower cost, the first start was a solver failure;
            // if it ends there too, the bound is the data's answer. (Time constants and distances
            // of the other parameters may rightly sit on a bound: "faster than the data resolve".)
            std::string side = sizeBound(cx, c, f.values);
            if (!side.empty()) {
                const FitOutcome g = fitSpec(cx, s2, retryStart(cx, c, f.values, st, side), fitIdx, 1, res.fits);
                if (g.ok && sizeBound(cx, c, g.values).empty() && g.ss < f.ss) {
                    f = g;
                    startNote += "the first start ended on the " + side + " bound of the size, a start halfway to it did not "
                                 "(a solver failure): refitted. ";
                    side.clear();
                }
            }
            sc.deltaBic = bicOf(f, s2, s2.segments == spec.segments ? curDiag.integratedAcfTime : 1.0) - bicBase;
            sc.fitNrmse = f.count > 0 ? std::sqrt(f.ss / f.count) : 0.0;
            for (const ParamEstimate& p : f.estimates)
                if (p.name.rfind(c + ".", 0) == 0) sc.params.push_back({p.name.substr(c.size() + 1), p.value, p.stderr_});
            sc.sizeCorrelation = sizeCorrelations(f.fit, c);
            sc.startNote = startNote;
            if (!side.empty()) {
                EffectInfo info;
                findEffect(c, info);
                sc.reason = startNote + "parameter " + info.params.front().name + " ended on its physical " + side +
                            " bound from two starts (scanned, and halfway to the bound): the data's answer, not a solver "
                            "failure; not identified (dBIC " + std::to_string(sc.deltaBic) + " not credited)";
                scores[c] = sc;
                continue;
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
            // (0) Confounded with an effect already in the model: the two trade off in the joint fit.
            if (const std::string with = confoundedWith(sc, spec.effects, opt.confoundedVif); !with.empty()) {
                const double r = sc.sizeCorrelation.at(with);
                sc.confoundedWith = with;
                sc.reason = "confounded with " + with + ": their sizes trade off in the joint fit (correlation " +
                            std::to_string(r) + ", variance inflation " + std::to_string(1.0 / std::max(1.0 - r * r, 1e-300)) +
                            " > " + std::to_string(opt.confoundedVif) + "): the data cannot tell the two apart; dBIC " +
                            std::to_string(sc.deltaBic) + " not credited";
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
        for (const Tried& t : tried) {
            scores[t.sc.name] = t.sc;
            for (AddedEffect& ae : res.effectsAdded)
                if (ae.name == t.sc.confoundedWith) ae.confoundedWith.push_back(t.sc.name);
        }
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

}  // namespace stickslip::identify
