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

}  // namespace stickslip::dsp
