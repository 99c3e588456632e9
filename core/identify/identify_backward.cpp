// The backward check of the loop's final model (step 5 of the selection rule, IdentifyOptions in
// identify.hpp). An effect is judged when it is added, against the model of that round; a later
// round may refit that model into another minimum (restartFromCandidates) or add an effect that
// takes over its part, and the effect's size can then vanish in the final fit. Such an effect is
// no longer evidence of anything: it is dropped when the model without it, refitted, is as good
// by the loop's own criterion.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "fit_internal.hpp"
#include "identify_loop.hpp"

namespace stickslip::identify::detail {

namespace {

// The first added effect not in `kept` whose size fails the size test on the current fit, with
// its size figures in `sc`. The size test uses the Jacobian's standard error × sqrt(τ_int): the
// final model's leave-one-run-out refits are not kept, and a vanished size has a Jacobian error
// of the size's own order (N005: τ = 1.0e-6 ± 1.1e-6 s).
bool firstVanished(const Loop& L, const std::vector<std::string>& kept, CandidateScore& sc) {
    for (const std::string& e : L.spec.effects) {
        if (std::find(kept.begin(), kept.end(), e) != kept.end()) continue;
        CandidateScore s;
        s.name = e;
        if (!passesSizeTest(L.cx, s, L.cur, {}, L.curDiag.integratedAcfTime)) {
            sc = s;
            return true;
        }
    }
    return false;
}

std::string vanishedText(const CandidateScore& sc) {
    return "its size " + sc.sizeParam + " = " + fmt(sc.sizeValue) + " in the final fit is not identified (|value - " +
           fmt(sc.sizeNull) + "| <= " + fmt(sc.sizeCritical) + " x " + fmt(sc.sizeStderr) + ", " + sc.sizeStderrKind + ")";
}

}  // namespace

int dropVanishedEffects(Loop& L) {
    int dropped = 0;
    std::vector<std::string> kept;
    CandidateScore sc;
    while (!L.cancelled() && firstVanished(L, kept, sc)) {
        const std::string e = sc.name;
        Spec without = L.spec;
        without.effects.erase(std::find(without.effects.begin(), without.effects.end(), e));
        L.progress("backward check: the model without " + e, 1.0);
        const FitOutcome g = fitSpec(L.cx, without, withoutEffect(L.cx, without, e, L.cur.values), L.fitIdx, 1, L.res.fits);
        // The effect's ΔBIC against the model without it, both at their own minimum, as the round
        // that added it scored it (same τ_int for both).
        const double tau = L.curDiag.integratedAcfTime;
        const double dBic = g.ok ? L.bicOf(L.cur, L.spec, tau) - L.bicOf(g, without, tau) : -INFINITY;
        if (dBic < -L.opt.bicMargin) {
            kept.push_back(e);  // the fit still needs it: a size the data resolve poorly, not a vanished one
            continue;
        }
        const std::string why = vanishedText(sc) + ", and the model without it, refitted, is as good (dBIC of keeping it " +
                                fmt(dBic) + ", not below -" + fmt(L.opt.bicMargin) + ")";
        CandidateScore& s = L.scores[e];
        s.accepted = false;
        s.reason = "added in round " + std::to_string(s.round) + ", dropped by the backward check of the final model: " + why;
        auto& added = L.res.effectsAdded;
        added.erase(std::remove_if(added.begin(), added.end(), [&](const AddedEffect& a) { return a.name == e; }), added.end());
        L.spec = std::move(without);
        L.cur = g;
        std::string note = "backward check: " + e + " dropped (" + why + ")";
        if (L.spec.effects.empty()) {
            // The refit is a better minimum of the baseline than the one the loop started from:
            // it is "before" from here on, and the note says where the first fit ended.
            note += "; the baseline is that refit (sum of squares " + fmt(L.cur.ss) + "; the first baseline fit ended at " +
                    fmt(L.baseFit.ss) + ")";
            adoptBaseline(L, L.res.baselineNote.empty() ? note : L.res.baselineNote + "; " + note);
        } else {
            adoptCurrent(L, note);
        }
        kept.clear();  // the refit moved the others: each is checked again
        ++dropped;
    }
    return dropped;
}

}  // namespace stickslip::identify::detail
