// Friction-loop orientation (paper Figs 8, 17): per forcing cycle, the signed area of the
// loop traced by (V, F/t_N) with V on the horizontal axis, by the shoelace formula
//   area = ½ Σ (V_i ρ_{i+1} − V_{i+1} ρ_i)  (closed over the cycle).
// area > 0: counter-clockwise; area < 0: clockwise; |area| ≤ degenerateFraction × (bounding
// box area): degenerate (e.g. a flat stick segment).
#pragma once

#include <vector>

namespace stickslip {

struct LoopOrientation {
    std::vector<double> cycleStart_s;  // start time of each complete cycle [s]
    std::vector<double> signedArea;    // [m/s · 1] per cycle
    int clockwise = 0;
    int counterClockwise = 0;
    int degenerate = 0;
};

// Cycles are consecutive windows of length period_s from t_s.front(); incomplete ones are dropped.
LoopOrientation frictionLoopOrientation(const std::vector<double>& t_s, const std::vector<double>& relVel_mps,
                                        const std::vector<double>& ratio, double period_s,
                                        double degenerateFraction = 1e-3);

}  // namespace stickslip
