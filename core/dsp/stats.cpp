#include "stats.hpp"

#include <cmath>

#include <algorithm>
#include <limits>

namespace stickslip::dsp {

double median(std::vector<double> v) {
    if (v.empty()) return 0.0;
    // Partial sort: only the element of rank n/2 is needed, O(n) instead of a full sort.
    const size_t mid = v.size() / 2;
    std::nth_element(v.begin(), v.begin() + static_cast<long>(mid), v.end());
    return v[mid];
}

double whiteNoiseRms(const std::vector<double>& x, int order) {
    if (order < 1 || order > 4) return std::numeric_limits<double>::quiet_NaN();
    const size_t n = static_cast<size_t>(order);
    if (x.size() < n + 1) return 0.0;
    // Binomial weights from the newest sample down: x_{k+n} − n x_{k+n−1} + … (summed in that
    // order, so order 3 is bit for bit x3 − 3x2 + 3x1 − x0).
    static constexpr double kWeight[5][5] = {{1}, {1, -1}, {1, -2, 1}, {1, -3, 3, -1}, {1, -4, 6, -4, 1}};
    // Var of the n-th difference of white noise: σ² · C(2n, n).
    static constexpr double kGain[] = {1.0, 2.0, 6.0, 20.0, 70.0};
    std::vector<double> d(x.size() - n);
    for (size_t k = 0; k < d.size(); ++k) {
        double s = x[k + n];
        for (size_t j = 1; j <= n; ++j) s += kWeight[n][j] * x[k + n - j];
        d[k] = std::abs(s);
    }
    // The median of |d| as the mean of the two middle ranks (median() keeps a sample instead).
    const size_t mid = d.size() / 2;
    std::nth_element(d.begin(), d.begin() + static_cast<long>(mid), d.end());
    double m = d[mid];
    if (d.size() % 2 == 0) m = 0.5 * (m + *std::max_element(d.begin(), d.begin() + static_cast<long>(mid)));
    return m / (0.674489750196082 * std::sqrt(kGain[n]));
}

}  // namespace stickslip::dsp
