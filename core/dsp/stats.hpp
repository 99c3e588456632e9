// Order statistics shared by the pipelines (sampling step, start values, recipes).
#pragma once

#include <vector>

namespace stickslip::dsp {

// The median of v as one of its elements: for an even count, the upper of the two middle
// values (rank n/2 of 0..n−1), not their mean, so that the result is always a sample that
// occurred (a sampling step, a measured ratio) and every caller keeps the numbers it had
// before the copies were merged. 0 for an empty v: callers treat 0 as "nothing to go on"
// (a step or a ratio of 0 is refused downstream), so no exception on a worker path.
double median(std::vector<double> v);

// The RMS of the white noise on a record sampled fast enough that its signal is smooth over
// order + 1 samples: the order-th difference (order 1–4, default 3; third: d_k = x_{k+3} −
// 3x_{k+2} + 3x_{k+1} − x_k) of white noise of RMS σ has RMS σ √C(2·order, order) (√20 for the
// third), a smooth signal's is O((ω Δt)^order) of it; the median of |d| (MAD of a zero-mean
// normal, 0.6745 of its RMS) is not moved by the few corners (stick–slip onsets) where the
// signal is not smooth. 0 for fewer than order + 1 samples; NaN for an order outside 1–4.
double whiteNoiseRms(const std::vector<double>& x, int order = 3);

}  // namespace stickslip::dsp
