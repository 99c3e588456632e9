#include "stats.hpp"

#include <algorithm>

namespace stickslip::dsp {

double median(std::vector<double> v) {
    if (v.empty()) return 0.0;
    // Partial sort: only the element of rank n/2 is needed, O(n) instead of a full sort.
    const size_t mid = v.size() / 2;
    std::nth_element(v.begin(), v.begin() + static_cast<long>(mid), v.end());
    return v[mid];
}

}  // namespace stickslip::dsp
