// Autocorrelation (with a decay time) and the stage–slider phase lag from the maximum of the
// cross-correlation (paper Figs 6–8), computed with FFTW (zero padded, so not circular).
#pragma once

#include <cstddef>
#include <vector>

namespace stickslip {

struct Correlation {
    std::vector<double> lag_s;  // lags [s]
    std::vector<double> r;      // normalised correlation (biased estimator, r = 1 at lag 0 for autocorrelation)
};

// Autocorrelation of x (mean removed) for lags 0 … maxLag samples. Empty if x is constant.
Correlation autocorrelation(const std::vector<double>& x, double sampleRate_Hz, std::size_t maxLag);

// Decay time: the smallest lag after which |r| stays below `level` (default 1/e) up to the
// last lag computed. NaN when it never does (periodic signals do not decay).
double correlationDecayTime(const Correlation& ac, double level = 0.36787944117144233);

// Cross-correlation r(τ) = Σ x'(t) y'(t + τ) / (n σx σy) for τ = −maxLag … maxLag samples.
Correlation crossCorrelation(const std::vector<double>& x, const std::vector<double>& y, double sampleRate_Hz,
                             std::size_t maxLag);

struct PhaseLag {
    double lag_s = 0;            // τ > 0: the slider lags the stage (slider(t) ≈ stage(t − τ)) [s]
    double nondimensional = 0;   // τ · ω_n (ω_n = √(k/m*) [rad/s]), the paper's "non-dimensionalised by the natural frequency"
    double fractionOfPeriod = 0; // τ · f [-]
    double peak = 0;             // the cross-correlation at its maximum [-]
    bool ok = false;
};

// Stage–slider phase lag: the lag of the cross-correlation maximum within |τ| ≤ T/2 (T = 1/forcingFrequency_Hz),
// refined by a parabola through the three samples around the maximum.
PhaseLag stageSliderPhaseLag(const std::vector<double>& stage_m, const std::vector<double>& slider_m,
                             double sampleRate_Hz, double forcingFrequency_Hz, double naturalFrequency_rad_s);

}  // namespace stickslip
