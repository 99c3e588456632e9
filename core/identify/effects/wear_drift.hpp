// wear_drift: μ drifts with the accumulated slip distance.
#pragma once

#include "effect.hpp"

namespace stickslip::identify {

// μ(s) = μ + dμ/ds · s, with s the slip distance accumulated since the first sample of the
// dataset (runs recorded in order on one specimen carry their slip over).
struct WearDrift {
    double dmu_ds_per_m = 0.0;  // dμ/ds [1/m]

    double muShift(double accumulatedSlip_m) const { return dmu_ds_per_m * accumulatedSlip_m; }

    static EffectInfo info() {
        return {"wear_drift",
                "Wear, running-in and transfer films change the surfaces as they slide, so the "
                "coefficient of friction drifts slowly with the distance slid. Runs recorded one "
                "after another on the same specimen then show a friction level that creeps from "
                "run to run and within a run.",
                "Slow trend of the residual with the accumulated slip distance (and so with run "
                "index and cycle index), with the sign of the force: the residual times sign(V) "
                "drifts.",
                {{"dmu_ds_per_m", "1/m", 0.0, -1.0, 1.0, false, 0.0, true}},
                {"accumulated_slip", "cycle_index", "run_index"},
                {true, true}};
    }
};

}  // namespace stickslip::identify
