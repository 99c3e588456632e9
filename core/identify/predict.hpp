// Predicting measured signals from model parameters, for both set-ups (issue 5):
//  - prescribed slip (paper Fig. 15a): the measured slip history g(t) drives the law; the
//    friction force F(t) is predicted.
//  - dynamics (paper Fig. 15b): the measured stage motion u(t) drives the spring–mass rig;
//    slider displacement x(t) and friction force F(t) are predicted by multiple shooting:
//    short segments, each re-initialised from the measured x, ẋ (Savitzky–Golay) and F, so
//    that the divergence of nearby trajectories (chaos) does not dominate the residual.
//    Segments can start where the slider slips (PredictSettings::slipStartFraction), where the
//    measured state determines the model's; the stage is interpolated smoothly between samples.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "../friction/friction_law.hpp"
#include "../params.hpp"
#include "preprocess.hpp"

namespace stickslip::identify {

struct PredictSettings {
    // prescribed
    int stride = 4;              // use every stride-th measured sample as a law step boundary (decimation)
    int substeps = 8;            // law steps per (decimated) sample interval
    double warmup_s = 0.25;      // simulate this long before the fit window (the law forgets its start)
    // dynamics
    double dt_s = 1.0e-4;        // integration step; rounded so that whole steps fill a sample interval
    double segment_s = 0.05;     // length of one re-initialised segment
    double segmentSpacing_s = 0.25;  // start-to-start spacing of segments (≥ segment_s)
    int residualStride = 5;      // samples between residual points inside a segment
    // Where a segment starts. The measured state cannot set the model's state while the slider
    // is stuck: the friction state α is frozen at its value from the end of the last slip (the
    // law has no healing, so it is not the steady state at V ≈ 0), and the contact spring ε_T
    // with k and m* rings at sqrt((k + ε_T)/m*) (≈ 140 Hz on D05), above the 100 Hz low-pass, so
    // the filtered x, ẋ and F miss it. Both errors bias the fit (on D05 μ by −3 %). While the
    // slider slips, the measured state does set the model's: α relaxes to its steady state within
    // a slip of D_c, the contact is a dashpot (η t_N), nothing rings, and F follows the law. So
    // with slipStartFraction > 0 each segment starts at the first sample at or after its nominal
    // start (and after the previous segment) where |V| ≥ slipStartFraction · max |V| of the fit
    // window; when there is none within the segment spacing (permanent stick) it starts at the
    // nominal time. 0 = start at the nominal times. Default 0.5, with fitInitialState (a slip
    // start alone is sensitive to the error of the measured ẋ, which a slipping slider forgets
    // only at the rate η t_N/m*; the D05 fit from ε_T = 1e6 also ended in a wrong valley of
    // ε_T, which DatasetFitSettings::autoScan now avoids).
    double slipStartFraction = 0.5;
    // Pass the prediction through the run's own cleaning filter (CleanRun::filter) before it is
    // compared with the cleaned measurement, so that both sides of the residual have seen the
    // same zero-phase band-stop/low-pass: the returned prediction is filter(y) on the predicted
    // stretch, y = prediction there and the unfiltered measurement elsewhere, i.e. cleaned +
    // filter(prediction − unfiltered measurement, zero outside the stretch) (CleanRun keeps the
    // unfiltered force and slider displacement). Without it the filter's smoothing of
    // stick–slip corners (and of the rig's stick ringing) is a systematic error the
    // parameters absorb.
    bool filterPrediction = true;
    // Multiple shooting with each segment's initial slider state (x, ẋ) as a nuisance
    // parameter, profiled out (variable projection): for the given law and rig parameters the
    // segment starts from the measured x, ẋ, then `initialStateIterations` Gauss–Newton steps
    // move (x, ẋ) towards where the segment's scored, filtered residuals are least; the last
    // step's linear model gives the returned residual (smooth in the law parameters, no extra
    // simulation). The measured initial state has errors (filtered displacement
    // noise, the Savitzky–Golay velocity, stick ringing above the low-pass) that persist
    // through a segment and bias the law parameters (errors in variables, on D05 ε_T, m*, ζ by
    // 2–8 standard errors); with the state profiled out they do not enter. Costs 2 segment
    // simulations per step and one per step after the first. Prediction::nuisanceParameters counts the profiled parameters, so
    // the fit's residual degrees of freedom are m − p − that.
    bool fitInitialState = true;
    int initialStateIterations = 1;
    ParamIssues validate() const;  // every problem, naming the setting, its value and the allowed range
};

// One run's prediction at the sample indices `index` (into the CleanRun's signals).
struct Prediction {
    bool ok = false;
    std::string message;
    std::vector<size_t> index;
    std::vector<double> force_N;   // predicted F
    std::vector<double> slider_m;  // predicted x (dynamics only)
    size_t nuisanceParameters = 0; // segment initial states profiled out (PredictSettings::fitInitialState)
};

// Model parameters by name (keys of setParam: mu C1 eta Dc vc epsT r, rig m c k, and
// "zeta" = damping ratio, which sets c = 2 ζ sqrt(k m) per run). When tieC1ToMu and C1 is
// not given, C1 = μ (the paper's choice μ = C1).
struct ModelSpec {
    LawKind law = LawKind::RateState;
    std::map<std::string, double> values;
    bool tieC1ToMu = true;
};

// The SimParams of one run: the run's known settings (k, m, c, tN, A, f) then the model's
// values. A model's ζ sets c = 2ζ sqrt(k m) only on runs without a recorded c (a measured
// damping is a known setting, not a fit's). False (with a message) when a name is unknown.
bool runParams(const CleanRun& run, const ModelSpec& spec, SimParams& out, std::string* error);

Prediction predictPrescribed(const CleanRun& run, const FrictionLaw& law, double normalForce_N, const PredictSettings& s);
Prediction predictDynamics(const CleanRun& run, const RigParams& rig, const FrictionLaw& law, const PredictSettings& s);
// Dispatch on the set-up using runParams.
Prediction predictRun(const CleanRun& run, SetupKind setup, const ModelSpec& spec, const PredictSettings& s);

}  // namespace stickslip::identify
