// The missing-effect loop's state (identify.cpp) and the guards that refit the current model
// when it stopped in a worse minimum (identify_restart.cpp).
#pragma once

#include <chrono>
#include <map>
#include <string>
#include <vector>

#include "identify_internal.hpp"

namespace stickslip::identify::detail {

using Clock = std::chrono::steady_clock;

// A candidate fitted in a round: its score, its fit and the model it extends to.
struct Tried {
    CandidateScore sc;
    FitOutcome fit;
    Spec spec;
    double bicBase = 0;  // the criterion of the model it extends
};

// The loop's state: the current model, its fit, errors and diagnostics, and every score so far.
struct Loop {
    Loop(Context& c, const IdentifyOptions& o, IdentifyResult& r, Clock::time_point started = Clock::now())
        : cx(c), opt(o), res(r), t0(started) {}
    Context& cx;
    const IdentifyOptions& opt;
    IdentifyResult& res;
    std::vector<size_t> fitIdx, valIdx;
    double episodes = 0, segEpisodes = 0;
    Spec spec;
    FitOutcome cur;
    Diagnostics curDiag;
    ModelErrors curErrors;
    double curHeldOut = 0;
    std::vector<std::vector<double>> predBefore;
    std::map<std::string, CandidateScore> scores;
    int roundRestarts = 0;  // restartFromCandidates taken in the current round
    // The last round's candidate fits whose size ended on a physical bound (polishFinalModel).
    std::vector<Tried> lastOnBound;
    // Wall time of each candidate's last fit (fitCandidates' scheduling order only).
    std::map<std::string, double> candidateSeconds;
    Spec baseSpec;             // the baseline as adopted (adoptBaseline), for the self-test
    FitOutcome baseFit;
    Clock::time_point t0;  // when identifyEffects began (IdentifyResult::timeline)
    mutable bool stageOpen = false;  // the last stage of res.timeline is still running
    mutable long stageFits0 = 0;     // res.fits when it began

    bool cancelled() const { return opt.cancelRequested(); }
    // Reports a stage to the caller and opens it in res.timeline (closing the previous one).
    void progress(const std::string& s, double f) const {
        closeStage();
        const double now = res.timeline.empty() ? elapsed() : res.timeline.back().end_s;
        res.timeline.push_back({s, now, now, 0});
        stageFits0 = res.fits;
        stageOpen = true;
        if (opt.progress) opt.progress(s, f);
    }
    // Closes res.timeline's open stage: its end and the fits it ran.
    void closeStage() const {
        if (!stageOpen) return;
        res.timeline.back().end_s = elapsed();
        res.timeline.back().fits = res.fits - stageFits0;
        stageOpen = false;
    }
    double elapsed() const { return std::chrono::duration<double>(Clock::now() - t0).count(); }
    // The penalised criterion with the effective sample count capped by the independent units
    // (slip episodes, or segments with the segment residual).
    double bicOf(const FitOutcome& f, const Spec& s, double tauInt) const { return bicAt(f.ss, f, s, tauInt); }
    // The same criterion for the model of `f` at another sum of squares `ss` (same data, same
    // free parameters).
    double bicAt(double ss, const FitOutcome& f, const Spec& s, double tauInt) const {
        return bic(ss, f.count, neffCap(f, s, tauInt), f.nFree);
    }
    // The cap on n_eff (bic() also keeps it within [2, n]) and, in `limit`, what sets it.
    double neffCap(const FitOutcome& f, const Spec& s, double tauInt, std::string* limit = nullptr) const {
        const double byAcf = f.count / std::max(tauInt, 1.0);
        const double units = s.segments ? std::max(segEpisodes, 2.0) : episodes;
        if (limit) *limit = units < byAcf ? (s.segments ? "segments" : "slip episodes") : "independent residuals (n/tau_int)";
        return std::min(byAcf, units);
    }
    std::string residualName(const Spec& s) const {
        return !cx.anyDynamics ? std::string("prescribed") : s.segments ? std::string("segments") : std::string("equation_error");
    }
};

// One round of the loop: the current model's criterion, and its view refitted with the segment
// residual (for the stick-phase candidates of the Auto residual), made lazily, at most once per
// round.
struct Round {
    int number = 0;
    double bicCur = 0;
    Spec segSpec;
    FitOutcome segBase;
    bool segBaseTried = false;
    ModelErrors segBaseErrors;
    bool segBaseErrorsDone = false;
    // The current model's numerical part (numericsOffset), per residual ([1]: the segment
    // residual), made once: every candidate's noise null in the round is around the same point.
    std::vector<double> numerics[2];
    int numericsMade[2] = {0, 0};  // 0 not yet, 1 made, −1 failed
    // Candidate fits not scored because their size ended on a physical bound (fitCandidate): still
    // fits of models that contain the current one (polishFinalModel).
    std::vector<Tried> onBound;

    std::string label() const { return "round " + std::to_string(number); }
    const FitOutcome& segBaseline(Loop& L) {
        if (!segBaseTried) {
            segBaseTried = true;
            L.progress(label() + ": baseline with the segment residual", 0.0);
            segBase = fitSpec(L.cx, segSpec, L.cur.values, L.fitIdx, 1, L.res.fits);
        }
        return segBase;
    }
    const ModelErrors& segBaselineErrors(Loop& L) {
        if (!segBaseErrorsDone) {
            L.progress(label() + ": held-out check of the segment baseline", 1.0);
            segBaseErrors = errorsOf(L.cx, segSpec, segBase, L.fitIdx, L.valIdx, L.res.fits);
            segBaseErrorsDone = true;
        }
        return segBaseErrors;
    }
};

// The candidate's figures from its fit: ΔBIC against the model it extends, fit error, its
// parameters and how its size trades off with the others (identify_candidates.cpp).
void scoreFit(const Loop& L, Tried& t);
// Every candidate of `cands` not yet in the model fitted on top of the current one, the fits one
// per core (identify_candidates.cpp): the scored ones in catalogue order; the others get their
// reason in L.scores, and those whose size ended on a physical bound go to R.onBound. `previous`:
// the round's candidate fits before the current model was refitted (a restart), as starts.
std::vector<Tried> fitCandidates(Loop& L, Round& R, const std::vector<std::string>& cands,
                                 const std::vector<Tried>& previous);

// The parameters of `effect` in a fit, without the "effect." prefix (a candidate's or an added
// effect's row in the report).
inline std::vector<ParamEstimate> effectParams(const FitOutcome& f, const std::string& effect) {
    std::vector<ParamEstimate> out;
    for (const ParamEstimate& p : f.estimates)
        if (p.name.rfind(effect + ".", 0) == 0) out.push_back({p.name.substr(effect.size() + 1), p.value, p.stderr_});
    return out;
}

// Makes L.cur the baseline: its held-out errors (with the held-out restart guard), diagnostics
// and the "before" figures. `note` is kept as the baseline's note when the guard finds nothing.
void adoptBaseline(Loop& L, const std::string& note);
// Makes the refitted L.cur (the baseline and the effects added so far, at least one) the current
// model again: its held-out errors (with the held-out restart guard), diagnostics and "after", the
// added effects' parameters, and the last added effect's held-out error after and note.
void adoptCurrent(Loop& L, const std::string& note);
// IdentifyOptions::heldOutRestart from the leave-one-run-out refits `loo` of `fit` (details in
// identify_restart.cpp). True when `fit` changed; `note` says what was found either way.
bool restartFromHeldOut(Loop& L, const Spec& spec, FitOutcome& fit, const std::vector<std::map<std::string, double>>& loo,
                        std::string& note);
// Baseline parameters on a bound of their range (IdentifyOptions::heldOutRestart): each gets a
// second start from the middle of its range; the baseline is refitted there when that ends lower
// by more than the BIC margin (a solver failure), else the bound is the data's answer. Appends
// the verdicts to L.res.baselineBounds; returns what was found, for the baseline's note.
std::string checkBaselineBounds(Loop& L);
// The same guard from the candidates of a round (details in identify_restart.cpp). True when the
// current model changed (the round must be fitted again).
bool restartFromCandidates(Loop& L, const std::vector<Tried>& tried);
// After the loop, when its last round added nothing and the backward check dropped nothing: that
// round's candidates whose size ended on a physical bound (L.lastOnBound) are fits of models that
// contain the final one, so starts for it (details in identify_restart.cpp). True when the final
// model was refitted; the verdicts are not revisited.
bool polishFinalModel(Loop& L);
// The backward check of the final model (identify_backward.cpp): an added effect whose size has
// vanished in the final fit (it fails the size test there) and whose removal, with the model
// refitted without it, does not raise the BIC by more than the margin is dropped, and the model
// without it is adopted (the baseline's "before" too when none is left). Returns how many were
// dropped.
int dropVanishedEffects(Loop& L);

}  // namespace stickslip::identify::detail
