// Least-squares harmonic (truncated Fourier series) fits at a known frequency, and the
// refinement of that frequency from a record. The one harmonic fit of the code base: the
// cleaning of dynamics runs (stage displacement replaced by its fit) and the identify loop's
// stage motion (u = mean + a cos ωt + b sin ωt) both use it.
#pragma once

#include <cstddef>
#include <vector>

namespace stickslip::dsp {

// y(t) ≈ mean + Σ_h (cosine[h−1] cos(h ω t) + sine[h−1] sin(h ω t)), h = 1..order, ω = 2π f.
struct HarmonicFit {
    double frequency_Hz = 0.0;
    double omega = 0.0;            // 2π f [rad/s]
    double mean = 0.0;
    std::vector<double> cosine;    // a_h, h = 1..order
    std::vector<double> sine;      // b_h, h = 1..order
    double rss = 0.0;              // residual sum of squares over the fitted samples
    size_t samples = 0;            // how many samples were fitted
    int order() const { return static_cast<int>(cosine.size()); }
    double at(double t_s) const;            // the series at t
    double amplitude(int harmonic) const;   // hypot(a_h, b_h), h ≥ 1; 0 beyond the order
};

// Least-squares fit of mean + harmonics 1..order at f_Hz to y over samples [begin, end) of t
// (normal equations solved by LDLT; an empty or too short range gives a meaningless fit, the
// callers guarantee many periods of samples).
HarmonicFit harmonicFit(const std::vector<double>& t, const std::vector<double>& y, double f_Hz, int order,
                        size_t begin, size_t end);

// The harmonic fit over [begin, end) evaluated at every t; `rss` gets its residual sum of squares.
std::vector<double> fourierFit(const std::vector<double>& t, const std::vector<double>& y, double f_Hz, int order,
                               size_t begin, size_t end, double* rss = nullptr);
// The frequency within ±span (relative) of f0 whose Fourier fit leaves the least residual
// (golden-section search): the drive frequency to ~1e-6 from a noisy record.
double refineFrequency(const std::vector<double>& t, const std::vector<double>& y, double f0_Hz, int order, double span = 0.01);

}  // namespace stickslip::dsp
