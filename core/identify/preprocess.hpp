// Cleaning measured signals the way the paper did (section 2): zero-phase 60 Hz band-stop
// and 100 Hz low-pass Butterworth filters (forward–backward), resampling to a uniform step,
// velocity by a Savitzky–Golay smoothing differentiator, trimming ramps and transients.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "../io/dataset.hpp"

namespace stickslip::identify {

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

// Savitzky–Golay: least-squares polynomial of `polyOrder` over 2·halfWindow+1 samples at
// uniform spacing dt, evaluated for derivative `derivative` (0 smooth, 1 velocity, 2 …)
// at every sample (asymmetric windows at the ends).
std::vector<double> savitzkyGolay(const std::vector<double>& y, double dt_s, int halfWindow, int polyOrder,
                                  int derivative);

// Largest relative deviation of the sampling interval from its median.
double samplingIrregularity(const std::vector<double>& t);
// Linear interpolation of (t, y) at t0 + i·dt, i = 0..n−1.
std::vector<double> resampleLinear(const std::vector<double>& t, const std::vector<double>& y, double t0, double dt, size_t n);

// Period of the dominant oscillation of y (median spacing of upward mean crossings with
// hysteresis); 0 if fewer than two crossings.
double estimatePeriod(const std::vector<double>& t, const std::vector<double>& y);
// Indices [begin, end) where the moving peak-to-peak amplitude of y over one period is at
// least `fraction` of its maximum: the steady part of a tapered (ramp up / hold / ramp down)
// excitation.
std::pair<size_t, size_t> steadyAmplitudeWindow(const std::vector<double>& y, size_t periodSamples, double fraction);

// Least-squares Fourier series at frequency f (mean + harmonics 1..order) fitted to y over
// samples [begin, end) and evaluated at every t; `rss` gets the residual sum of squares.
std::vector<double> fourierFit(const std::vector<double>& t, const std::vector<double>& y, double f_Hz, int order,
                               size_t begin, size_t end, double* rss = nullptr);
// The frequency within ±span (relative) of f0 whose Fourier fit leaves the least residual
// (golden-section search): the drive frequency to ~1e-6 from a noisy record.
double refineFrequency(const std::vector<double>& t, const std::vector<double>& y, double f0_Hz, int order, double span = 0.01);

struct FilterSettings {
    bool bandStop = true;         // mains band-stop on
    double bandStopCenter_Hz = 60.0;
    double bandStopWidth_Hz = 10.0;  // −3 dB width of the stop band
    int bandStopOrder = 2;        // prototype order (filter order 2·this), applied forward and backward
    bool lowPass = true;
    double lowPass_Hz = 100.0;
    int lowPassOrder = 4;
};

struct TrimSettings {
    double start_s = 0.0;             // always drop this much at the start
    double end_s = 0.0;               // and at the end
    bool steadyAmplitude = true;      // keep only where the drive amplitude is steady (drops ramps)
    double amplitudeFraction = 0.9;   // "steady": moving amplitude ≥ this fraction of its maximum
};

struct PreprocessSettings {
    FilterSettings filters;
    bool resample = true;                 // resample to the median step when the time column is irregular
    double irregularityTolerance = 0.01;  // relative
    int sgHalfWindow = 7;                 // Savitzky–Golay window 2·7+1 samples
    int sgOrder = 3;
    TrimSettings trim;
    // Dynamics runs (a slider displacement is present) with a steady harmonic drive: the stage
    // displacement that drives the model is replaced by its Fourier fit (this many harmonics)
    // at the refined drive frequency. Sensor noise on u would otherwise reach the predicted
    // force amplified by ε_T during stick. 0 = use the filtered measurement as it is.
    int stageFourierOrder = 5;
    std::vector<std::string> validate(double sampleRate_Hz) const;  // every problem, empty if fine
};

nlohmann::json toJson(const PreprocessSettings& s);

// A cleaned run: all measured signals filtered (time untouched), uniform step, velocities
// derived where missing (slip g = u − x and V = u̇ − ẋ for the dynamics set-up; V = dg/dt
// for prescribed slip), and the window [begin, end) of samples to fit (after trimming).
struct CleanRun {
    io::Run run;           // cleaned signals, settings copied
    double dt_s = 0.0;     // uniform sampling step
    size_t begin = 0;      // first sample to fit
    size_t end = 0;        // one past the last sample to fit
    double period_s = 0.0; // dominant drive period (0 if none found)
    bool resampled = false;
    std::vector<std::string> notes;  // what was done, for reports
    // The zero-phase filter (band-stop and low-pass cascade, applied forward and backward) that
    // cleaned the measured signals; empty when both were off. Predictions are passed through the
    // same filter before they are compared with the cleaned signals (predict.hpp).
    Sos filter;
    FilterSettings filterSettings;  // the settings that designed `filter` (to redesign it at another rate)
    // The measured force and slider displacement before that filter (after resampling), kept
    // when the filter is on (else empty): the filtered prediction is then exactly
    // filter(prediction) where predicted and filter(measurement) elsewhere.
    std::vector<double> unfilteredForce_N, unfilteredSlider_m;
};

bool preprocessRun(const io::Run& raw, const PreprocessSettings& s, CleanRun& out, std::string* error);

}  // namespace stickslip::identify
