// The time base of a record: how irregular it is, resampling to a uniform step, the period of
// its dominant oscillation, and the stretch where that oscillation's amplitude is steady.
#pragma once

#include <cstddef>
#include <utility>
#include <vector>

namespace stickslip::dsp {

// Largest relative deviation of the sampling interval from its median.
double samplingIrregularity(const std::vector<double>& t);
// Linear interpolation of (t, y) at t0 + i·dt, i = 0..n−1.
std::vector<double> resampleLinear(const std::vector<double>& t, const std::vector<double>& y, double t0, double dt, size_t n);

// Period of the dominant oscillation of y (median spacing of upward mean crossings with
// hysteresis); 0 if fewer than two crossings.
double estimatePeriod(const std::vector<double>& t, const std::vector<double>& y);
// Indices [begin, end) where the moving peak-to-peak amplitude of y over one period is at
// least `fraction` of its maximum: the steady part of a tapered (ramp up / hold / ramp down)
// excitation.
std::pair<size_t, size_t> steadyAmplitudeWindow(const std::vector<double>& y, size_t periodSamples, double fraction);

}  // namespace stickslip::dsp
