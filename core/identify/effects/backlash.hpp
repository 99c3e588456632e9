// backlash: a dead band in the slip before the contact engages.
#pragma once

#include <cmath>

#include "effect.hpp"

namespace stickslip::identify {

// Play of half-width δ between the drive and the contact: the tangential spring sees the
// elastic coordinate w = g − λ only beyond the play, F = ε_T dz(w) with
// dz(w) = sign(w) max(|w| − δ, 0). After a reversal the force first falls to zero, stays
// there while the play (2δ) is crossed, then builds up on the other side.
struct Backlash {
    double halfWidth_m = 1e-5;  // δ, half the dead band [m]

    double deadZone(double w) const {
        const double a = std::abs(w) - halfWidth_m;
        return a <= 0.0 ? 0.0 : (w > 0.0 ? a : -a);
    }
    bool inPlay(double w) const { return std::abs(w) <= halfWidth_m; }
    // The coordinate w at which a contact of stiffness ε carries force F with the play taken up
    // on the side F acts on (ε dz(w) = F): how a run or segment that starts loaded begins.
    double loadedCoordinate(double force, double eps) const {
        return force / eps + (force >= 0.0 ? halfWidth_m : -halfWidth_m);
    }

    static EffectInfo info() {
        return {"backlash",
                "A clearance in the drive train (pins in holes, loose band, bolted joints) lets the "
                "driving side move a little without loading the contact after every reversal. The "
                "measured force then drops to about zero at reversal, stays flat while the play is "
                "crossed, and rises only after it: a dead band of width 2*delta in the slip.",
                "Residual right after each reversal, of the sign of the previous slip (the model "
                "builds force too early): correlation with 'time since last reversal' and with the "
                "slip displacement near reversals.",
                {{"halfWidth_m", "m", 5e-5, 1e-7, 2e-2, true}},
                {"time_since_reversal", "displacement"},
                {true, true}};
    }
};

}  // namespace stickslip::identify
