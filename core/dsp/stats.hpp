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

// The RMS of the white noise on a record sampled fast enough that its signal is smooth over four
// samples: the third difference d_k = x_{k+3} − 3x_{k+2} + 3x_{k+1} − x_k of white noise of RMS σ
// has RMS σ √20, a smooth signal's is O((ω Δt)³) of it; the median of |d| (MAD of a zero-mean
// normal, 0.6745 of its RMS) is not moved by the few corners (stick–slip onsets) where the
// signal is not smooth. 0 for fewer than 4 samples.
double whiteNoiseRms(const std::vector<double>& x);

}  // namespace stickslip::dsp
