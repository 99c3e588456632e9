// Classification of a settled motion from its Poincaré section: permanent stick,
// period-n (n = 1…maxPeriod) or irregular (quasi-periodic or chaotic — use the Lyapunov
// exponent to tell them apart).
//
// Stated tolerance: the section is period-n when, for every sample i with i + n < size,
//   |x_{i+n} − x_i| ≤ relTol · xScale  and  |V_{i+n} − V_i| ≤ relTol · vScale,
// with xScale = max(A, μ t_N / k) and vScale = xScale · ω (ω the forcing frequency);
// the smallest such n is the period. Permanent stick: no sampled step slipped.
#pragma once

#include <string>

#include "../params.hpp"
#include "poincare.hpp"

namespace stickslip {

enum class MotionClass { Stick, Periodic, Irregular };
const char* toString(MotionClass);  // "stick", "periodic", "irregular"

struct ClassifyOptions {
    int maxPeriod = 16;     // largest period tested [cycles]
    double relTol = 1e-4;   // relative tolerance of the period test (see above) [-]
    ParamIssues validate() const;
};

struct Classification {
    MotionClass motion = MotionClass::Irregular;
    int period = 0;               // n for Periodic, 1 for Stick, 0 for Irregular
    double stickFraction = 0;     // copied from the section [-]
    double maxRelVel_mps = 0;     // copied from the section [m/s]
    double bestMismatch = 0;      // smallest normalised max |P_{i+n} − P_i| over n (÷ relTol·scale) [-]
};

struct ClassifyScales {
    double x_m = 1e-3;
    double v_mps = 1e-2;
};
ClassifyScales classifyScales(const SimParams& p);

Classification classifyMotion(const PoincareSection& s, const ClassifyScales& sc, const ClassifyOptions& opt = {});

}  // namespace stickslip
