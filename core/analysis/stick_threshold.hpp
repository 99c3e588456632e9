// Closed-form amplitude below which the slider sticks permanently (steady state, linear):
// while stuck, the contact is a spring ε_T in series with the oscillator, so the friction
// force amplitude is |F| = A / |1/Z + 1/ε_T|; stick holds while |F| ≤ μ t_N:
//   A_s = μ t_N |1/Z + 1/ε_T|,  Z = k − m ω² + i c ω,
// which is μ t_N (1/|Z| + 1/ε_T) whenever Z is close to real and positive (small c, below resonance).
#pragma once

#include "../params.hpp"

namespace stickslip {

// A_s [m] for the law selected in p (μ and ε_T of that law).
double stickThresholdAmplitude(const SimParams& p);

}  // namespace stickslip
