#include "spectrum.hpp"

#include <fftw3.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "fftw_lock.hpp"

namespace stickslip {

namespace detail {
std::mutex& fftwPlanMutex() {
    static std::mutex m;  // function-local: one lock for FFTW's planner (a library-wide resource)
    return m;
}
}  // namespace detail

PowerSpectrum powerSpectrum(const std::vector<double>& x, double fs, const WelchOptions& opt) {
    PowerSpectrum out;
    const std::size_t n = x.size();
    if (!(fs > 0) || !std::isfinite(fs)) { out.message = "sample rate must be > 0"; return out; }
    if (!(opt.overlap >= 0 && opt.overlap < 1)) { out.message = "overlap must be in [0, 1)"; return out; }
    for (double v : x)
        if (!std::isfinite(v)) { out.message = "series contains non-finite values"; return out; }
    std::size_t L = opt.segmentLength;
    if (L == 0) {
        L = 16;
        while (L * 2 <= n / 4) L *= 2;
    }
    if (n < 16 || L < 4 || L > n) { out.message = "series too short for the segment length (need >= 16 samples)"; return out; }
    const std::size_t hop = std::max<std::size_t>(1, static_cast<std::size_t>(std::floor(L * (1.0 - opt.overlap))));
    std::vector<double> w(L);
    double wss = 0;  // Σ w²
    for (std::size_t i = 0; i < L; ++i) {
        w[i] = 0.5 - 0.5 * std::cos(2 * std::numbers::pi * static_cast<double>(i) / static_cast<double>(L));  // periodic Hann
        wss += w[i] * w[i];
    }
    const std::size_t nf = L / 2 + 1;
    double* in = fftw_alloc_real(L);
    fftw_complex* spec = fftw_alloc_complex(nf);
    fftw_plan plan;
    {
        std::lock_guard<std::mutex> lk(detail::fftwPlanMutex());
        plan = fftw_plan_dft_r2c_1d(static_cast<int>(L), in, spec, FFTW_ESTIMATE);
    }
    out.psd.assign(nf, 0.0);
    int segs = 0;
    for (std::size_t start = 0; start + L <= n; start += hop) {
        double mean = 0;
        for (std::size_t i = 0; i < L; ++i) mean += x[start + i];
        mean /= static_cast<double>(L);
        for (std::size_t i = 0; i < L; ++i) in[i] = (x[start + i] - mean) * w[i];
        fftw_execute(plan);
        for (std::size_t k = 0; k < nf; ++k) out.psd[k] += spec[k][0] * spec[k][0] + spec[k][1] * spec[k][1];
        ++segs;
    }
    {
        std::lock_guard<std::mutex> lk(detail::fftwPlanMutex());
        fftw_destroy_plan(plan);
    }
    fftw_free(in);
    fftw_free(spec);
    // One-sided density: |X_k|² / (fs Σw²), doubled except at DC and Nyquist.
    const double scale = 1.0 / (fs * wss * segs);
    out.frequency_Hz.resize(nf);
    for (std::size_t k = 0; k < nf; ++k) {
        out.frequency_Hz[k] = static_cast<double>(k) * fs / static_cast<double>(L);
        const bool edge = (k == 0) || (L % 2 == 0 && k == nf - 1);
        out.psd[k] *= scale * (edge ? 1.0 : 2.0);
    }
    out.resolution_Hz = fs / static_cast<double>(L);
    out.segments = segs;
    out.ok = true;
    return out;
}

std::vector<SpectralPeak> spectrumPeaks(const PowerSpectrum& s, std::size_t maxPeaks, double minRelative) {
    std::vector<SpectralPeak> peaks;
    const std::size_t n = s.psd.size();
    for (std::size_t k = 1; k + 1 < n; ++k)
        if (s.psd[k] > s.psd[k - 1] && s.psd[k] >= s.psd[k + 1]) {
            // Parabolic interpolation of the peak position on log power.
            double f = s.frequency_Hz[k];
            const double a = std::log(std::max(s.psd[k - 1], 1e-300)), b = std::log(s.psd[k]),
                         c = std::log(std::max(s.psd[k + 1], 1e-300));
            const double den = a - 2 * b + c;
            if (den < 0) f += 0.5 * (a - c) / den * s.resolution_Hz;
            peaks.push_back({f, s.psd[k]});
        }
    std::sort(peaks.begin(), peaks.end(), [](const SpectralPeak& a, const SpectralPeak& b) { return a.psd > b.psd; });
    if (!peaks.empty()) {
        const double top = peaks.front().psd;
        peaks.erase(std::remove_if(peaks.begin(), peaks.end(), [&](const SpectralPeak& p) { return p.psd < minRelative * top; }),
                    peaks.end());
    }
    if (peaks.size() > maxPeaks) peaks.resize(maxPeaks);
    return peaks;
}

double broadbandFraction(const PowerSpectrum& s, double fundamental_Hz, int maxDenominator, int halfWidthBins) {
    if (s.psd.size() < 3 || !(fundamental_Hz > 0) || !(s.resolution_Hz > 0)) return 0.0;
    std::vector<unsigned char> line(s.psd.size(), 0);
    // Mark bins near k · f0 / q for every q ≤ maxDenominator (sub- and super-harmonics).
    const double fmax = s.frequency_Hz.back();
    for (int q = 1; q <= maxDenominator; ++q) {
        const double base = fundamental_Hz / q;
        for (double f = base; f <= fmax + base; f += base) {
            const long centre = std::lround(f / s.resolution_Hz);
            for (long b = centre - halfWidthBins; b <= centre + halfWidthBins; ++b)
                if (b >= 0 && b < static_cast<long>(line.size())) line[static_cast<std::size_t>(b)] = 1;
        }
    }
    double total = 0, off = 0;
    for (std::size_t k = 1; k < s.psd.size(); ++k) {
        total += s.psd[k];
        if (!line[k]) off += s.psd[k];
    }
    return total > 0 ? off / total : 0.0;
}

}  // namespace stickslip
