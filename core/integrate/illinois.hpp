// Illinois (regula falsi with halving of the stagnant end; Dowell & Jarratt 1971): the root of
// g in a bracket [lo, hi] whose ends have g of opposite signs. One copy for the integrator's
// event roots (stick → slip onsets on the scheme's trial and on the closed form, velocity
// reversals on a step's interpolant).
#pragma once

namespace stickslip::detail {

// lo's side is where g > 0 (loPositive) or g ≤ 0 (not). Iterates until hi − lo ≤ width or 100
// evaluations; returns the last point found on lo's side, so the caller keeps that side's regime.
template <class G>
double illinois(G&& g, double lo, double glo, double hi, double ghi, double width, bool loPositive) {
    int side = 0;
    for (int it = 0; it < 100 && hi - lo > width; ++it) {
        double t = (lo * ghi - hi * glo) / (ghi - glo);
        if (!(t > lo && t < hi)) t = 0.5 * (lo + hi);
        const double gt = g(t);
        if ((gt > 0.0) == loPositive) { lo = t; glo = gt; if (side == -1) ghi *= 0.5; side = -1; }
        else { hi = t; ghi = gt; if (side == 1) glo *= 0.5; side = 1; }
    }
    return lo;
}

}  // namespace stickslip::detail
