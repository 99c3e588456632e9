// Cleaning measured signals the way the paper did (section 2): zero-phase 60 Hz band-stop
// and 100 Hz low-pass Butterworth filters (forward–backward), resampling to a uniform step,
// velocity by a Savitzky–Golay smoothing differentiator, trimming ramps and transients.
// The run pipeline only: the signal processing it is built from is in core/dsp.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "../dsp/iir.hpp"
#include "../io/dataset.hpp"
#include "../param_table.hpp"

namespace stickslip::identify {

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
    // Dynamics runs with a slider acceleration: the slider's displacement and velocity are
    // replaced by the Rauch–Tung–Striebel smoother of ẍ = a over the raw signals
    // (dsp::smoothKinematics, noise levels estimated per run). The law is driven by the slip
    // g = u − x, and the position's noise differentiated into the slip rate biases it
    // (docs/identify-results.md, session 70).
    bool fuseSliderAcceleration = false;
    ParamIssues validate(double sampleRate_Hz) const;  // every problem, empty if fine
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
    dsp::Sos filter;
    FilterSettings filterSettings;  // the settings that designed `filter` (to redesign it at another rate)
    // The measured force and slider displacement before that filter (after resampling), kept
    // when the filter is on (else empty): the filtered prediction is then exactly
    // filter(prediction) where predicted and filter(measurement) elsewhere.
    std::vector<double> unfilteredForce_N, unfilteredSlider_m;
};

bool preprocessRun(const io::Run& raw, const PreprocessSettings& s, CleanRun& out, std::string* error);

}  // namespace stickslip::identify
