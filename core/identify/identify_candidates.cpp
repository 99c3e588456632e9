// The candidates of one round of the missing-effect loop (identify.cpp), each fitted on top of
// the current model and scored; the round's fits one per core.
#include <algorithm>
#include <chrono>
#include <mutex>
#include <numeric>
#include <optional>

#include "fit_internal.hpp"
#include "identify_loop.hpp"

namespace stickslip::identify::detail {

// The candidate's figures from its fit: ΔBIC against the model it extends, fit error, its
// parameters and how its size trades off with the others.
void scoreFit(const Loop& L, Tried& t) {
    CandidateScore& sc = t.sc;
    const FitOutcome& f = t.fit;
    const double tauInt = t.spec.segments == L.spec.segments ? L.curDiag.integratedAcfTime : 1.0;
    sc.deltaBic = L.bicOf(f, t.spec, tauInt) - t.bicBase;
    sc.neff = effectiveCount(static_cast<double>(f.count), L.neffCap(f, t.spec, tauInt, &sc.neffLimit));
    sc.fitNrmse = f.nrmse(0.0);
    sc.params = effectParams(f, sc.name);
    sc.sizeCorrelation = sizeCorrelations(f.fit, sc.name);
    sc.tradesOffWithBaseline = baselineTradeOff(sc, L.opt.confoundedVif);
}

namespace {

// Whether candidate c is fitted with the segment residual on top of the round's segment
// baseline (Round::segBaseline): a stick-phase effect under the Auto residual of dynamics runs.
bool needsSegmentBaseline(const Loop& L, const std::string& c) {
    return L.cx.anyDynamics && !L.spec.segments && actsInStick(c) && L.opt.dynamicsResidual == DynamicsResidual::Auto;
}

// A candidate's fit (fitCandidate): scored, or not, with the reason in `score` (and, when its
// size ended on a physical bound, the fit in `onBound`), the fits it took and its wall time.
struct CandidateFit {
    bool ran = false;
    std::optional<Tried> scored;
    CandidateScore score;
    std::optional<Tried> onBound;
    long fits = 0;
    double wall_s = 0;
};

// Fits candidate c on top of the current model (warm start from a scan around the current
// point, or from `previous`, c's fit before the current model was refitted, when that fits the
// runs better; retried from another start when it ends above the model it contains or with its
// size on a physical bound). Reads the loop and the round only (the round's segment baseline
// made beforehand when c needs it), so the round's candidates can be fitted at the same time.
CandidateFit fitCandidate(const Loop& L, const Round& R, const std::string& c, const Tried* previous) {
    CandidateFit out;
    out.ran = true;
    CandidateScore& sc = out.score;
    sc.name = c;
    sc.round = R.number;
    Spec s2 = L.spec;
    s2.effects.push_back(c);
    const FitOutcome* base = &L.cur;
    double bicBase = R.bicCur;
    if (needsSegmentBaseline(L, c)) {
        const FitOutcome& sb = R.segBase;
        if (!R.segBaseTried || !sb.ok) {
            sc.reason = "baseline fit with the segment residual failed: " + sb.message;
            return out;
        }
        s2.segments = true;
        base = &sb;
        bicBase = L.bicOf(sb, R.segSpec, 1.0);
    }
    sc.residual = L.residualName(s2);
    // After a restart the candidate's own earlier fit is often nearer its new minimum than the
    // scan: the restart came from such a point (restartFromCandidates).
    const bool usePrevious = previous && previous->spec.segments == s2.segments && previous->fit.ok;
    const auto st = scannedStart(L.cx, s2, c, base->values, L.fitIdx, usePrevious ? &previous->fit.values : nullptr);
    FitOutcome f = fitSpec(L.cx, s2, st, L.fitIdx, 1, out.fits);
    if (!f.ok) {
        sc.reason = "fit failed: " + f.message;
        return out;
    }
    // The candidate contains the current model (its effect where it vanishes): a fit that
    // ends above the current model's sum of squares stopped in a worse local minimum — a
    // solver failure, retried from the current model's own point.
    std::string startNote;
    if (f.ss > base->ss * (1.0 + 1e-6)) {
        const FitOutcome g = fitSpec(L.cx, s2, retryStart(L.cx, c, base->values, st, ""), L.fitIdx, 1, out.fits);
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
    std::string side = sizeBound(L.cx, c, f.values);
    if (!side.empty()) {
        const FitOutcome g = fitSpec(L.cx, s2, retryStart(L.cx, c, f.values, st, side), L.fitIdx, 1, out.fits);
        if (g.ok && sizeBound(L.cx, c, g.values).empty() && g.ss < f.ss) {
            f = g;
            startNote += "the first start ended on the " + side + " bound of the size, a start halfway to it did not "
                         "(a solver failure): refitted. ";
            side.clear();
        }
    }
    sc.startNote = startNote;
    Tried t{sc, std::move(f), s2, bicBase};
    scoreFit(L, t);
    if (!side.empty()) {
        EffectInfo info;
        findEffect(c, info);
        t.sc.reason = startNote + "parameter " + info.params.front().name + " ended on its physical " + side +
                      " bound from two starts (scanned, and halfway to the bound): the data's answer, not a solver "
                      "failure; not identified (dBIC " + fmt(t.sc.deltaBic) + " not credited)";
        out.score = t.sc;
        out.onBound = std::move(t);
        return out;
    }
    out.scored = std::move(t);
    return out;
}

}  // namespace

std::vector<Tried> fitCandidates(Loop& L, Round& R, const std::vector<std::string>& cands,
                                 const std::vector<Tried>& previous) {
    std::vector<std::string> todo;
    std::vector<const Tried*> prevs;
    for (const std::string& c : cands) {
        if (std::find(L.spec.effects.begin(), L.spec.effects.end(), c) != L.spec.effects.end()) continue;
        todo.push_back(c);
        const auto prev = std::find_if(previous.begin(), previous.end(), [&](const Tried& t) { return t.sc.name == c; });
        prevs.push_back(prev != previous.end() ? &*prev : nullptr);
    }
    if (std::any_of(todo.begin(), todo.end(), [&](const std::string& c) { return needsSegmentBaseline(L, c); }) &&
        !L.cancelled())
        R.segBaseline(L);
    // The candidates are fitted at the same time, one per core (each fit's own batches then run
    // on its thread, parallelFor), instead of one fit's batches over the cores, whose unequal
    // runs leave a core idle (measured: the damper ~12 % faster, D01 unchanged; session 57 in
    // docs/identify-results.md). The outcome does not depend on the thread count or the order in
    // which the fits finish: each writes only its own slot, merged below in catalogue order.
    // Longest first by what each took last time (the previous round's, or this round's before
    // a restart), so that no long fit starts last: only the wall time depends on this order.
    std::vector<size_t> order(todo.size());
    std::iota(order.begin(), order.end(), size_t{0});
    const auto took = [&](size_t k) {
        const auto it = L.candidateSeconds.find(todo[k]);
        return it != L.candidateSeconds.end() ? it->second : 0.0;
    };
    std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return took(a) > took(b); });
    std::vector<CandidateFit> fitted(todo.size());
    if (!L.cancelled()) {
        L.progress(R.label() + ": " + std::to_string(todo.size()) + " candidate fits", 0.0);
        std::mutex reporting;
        size_t done = 0;
        parallelFor(todo.size(), [&](size_t o) {
            const size_t k = order[o];
            if (L.cancelled()) return;
            const auto t0 = Clock::now();
            fitted[k] = fitCandidate(L, R, todo[k], prevs[k]);
            fitted[k].wall_s = std::chrono::duration<double>(Clock::now() - t0).count();
            const std::lock_guard<std::mutex> lock(reporting);
            ++done;
            if (L.opt.progress)
                L.opt.progress(R.label() + ": " + todo[k] + " fitted", static_cast<double>(done) / todo.size());
        });
    }
    std::vector<Tried> tried;
    for (size_t k = 0; k < fitted.size(); ++k) {
        CandidateFit& f = fitted[k];
        if (!f.ran) continue;
        L.candidateSeconds[todo[k]] = f.wall_s;
        L.res.fits += f.fits;
        CandidateScore& sc = f.scored ? f.scored->sc : f.score;  // the score the report keeps
        sc.fitWall_s = f.wall_s;
        sc.fits = f.fits;
        if (f.scored) tried.push_back(std::move(*f.scored));
        else L.scores[f.score.name] = f.score;
        if (f.onBound) R.onBound.push_back(std::move(*f.onBound));
    }
    return tried;
}

}  // namespace stickslip::identify::detail
