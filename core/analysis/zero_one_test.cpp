#include "zero_one_test.hpp"

#include <algorithm>
#include <cmath>

namespace stickslip {

ZeroOneResult zeroOneTest(const std::vector<double>& phi, const ZeroOneOptions& opt) {
    ZeroOneResult res;
    const std::size_t N = phi.size();
    const int div = std::max(2, opt.nCutDivisor);
    const std::size_t ncut = N / static_cast<std::size_t>(div);
    if (N < 50 || ncut < 5) { res.message = "series too short for the 0-1 test (need >= 50 samples)"; return res; }
    if (opt.nc < 1 || !(opt.cMin > 0 && opt.cMax > opt.cMin && opt.cMax < 3.14159265358979)) {
        res.message = "need nc >= 1 and 0 < cMin < cMax < π";
        return res;
    }
    double mean = 0, lo = phi[0], hi = phi[0];
    for (double v : phi) {
        if (!std::isfinite(v)) { res.message = "series contains non-finite values"; return res; }
        mean += v;
        lo = std::min(lo, v);
        hi = std::max(hi, v);
    }
    mean /= static_cast<double>(N);
    if (!(hi - lo > opt.constantTol * std::max(std::abs(hi), std::abs(lo)))) {
        res.K = 0.0;
        res.ok = true;
        res.message = "constant within tolerance: regular (fixed point)";
        return res;
    }
    std::vector<double> p(N), q(N), D(ncut);
    std::vector<double> ns(ncut);
    for (std::size_t n = 0; n < ncut; ++n) ns[n] = static_cast<double>(n + 1);
    const double golden = 0.6180339887498949;
    for (int ic = 0; ic < opt.nc; ++ic) {
        // Low-discrepancy c values: the golden-ratio sequence, deterministic and portable.
        const double frac = std::fmod(0.5 + golden * ic, 1.0);
        const double c = opt.cMin + (opt.cMax - opt.cMin) * frac;
        double ps = 0, qs = 0;
        for (std::size_t j = 0; j < N; ++j) {
            const double jc = static_cast<double>(j + 1) * c;
            ps += phi[j] * std::cos(jc);
            qs += phi[j] * std::sin(jc);
            p[j] = ps;
            q[j] = qs;
        }
        for (std::size_t n = 1; n <= ncut; ++n) {
            double m = 0;
            const std::size_t cnt = N - n;
            for (std::size_t j = 0; j < cnt; ++j) {
                const double dp = p[j + n] - p[j], dq = q[j + n] - q[j];
                m += dp * dp + dq * dq;
            }
            m /= static_cast<double>(cnt);
            // Subtract the oscillatory term of a regular mean (modified mean square displacement).
            const double nd = static_cast<double>(n);
            D[n - 1] = m - mean * mean * (1 - std::cos(nd * c)) / (1 - std::cos(c));
        }
        // K_c = correlation coefficient of (n, D(n)).
        double mx = 0, my = 0;
        for (std::size_t i = 0; i < ncut; ++i) { mx += ns[i]; my += D[i]; }
        mx /= static_cast<double>(ncut);
        my /= static_cast<double>(ncut);
        double sxy = 0, sxx = 0, syy = 0;
        for (std::size_t i = 0; i < ncut; ++i) {
            sxy += (ns[i] - mx) * (D[i] - my);
            sxx += (ns[i] - mx) * (ns[i] - mx);
            syy += (D[i] - my) * (D[i] - my);
        }
        const double kc = (sxx > 0 && syy > 0) ? sxy / std::sqrt(sxx * syy) : 0.0;
        res.c.push_back(c);
        res.Kc.push_back(kc);
    }
    std::vector<double> sorted = res.Kc;
    std::sort(sorted.begin(), sorted.end());
    const std::size_t m = sorted.size();
    res.K = m % 2 ? sorted[m / 2] : 0.5 * (sorted[m / 2 - 1] + sorted[m / 2]);
    res.ok = true;
    return res;
}

}  // namespace stickslip
