#include "sampling.hpp"

#include <algorithm>
#include <cmath>

#include "stats.hpp"

namespace stickslip::dsp {

double samplingIrregularity(const std::vector<double>& t) {
    if (t.size() < 3) return 0.0;
    std::vector<double> d(t.size() - 1);
    for (size_t i = 1; i < t.size(); ++i) d[i - 1] = t[i] - t[i - 1];
    const double med = median(d);
    double worst = 0.0;
    for (double x : d) worst = std::max(worst, std::abs(x - med) / med);
    return worst;
}

std::vector<double> resampleLinear(const std::vector<double>& t, const std::vector<double>& y, double t0, double dt, size_t n) {
    std::vector<double> out(n);
    size_t j = 0;
    for (size_t i = 0; i < n; ++i) {
        const double ti = t0 + static_cast<double>(i) * dt;
        while (j + 2 < t.size() && t[j + 1] < ti) ++j;
        const double a = (ti - t[j]) / (t[j + 1] - t[j]);
        out[i] = y[j] + std::clamp(a, 0.0, 1.0) * (y[j + 1] - y[j]);
    }
    return out;
}

double estimatePeriod(const std::vector<double>& t, const std::vector<double>& y) {
    if (y.size() < 4) return 0.0;
    double m = 0, s2 = 0;
    for (double v : y) m += v;
    m /= static_cast<double>(y.size());
    for (double v : y) s2 += (v - m) * (v - m);
    const double th = 0.1 * std::sqrt(s2 / static_cast<double>(y.size()));
    std::vector<double> ups;
    bool armed = false;
    double lastNeg = t[0];
    for (size_t i = 1; i < y.size(); ++i) {
        const double v = y[i] - m, v0 = y[i - 1] - m;
        if (v < -th) armed = true;
        if (v0 <= 0.0 && v > 0.0) lastNeg = t[i - 1] + (t[i] - t[i - 1]) * (-v0) / (v - v0);
        if (armed && v > th) {
            ups.push_back(lastNeg);
            armed = false;
        }
    }
    if (ups.size() < 2) return 0.0;
    std::vector<double> d;
    for (size_t i = 1; i < ups.size(); ++i) d.push_back(ups[i] - ups[i - 1]);
    return median(d);
}

std::pair<size_t, size_t> steadyAmplitudeWindow(const std::vector<double>& y, size_t per, double fraction) {
    const size_t n = y.size();
    if (n == 0 || per < 2) return {0, n};
    std::vector<double> amp(n);
    const size_t half = per / 2;
    for (size_t i = 0; i < n; ++i) {
        const size_t a = i > half ? i - half : 0, b = std::min(n, i + half + 1);
        const auto [lo, hi] = std::minmax_element(y.begin() + static_cast<long>(a), y.begin() + static_cast<long>(b));
        amp[i] = *hi - *lo;
    }
    const double th = fraction * *std::max_element(amp.begin(), amp.end());
    size_t bestB = 0, bestE = n, bestLen = 0;
    for (size_t i = 0; i < n;) {
        if (amp[i] < th) { ++i; continue; }
        size_t j = i;
        while (j < n && amp[j] >= th) ++j;
        if (j - i > bestLen) { bestLen = j - i; bestB = i; bestE = j; }
        i = j;
    }
    return {bestB, bestE};
}

}  // namespace stickslip::dsp
