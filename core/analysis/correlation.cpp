#include "correlation.hpp"

#include <fftw3.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "fftw_lock.hpp"

namespace stickslip {

namespace {

std::size_t nextFastSize(std::size_t n) {
    std::size_t p = 1;
    while (p < n) p *= 2;
    return p;
}

// Raw cross-correlation sums c(τ) = Σ_t a(t) b(t + τ) for τ = −maxLag … maxLag, by FFT with
// zero padding to ≥ n + maxLag (so the circular product equals the linear one on those lags).
std::vector<double> correlationSums(const std::vector<double>& a, const std::vector<double>& b, std::size_t maxLag) {
    const std::size_t n = a.size();
    const bool same = &a == &b;   // autocorrelation: one forward transform, conj(A)·A = |A|²
    const std::size_t L = nextFastSize(n + maxLag + 1);
    const std::size_t nf = L / 2 + 1;
    double* ra = fftw_alloc_real(L);
    double* rb = same ? nullptr : fftw_alloc_real(L);
    fftw_complex* A = fftw_alloc_complex(nf);
    fftw_complex* B = same ? nullptr : fftw_alloc_complex(nf);
    fftw_plan pa, pb = nullptr, pinv;
    {
        std::lock_guard<std::mutex> lk(detail::fftwPlanMutex());
        pa = fftw_plan_dft_r2c_1d(static_cast<int>(L), ra, A, FFTW_ESTIMATE);
        if (!same) pb = fftw_plan_dft_r2c_1d(static_cast<int>(L), rb, B, FFTW_ESTIMATE);
        pinv = fftw_plan_dft_c2r_1d(static_cast<int>(L), A, ra, FFTW_ESTIMATE);
    }
    std::fill(ra, ra + L, 0.0);
    if (!same) std::fill(rb, rb + L, 0.0);
    std::copy(a.begin(), a.end(), ra);
    if (!same) std::copy(b.begin(), b.end(), rb);
    fftw_execute(pa);
    if (!same) fftw_execute(pb);
    // c(τ) = IFFT(conj(A) · B)(τ)
    if (same) {
        for (std::size_t k = 0; k < nf; ++k) {
            A[k][0] = A[k][0] * A[k][0] + A[k][1] * A[k][1];
            A[k][1] = 0.0;
        }
    }
    for (std::size_t k = 0; k < nf && !same; ++k) {
        const double re = A[k][0] * B[k][0] + A[k][1] * B[k][1];
        const double im = A[k][0] * B[k][1] - A[k][1] * B[k][0];
        A[k][0] = re;
        A[k][1] = im;
    }
    fftw_execute(pinv);  // overwrites ra with L · c(τ), τ ≥ 0 at [τ], τ < 0 at [L + τ]
    std::vector<double> out(2 * maxLag + 1);
    for (std::size_t i = 0; i <= 2 * maxLag; ++i) {
        const long tau = static_cast<long>(i) - static_cast<long>(maxLag);
        const std::size_t idx = tau >= 0 ? static_cast<std::size_t>(tau) : L - static_cast<std::size_t>(-tau);
        out[i] = ra[idx] / static_cast<double>(L);
    }
    {
        std::lock_guard<std::mutex> lk(detail::fftwPlanMutex());
        fftw_destroy_plan(pa);
        if (pb) fftw_destroy_plan(pb);
        fftw_destroy_plan(pinv);
    }
    fftw_free(ra);
    if (rb) fftw_free(rb);
    fftw_free(A);
    if (B) fftw_free(B);
    return out;
}

bool demean(const std::vector<double>& x, std::vector<double>& out, double& sd) {
    const std::size_t n = x.size();
    if (n < 2) return false;
    double mean = 0;
    for (double v : x) {
        if (!std::isfinite(v)) return false;
        mean += v;
    }
    mean /= static_cast<double>(n);
    out.resize(n);
    double ss = 0;
    for (std::size_t i = 0; i < n; ++i) {
        out[i] = x[i] - mean;
        ss += out[i] * out[i];
    }
    sd = std::sqrt(ss / static_cast<double>(n));
    return sd > 0;
}

}  // namespace

Correlation autocorrelation(const std::vector<double>& x, double fs, std::size_t maxLag) {
    Correlation c;
    std::vector<double> d;
    double sd = 0;
    if (!(fs > 0) || !demean(x, d, sd)) return c;
    maxLag = std::min(maxLag, x.size() - 1);
    const std::vector<double> sums = correlationSums(d, d, maxLag);
    const double norm = sums[maxLag];  // lag 0
    c.lag_s.resize(maxLag + 1);
    c.r.resize(maxLag + 1);
    for (std::size_t k = 0; k <= maxLag; ++k) {
        c.lag_s[k] = static_cast<double>(k) / fs;
        c.r[k] = sums[maxLag + k] / norm;
    }
    return c;
}

double correlationDecayTime(const Correlation& ac, double level) {
    if (ac.r.size() < 2) return std::numeric_limits<double>::quiet_NaN();
    // Scan from the longest lag backwards for the last lag with |r| ≥ level.
    for (std::size_t k = ac.r.size(); k-- > 0;) {
        if (std::abs(ac.r[k]) >= level) {
            if (k + 1 >= ac.r.size()) return std::numeric_limits<double>::quiet_NaN();  // never decays
            // Linear interpolation between k and k + 1 for the crossing of |r| = level.
            const double a = std::abs(ac.r[k]), b = std::abs(ac.r[k + 1]);
            const double s = a > b ? (a - level) / (a - b) : 0.0;
            return ac.lag_s[k] + s * (ac.lag_s[k + 1] - ac.lag_s[k]);
        }
    }
    return 0.0;
}

Correlation crossCorrelation(const std::vector<double>& x, const std::vector<double>& y, double fs,
                             std::size_t maxLag) {
    Correlation c;
    if (x.size() != y.size() || !(fs > 0)) return c;
    std::vector<double> dx, dy;
    double sx = 0, sy = 0;
    if (!demean(x, dx, sx) || !demean(y, dy, sy)) return c;
    maxLag = std::min(maxLag, x.size() - 1);
    const std::vector<double> sums = correlationSums(dx, dy, maxLag);
    const double norm = static_cast<double>(x.size()) * sx * sy;
    c.lag_s.resize(sums.size());
    c.r.resize(sums.size());
    for (std::size_t i = 0; i < sums.size(); ++i) {
        c.lag_s[i] = (static_cast<double>(i) - static_cast<double>(maxLag)) / fs;
        c.r[i] = sums[i] / norm;
    }
    return c;
}

PhaseLag stageSliderPhaseLag(const std::vector<double>& stage, const std::vector<double>& slider, double fs,
                             double forcingFrequency_Hz, double naturalFrequency_rad_s) {
    PhaseLag out;
    if (!(forcingFrequency_Hz > 0) || !(fs > 0)) return out;
    const std::size_t maxLag = static_cast<std::size_t>(std::floor(0.5 * fs / forcingFrequency_Hz));
    // r(τ) = corr(stage(t), slider(t + τ)): the slider repeats the stage τ later.
    const Correlation c = crossCorrelation(stage, slider, fs, maxLag);
    if (c.r.size() < 3) return out;
    std::size_t best = 0;
    for (std::size_t i = 1; i < c.r.size(); ++i)
        if (c.r[i] > c.r[best]) best = i;
    double lag = c.lag_s[best];
    if (best > 0 && best + 1 < c.r.size()) {
        const double a = c.r[best - 1], b = c.r[best], d = c.r[best + 1];
        const double den = a - 2 * b + d;
        if (den < 0) lag += 0.5 * (a - d) / den / fs;
    }
    out.lag_s = lag;
    out.nondimensional = lag * naturalFrequency_rad_s;
    out.fractionOfPeriod = lag * forcingFrequency_Hz;
    out.peak = c.r[best];
    out.ok = true;
    return out;
}

}  // namespace stickslip
