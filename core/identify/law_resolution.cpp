// The final model's law channel at a finer step (identify.hpp, LawResolution).
#include <cmath>
#include <limits>

#include "identify_internal.hpp"

namespace stickslip::identify::detail {

LawResolution checkLawResolution(const Context& cx, const ExtendedModel& m, double mass, int refinement) {
    LawResolution out;
    out.refinement = refinement;
    if (refinement < 2 || cx.runs.empty()) return out;
    std::vector<LawResolution::Run> runs(cx.runs.size());
    std::vector<char> ok(cx.runs.size(), 0);
    parallelFor(cx.runs.size(), [&](size_t k) {
        const Prepared& p = cx.runs[k];
        runs[k].file = p.run->file;
        LawRun used, fine;
        std::vector<double> r, fr;
        std::vector<char> compared;
        double ss = 0, count = 0;
        if (!simulateLawRun(cx, p, m, used) || !simulateLawRun(cx, p, m, fine, refinement) ||
            !runResiduals(cx, p, m, mass, r, ss, count, nullptr, &compared, &fr, false, &used))
            return;
        // The change as the residual would see it: through the run's cleaning filters, only where
        // the law channel applies (Prepared::filtered with the same mask as runResiduals).
        const size_t n = p.size();
        std::vector<double> y(n);
        for (size_t i = 0; i < n; ++i) y[i] = p.F[i] + (fine.contactForce_N[i] - used.contactForce_N[i]);
        const bool dyn = p.run->setup == SetupKind::Dynamics;
        const std::vector<double> d = p.filtered(y, dyn ? &p.slides : nullptr);
        double sc = 0, sd = 0;
        size_t nc = 0, nd = 0;
        for (size_t i = 0; i < n; ++i) {
            if (!compared[i]) continue;
            const double c = d[i] - p.F[i];
            sc += c * c;
            ++nc;
            if (i > 0 && compared[i - 1]) {
                const double e = fr[i] - fr[i - 1];
                sd += e * e;
                ++nd;
            }
        }
        if (nc == 0 || nd == 0) return;
        runs[k].change_N = std::sqrt(sc / static_cast<double>(nc));
        runs[k].noise_N = std::sqrt(sd / (2.0 * static_cast<double>(nd)));
        ok[k] = 1;
    });
    for (size_t k = 0; k < runs.size(); ++k)
        if (!ok[k]) return out;
    out.runs = std::move(runs);
    out.checked = true;
    return out;
}

double evalSSRefined(const Context& cx, const Spec& spec, const std::map<std::string, double>& vals,
                     const std::vector<size_t>& idx, int refinement) {
    if (spec.segments) return std::numeric_limits<double>::quiet_NaN();
    double mass = std::numeric_limits<double>::quiet_NaN();
    const ExtendedModel m = buildModel(cx, spec, vals, mass);
    std::vector<double> ss(idx.size(), 0.0);
    std::vector<char> ok(idx.size(), 0);
    parallelFor(idx.size(), [&](size_t j) {
        const Prepared& p = cx.runs[idx[j]];
        LawRun law;
        std::vector<double> r;
        double n = 0;
        ok[j] = simulateLawRun(cx, p, m, law, std::max(refinement, 1)) &&
                runResiduals(cx, p, m, mass, r, ss[j], n, nullptr, nullptr, nullptr, false, &law);
    });
    double total = 0;
    for (size_t j = 0; j < idx.size(); ++j) {
        if (!ok[j]) return std::numeric_limits<double>::infinity();
        total += ss[j];
    }
    return total;
}

}  // namespace stickslip::identify::detail
