// Savitzky–Golay smoothing and differentiation of uniformly sampled signals.
#pragma once

#include <vector>

namespace stickslip::dsp {

// Savitzky–Golay: least-squares polynomial of `polyOrder` over 2·halfWindow+1 samples at
// uniform spacing dt, evaluated for derivative `derivative` (0 smooth, 1 velocity, 2 …)
// at every sample (asymmetric windows at the ends).
std::vector<double> savitzkyGolay(const std::vector<double>& y, double dt_s, int halfWindow, int polyOrder,
                                  int derivative);

}  // namespace stickslip::dsp
