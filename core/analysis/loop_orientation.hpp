// Friction-loop orientation (paper Figs 8, 17), two measures.
//
// 1. frictionLoops — the paper's loops: each slip excursion (a run of samples with one sign of
//    V between zero crossings) is one loop in the (V, F/t_N) plane. Samples with
//    |V| < minSpeedFraction · (peak |V| of the excursion) are left out: there the stage
//    reverses and the contact is stuck or pre-sliding elastically through ε_T, a nearly
//    vertical segment in the figures whose hysteresis (always counter-clockwise for an elastic
//    predictor) would otherwise swamp the sliding loop. The remaining arc is closed by its
//    chord and its signed area (shoelace) gives the orientation. Excursions whose peak |V| is
//    below minPeakFraction · (max |V| of the record) are noise around a reversal and skipped.
//    Orientation is invariant under the point reflection (V, F) → (−V, −F), so V < 0 loops
//    count like V > 0 ones.
// 2. frictionLoopOrientation — the whole forcing cycle as one closed curve (elastic reversal
//    segments included). Per forcing cycle, the signed area by the shoelace formula
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

struct LoopOptions {
    double minSpeedFraction = 0.1;    // drop |V| below this fraction of the excursion's peak [-]
    double minPeakFraction = 0.2;     // skip excursions with a peak below this fraction of max |V| [-]
    double degenerateFraction = 1e-3; // |area| ≤ this × bounding box: degenerate [-]
};

struct FrictionLoops {
    std::vector<double> start_s;     // start time of each excursion [s]
    std::vector<double> signedArea;  // > 0 counter-clockwise [m/s · 1]
    std::vector<int> sign;           // sign of V in the excursion (+1 / −1)
    int clockwise = 0;
    int counterClockwise = 0;
    int degenerate = 0;
};

FrictionLoops frictionLoops(const std::vector<double>& t_s, const std::vector<double>& relVel_mps,
                            const std::vector<double>& ratio, const LoopOptions& opt = {});

}  // namespace stickslip
