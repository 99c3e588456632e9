// Butterworth IIR filters as cascades of second-order sections, and causal and zero-phase
// filtering with them. General signal processing: nothing here knows about runs or friction.
#pragma once

#include <cstddef>
#include <vector>

namespace stickslip::dsp {

// One second-order section, H(z) = (b0 + b1 z⁻¹ + b2 z⁻²)/(1 + a1 z⁻¹ + a2 z⁻²).
struct Biquad {
    double b0 = 1, b1 = 0, b2 = 0, a1 = 0, a2 = 0;
};
using Sos = std::vector<Biquad>;

// Digital Butterworth designs by the bilinear transform with pre-warping.
// Low-pass of `order` (≥ 1) with −3 dB at cutoff_Hz < fs/2.
Sos butterworthLowpass(int order, double cutoff_Hz, double sampleRate_Hz);
// Band-stop from a low-pass prototype of `order` (the filter has 2·order poles), stop band
// between low_Hz and high_Hz (−3 dB edges).
Sos butterworthBandstop(int order, double low_Hz, double high_Hz, double sampleRate_Hz);
// |H(e^{iω})| at frequency f.
double sosMagnitude(const Sos& sos, double f_Hz, double sampleRate_Hz);
// Group delay at zero frequency, in samples: Σ over sections of Σk·b_k/Σb_k − Σk·a_k/Σa_k
// (−dφ/dω at ω = 0 of a rational H). The time scale over which the filter remembers its input;
// 0 for an empty cascade; NaN for a section that blocks DC.
double groupDelayAtDc(const Sos& sos);
// Causal filtering with the steady-state initial conditions of x[0].
std::vector<double> sosFilter(const Sos& sos, const std::vector<double>& x);
// Zero-phase filtering: forward, then backward, with odd-reflection padding at both ends
// (as scipy.signal.sosfiltfilt, but padlen = impulseResponseLength(sos) instead of scipy's
// 3·(2·sections + 1), capped at n − 1); the magnitude response is |H|².
std::vector<double> filtfilt(const Sos& sos, const std::vector<double>& x);
// Samples after which the causal impulse response of sos stays below `tolerance` of its peak
// (0 for an empty cascade; at most 2^20).
size_t impulseResponseLength(const Sos& sos, double tolerance = 1e-6);
// Zero-phase filtering of x as if it were continued by zeros on both sides (a signal that is
// non-zero only on a short stretch, e.g. a prediction-minus-measurement over one shooting
// segment): filtfilt of x padded with `margin` zeros at each end (0: impulseResponseLength),
// returned on x's samples, except that the odd reflection beyond the zeros is scipy's short
// 3·(2·sections + 1) samples (the margins already hold the filter's memory). Linear in x.
std::vector<double> filtfiltZeroExtended(const Sos& sos, const std::vector<double>& x, size_t margin = 0);

}  // namespace stickslip::dsp
