#include "stats.hpp"

#include <cmath>

#include <algorithm>

namespace stickslip::dsp {

double median(std::vector<double> v) {
    if (v.empty()) return 0.0;
    // Partial sort: only the element of rank n/2 is needed, O(n) instead of a full sort.
    const size_t mid = v.size() / 2;
    std::nth_element(v.begin(), v.begin() + static_cast<long>(mid), v.end());
    return v[mid];
}

double whiteNoiseRms(const std::vector<double>& x) {
    if (x.size() < 4) return 0.0;
    std::vector<double> d(x.size() - 3);
    for (size_t k = 0; k + 3 < x.size(); ++k) d[k] = std::abs(x[k + 3] - 3.0 * x[k + 2] + 3.0 * x[k + 1] - x[k]);
    // The median of |d| as the mean of the two middle ranks (median() keeps a sample instead).
    const size_t mid = d.size() / 2;
    std::nth_element(d.begin(), d.begin() + static_cast<long>(mid), d.end());
    double m = d[mid];
    if (d.size() % 2 == 0) m = 0.5 * (m + *std::max_element(d.begin(), d.begin() + static_cast<long>(mid)));
    return m / (0.674489750196082 * std::sqrt(20.0));
}

}  // namespace stickslip::dsp
