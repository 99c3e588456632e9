// Power spectral density by Welch's method (Hann window, overlapping segments, mean removed
// per segment), with FFTW3. One-sided density: Σ psd · Δf = variance of the signal.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace stickslip {

struct WelchOptions {
    std::size_t segmentLength = 0;  // samples per segment; 0 = largest power of two ≤ n/4 (≥ 16, ≤ n)
    double overlap = 0.5;           // fraction of a segment shared with the next, in [0, 1)
};

struct PowerSpectrum {
    std::vector<double> frequency_Hz;  // 0 … fs/2
    std::vector<double> psd;           // one-sided PSD [unit²/Hz]
    double resolution_Hz = 0;          // Δf = fs / segmentLength
    int segments = 0;                  // segments averaged
    bool ok = false;
    std::string message;               // why not ok
};

PowerSpectrum powerSpectrum(const std::vector<double>& x, double sampleRate_Hz, const WelchOptions& opt = {});

struct SpectralPeak {
    double frequency_Hz = 0;
    double psd = 0;
};

// Local maxima of the PSD (excluding DC), strongest first, at most maxPeaks, each at least
// minRelative × the strongest.
std::vector<SpectralPeak> spectrumPeaks(const PowerSpectrum& s, std::size_t maxPeaks, double minRelative = 1e-3);

// Fraction of the power (excluding DC) not within ±halfWidthBins bins of a multiple of
// fundamental_Hz / maxDenominator (harmonics and subharmonics up to 1/maxDenominator):
// near 0 for periodic motion of period ≤ maxDenominator, larger for broad-band spectra.
double broadbandFraction(const PowerSpectrum& s, double fundamental_Hz, int maxDenominator = 16, int halfWidthBins = 2);

}  // namespace stickslip
