// Position and velocity of a body from its measured position and measured acceleration:
// the Rauch–Tung–Striebel smoother of ẍ = a, with the acceleration as the model's input
// (its noise is the process noise) and a constant accelerometer offset as a third state.
// Differentiating a noisy position amplifies its noise by 1/dt; fusing the acceleration
// keeps the velocity's error at the acceleration noise integrated over the filter's
// bandwidth. Both noise levels are estimated from the signals when not given, so the
// smoother calibrates itself on each recording.
#pragma once

#include <string>
#include <vector>

namespace stickslip::dsp {

struct KinematicSmootherOptions {
    double dispNoise = 0.0;   // rms of the position's white noise [m]; 0 = estimate (third differences, MAD)
    // rms of the acceleration's white noise [m/s²]; 0 = estimate (maximum likelihood). The
    // estimate is an effective level: the noise plus how far a departs from linear between
    // samples (jumps at slip onsets and stops), so it exceeds the sensor's noise.
    double accelNoise = 0.0;
    // Message naming the field, value and range; empty when valid.
    std::string validate() const;
};

struct KinematicEstimate {
    bool ok = false;
    std::string message;
    std::vector<double> x, v;       // smoothed position [m] and velocity [m/s] at every sample
    double dispNoise = 0.0;         // the levels used (given or estimated)
    double accelNoise = 0.0;
    double accelOffset = 0.0;       // estimated constant accelerometer offset [m/s²]
    double logLikelihood = 0.0;     // of the innovations, at the levels used
};

// x and a sampled together at the uniform step dt_s (at least 16 samples, all finite).
KinematicEstimate smoothKinematics(const std::vector<double>& x, const std::vector<double>& a, double dt_s,
                                   const KinematicSmootherOptions& opt = {});

}  // namespace stickslip::dsp
