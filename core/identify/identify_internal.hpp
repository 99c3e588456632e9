// Internal pieces of the identify loop (identify.hpp), shared by its translation units:
// run preparation (identify_prepare.cpp), residuals (identify_residuals.cpp), fits and
// held-out errors (identify_fit.cpp), selection tests (identify_selection.cpp), the loop itself
// (identify.cpp) and the report (identify_report.cpp). Not part of the public API.
#pragma once

#include <algorithm>
#include <atomic>
#include <thread>
#include <cmath>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "../dsp/iir.hpp"
#include "fit.hpp"
#include "identify.hpp"
#include "noise_null.hpp"

namespace stickslip::identify::detail {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// A run prepared for fast repeated evaluation: decimated samples, weights.
struct Prepared {
    const IdentifyRun* run = nullptr;
    std::vector<double> t, g, V, F, a, x, xd;
    // The law channel's slip at the end of each of its steps (substeps per decimated interval),
    // read off the recorded slip rather than the line between decimated samples: that line cuts
    // the corners of every stick (dwell) by up to a decimated interval, and a frictional lag of
    // about that size absorbs the cut. Prescribed runs only (identify_prepare.cpp says why); empty
    // when the run is not decimated.
    std::vector<double> stepSlip;
    size_t dec = 1;  // recorded samples per decimated interval
    double invRmsF = 1.0;
    dsp::Sos predictionFilter;  // the run's cleaning filters at the decimated rate (those below its Nyquist)
    // Dynamics law channel: compared samples keep this many samples from any sample it does not
    // compare (IdentifyOptions::maskEdgeGuard): the filter's DC group delay, rounded up.
    size_t edgeGuard = 0;
    // Dynamics law channel, fixed by the data: where the contact slides (|V| >= vStick; the
    // prediction applies there) and, of those, the samples compared (slides eroded by edgeGuard).
    std::vector<char> slides, compared;
    // The prediction y as the cleaned measurement would show it: F + filter(mask·(y − F)), the
    // difference taken only where the prediction applies (mask; all samples when null), so the
    // stick phases that are not compared cannot leak into compared samples.
    std::vector<double> filtered(const std::vector<double>& y, const std::vector<char>* mask = nullptr) const {
        if (predictionFilter.empty()) return y;
        std::vector<double> d(y.size(), 0.0);
        for (size_t i = 0; i < y.size(); ++i)
            if (!mask || (*mask)[i]) d[i] = y[i] - F[i];
        d = dsp::filtfiltZeroExtended(predictionFilter, d);
        for (size_t i = 0; i < y.size(); ++i) d[i] += F[i];
        return d;
    }
    // The model's whole force through the cleaning filters, with the model's own force where the
    // mask is off (`outside`, e.g. the equation of motion's in stick): filter(y·mask + outside·(1 −
    // mask)), as the cleaned measurement is filter(raw). F + filter(y − F) above differs from it by
    // F − filter(F), which is not zero next to every slip onset and stop, where the cleaned force
    // bends faster than the filter passes (IdentifyOptions::stickRigPrediction).
    std::vector<double> filtered(const std::vector<double>& y, const std::vector<char>& mask,
                                 const std::vector<double>& outside) const {
        if (predictionFilter.empty()) return y;
        std::vector<double> d(y.size(), 0.0);
        for (size_t i = 0; i < y.size(); ++i) d[i] = mask[i] ? y[i] : outside[i];
        return dsp::filtfiltZeroExtended(predictionFilter, d);
    }
    // Dynamics, segment residual: smoothed slider state, cleaned stage motion, slip so far,
    // segments [first, last] of samples (each starts mid-slide).
    std::vector<double> xs, vs, u, Vs, cumSlip;
    std::vector<std::pair<size_t, size_t>> segments;
    double invRmsX = 1.0;
    bool stageHarmonic = false;
    double uc0 = 0, ua = 0, ub = 0, omega = 0;  // u = uc0 + ua cos ωt + ub sin ωt when harmonic
    size_t size() const { return t.size(); }
    double stageAt(double tt) const {
        if (stageHarmonic) return uc0 + ua * std::cos(omega * tt) + ub * std::sin(omega * tt);
        const double dt = t[1] - t[0];
        const double q = std::clamp((tt - t.front()) / dt, 0.0, static_cast<double>(t.size() - 1));
        const size_t i = std::min(static_cast<size_t>(q), t.size() - 2);
        const double w = q - static_cast<double>(i);
        return u[i] * (1.0 - w) + u[i + 1] * w;
    }
};

// The model (effects, in order added) and how its dynamics residual is formed.
struct Spec {
    std::vector<std::string> effects;   // catalogue names, in order added
    bool segments = false;              // dynamics: segment simulation instead of equation error
};

struct Context {
    std::vector<Prepared> runs;
    const IdentifyOptions* opt = nullptr;
    bool anyDynamics = false;
    double tNref = 1.0;
    double muScale = 1.0;  // the baseline's μ̂, for effect parameters in units of μ (scaledParam)
    // The same runs prepared at their recorded rate (decimation 1), for numericsOffset; null when
    // the runs are not decimated or the noise null does not carry the numerical part.
    const Context* fullRate = nullptr;
    bool cancelled() const { return opt && opt->cancelRequested(); }
};

struct FitOutcome {
    bool ok = false;
    std::string message;
    std::map<std::string, double> values;
    std::vector<ParamEstimate> estimates;
    double ss = 0, count = 0;   // over the fitted runs
    int nFree = 0;
    FitResult fit;
    // Points the solver asked for that the steady-state curve's coordinates put outside C1's or
    // η's bounds (curve_coordinates.hpp; 0 for a fit in C1, η, v_c): the edge of the feasible
    // region, which in those coordinates is not a box.
    long outsideLawBounds = 0;
    // Fits done again or continued in C1, η, v_c after the one in the curve coordinates (fitSpec:
    // 0 or 1; counted in `fits` like the first).
    int lawPasses = 0;
    // Pooled NRMSE over the fitted runs (each residual already divided by its run's force RMS);
    // `none` without residuals.
    double nrmse(double none = kNaN) const { return count > 0 ? std::sqrt(ss / count) : none; }
};

// Set on the threads of a parallelFor while they run its tasks: a parallelFor inside a task (a
// fit's residual batches inside a candidate's fit) runs on the task's own thread. The outer
// loop has already spread the work over the cores; nested threads would only add spawns and
// the inner loop's load imbalance (measured: 1.25-1.65x from two threads inside one fit).
inline thread_local bool tInParallelTask = false;

// fn(i) for i in [0, n) on every core, or on the calling thread inside another parallelFor's
// task (each i writes only its own results, so the outcome does not depend on the scheduling
// or the thread count).
template <class Fn>
void parallelFor(size_t n, Fn&& fn) {
    if (tInParallelTask) {
        for (size_t i = 0; i < n; ++i) fn(i);
        return;
    }
    std::atomic<size_t> next{0};
    auto work = [&]() {
        struct Mark {
            Mark() { tInParallelTask = true; }
            ~Mark() { tInParallelTask = false; }
        } mark;
        for (size_t i = next.fetch_add(1); i < n; i = next.fetch_add(1)) fn(i);
    };
    const size_t workers = std::min<size_t>(std::max(1u, std::thread::hardware_concurrency()), n);
    std::vector<std::thread> pool;
    for (size_t w = 1; w < workers; ++w) pool.emplace_back(work);
    work();
    for (std::thread& t : pool) t.join();
}

// An effect parameter with its start and bounds in the units of this data set (EffectParam::muUnits).
inline EffectParam scaledParam(EffectParam q, double muScale) {
    if (q.muUnits) {
        const double k = std::max(1.0, std::abs(muScale));
        q.initial *= k;
        q.lower *= k;
        q.upper *= k;
    }
    return q;
}

inline bool actsInStick(const std::string& effect) {
    return effect == "backlash" || effect == "presliding_compliance" || effect == "stick_healing";
}

void applyLaw(RateStateParams& p, const std::string& name, double v);
double lawValue(const RateStateParams& p, const std::string& name);
ExtendedModel buildModel(const Context& cx, const Spec& spec, const std::map<std::string, double>& vals, double& mass);
bool segmentResiduals(const Context& cx, const Prepared& p, const ExtendedModel& m, double mass, std::vector<double>& r,
                      double& ss, double& count, std::vector<double>* predicted, std::vector<char>* used,
                      std::vector<double>* frictionResidual);
// The contact force of the law run along the run's measured slip (what the law channel of
// runResiduals simulates): it depends on the law and the effects that act in the contact, not on
// the rig's m and ζ nor on the sensor's dashpot and mass (lawParameter() is false for those).
struct LawRun {
    std::vector<double> contactForce_N, relVel_mps, accel_mps2;
};
// refinement > 1: every law step split into that many (the check of the law's time resolution,
// law_resolution.cpp).
bool simulateLawRun(const Context& cx, const Prepared& p, const ExtendedModel& m, LawRun& out, int refinement = 1);
bool lawParameter(const std::string& name);
// The model the law channel runs: in the dynamics set-up viscous damping is a rig effect (in the
// equation of motion), not a dashpot beside the sensor.
ExtendedModel lawChannelModel(const Prepared& p, const ExtendedModel& m);
// simulateLawRun (refinement 1) carrying the forward sensitivities of the law channel's measured
// force with respect to `names` (prescribed_sensitivity.hpp); false when the run fails or a name
// is not a parameter of the law channel's model.
bool simulateLawRunSensitivity(const Context& cx, const Prepared& p, const ExtendedModel& m,
                               const std::vector<std::string>& names, LawRun& out, Eigen::MatrixXd& dMeasured);
// The Jacobian of residualVector over the runs idx at vals with respect to `names` (keys of
// vals), rows in residualVector's order: the law channel from forward sensitivities (filtered as
// its residual is), the equation-of-motion channel in closed form. Also the residuals
// themselves into `r` when given, from the same runs. False for the segment residual or a name
// neither channel covers (the caller then differences).
bool analyticResidualJacobian(const Context& cx, const Spec& spec, const std::map<std::string, double>& vals,
                              const std::vector<size_t>& idx, const std::vector<std::string>& names, Eigen::MatrixXd& J,
                              std::vector<double>* r = nullptr);
// Residuals of one run appended to `r` (see identify_residuals.cpp); with `law`, the law run
// computed by simulateLawRun for a model with the same law parameters is used instead of a new
// simulation (identical numbers).
bool runResiduals(const Context& cx, const Prepared& p, const ExtendedModel& m, double mass, std::vector<double>& r,
                  double& ss, double& count, std::vector<double>* predicted, std::vector<char>* used,
                  std::vector<double>* frictionResidual, bool segments, const LawRun* law = nullptr);
// The final model's law channel with every law step split in `refinement` (>= 2), against the
// one the fits used, run by run (identify.hpp, LawResolution); unchecked when a run fails.
constexpr int kLawResolutionRefinement = 8;
LawResolution checkLawResolution(const Context& cx, const ExtendedModel& m, double mass, int refinement);
// evalSS with the law channel's every step split in `refinement` (>= 1; 1 is evalSS): how a
// model's fit depends on the law's time step. Infinity where a run fails; NaN for the segment
// residual, which has no law channel of its own.
double evalSSRefined(const Context& cx, const Spec& spec, const std::map<std::string, double>& vals,
                     const std::vector<size_t>& idx, int refinement);
size_t residualCount(const Context& cx, const std::vector<size_t>& idx);
bool residualVector(const Context& cx, const Spec& spec, const std::map<std::string, double>& vals,
                    const std::vector<size_t>& idx, std::vector<double>& r, std::vector<NoiseBlock>* blocks = nullptr);
// The part of the residual r0 (residualVector of the same model) that the prediction's own
// discretisation makes: r0 minus the residual of the same model predicted at the runs' recorded
// rate (cx.fullRate: every recorded sample drives the law, the cleaning filters at their own
// rate) at the samples r0 compares; with the segment residual, or runs not decimated, with
// kNumericsRefinement times the law (Newmark) steps per sample. The fine residual is refitted to
// those samples (linearised at vals: its free parameters' Jacobian projected out), because the
// coarse fit's parameters already took up what they can of the coarse model's error. At the
// coarse optimum r0 − d is then the fine model's best-fit residual. False when a run fails.
// Which bound of its range `v` is on: −1 lower, +1 upper, 0 neither (or not finite); within 1e-6
// of the range in the parameter's own scale (identify_restart.cpp).
int boundSide(const FitParameter& p, double v);
constexpr int kNumericsRefinement = 4;
bool numericsOffset(const Context& cx, const Spec& spec, const std::map<std::string, double>& vals,
                    const std::vector<size_t>& idx, const std::vector<double>& r0, std::vector<double>& d);
Eigen::MatrixXd residualJacobian(const Context& cx, const Spec& spec, const std::map<std::string, double>& vals,
                                 const std::vector<size_t>& idx, const std::vector<FitParameter>& params,
                                 const std::vector<std::string>& which, size_t rows);
// Sum of squared residuals of a model over the runs idx (inf if a run fails).
double evalSS(const Context& cx, const Spec& spec, const std::map<std::string, double>& vals, const std::vector<size_t>& idx);
// The point of `points` (the model `spec` at each) with the lowest full sum of squares over the
// runs idx, and only one below `below` counts (−1: none; ties: the first). Evaluated with as
// little work as that answer needs: every point on the first run, then the points in the order
// of that partial sum, each stopped once its partial sum passes the lowest full sum so far. A
// stopped point's sum is above a full one, so the answer is the exhaustive one whatever the
// threads' timing. `sums` (if given) receives the full sums, and for stopped points the partial
// sum that stopped them (a lower bound above the answer's).
int lowestSS(const Context& cx, const Spec& spec, const std::vector<std::map<std::string, double>>& points,
             const std::vector<size_t>& idx, double below = std::numeric_limits<double>::infinity(),
             std::vector<double>* sums = nullptr);
// The residuals of model m over the runs idx, appended run after run to r (cleared first), and
// their sum of squares and count added to ss and n; false where a run cannot be evaluated.
bool residualsOver(const Context& cx, const Spec& spec, const std::vector<size_t>& idx, const ExtendedModel& m, double mass,
                   std::vector<double>& r, double& ss, double& n);

std::vector<FitParameter> parameters(const Context& cx, const Spec& spec, const std::map<std::string, double>& start);
// The point `vals` of a model with effect e, as a point of the model `without` (e absent): e's
// parameters removed, and one that continues a baseline parameter (viscous_damping's ζ continues
// the rig's ζ) handing its value back to that parameter, clamped to its range in `without`.
std::map<std::string, double> withoutEffect(const Context& cx, const Spec& without, const std::string& e,
                                            std::map<std::string, double> vals);
// Which finite-difference Jacobian a fit's solver uses (IdentifyOptions::forwardJacobian).
// NearOptimum: a refit started at the optimum of the full problem (leave-one-run-out) takes
// central differences whatever the option: its gradient is small there, of the order of a
// forward difference's O(δ) error, which would stop it where it started (measured: every
// refit of a backlash fit, jackknife spread 0).
enum class FitStart { Far, NearOptimum };
// What a fit returns. Full: standard errors, correlations and the sum of squares over its runs
// (for scoring, selection and the report). ValuesOnly: the optimum alone (a leave-one-run-out
// refit, which is only ever evaluated on its held-out run): the 2p-point Jacobian after the
// solve and the re-evaluation over its runs are skipped; `values` and `ok` are the same as
// Full's, `estimates` carry NaN standard errors, ss = NaN and count = 0.
enum class FitOutput { Full, ValuesOnly };
// `retryTolerance` > 0: Ceres' relative cost and parameter tolerances both (a refit done again
// because it never left its start); 0: the defaults, a cost tolerance of 1e-6 from far and
// IdentifyOptions::looFunctionTolerance near the optimum, a parameter tolerance of 1e-6.
FitOutcome fitSpec(const Context& cx, const Spec& spec, const std::map<std::string, double>& start,
                   const std::vector<size_t>& idx, int multistarts, long& fits, bool scanStiffness = false,
                   FitStart from = FitStart::Far, FitOutput output = FitOutput::Full, double retryTolerance = 0);
// One pass of fitSpec without its second pass in C1, η, v_c: `curveAllowed`, whether it may
// move in the steady-state curve's coordinates; `usedCurve` is set to whether it did.
FitOutcome fitSpecOnce(const Context& cx, const Spec& spec, const std::map<std::string, double>& start,
                       const std::vector<size_t>& idx, int multistarts, long& fits, bool scanStiffness, FitStart from,
                       FitOutput output, double retryTolerance, bool curveAllowed, bool& usedCurve);
// A fit in the steady-state curve's coordinates continued in C1, η, v_c from where it stopped
// (one start, no scans; `initialCost` is the first fit's, so neverMoved judges the two as one).
FitOutcome continueInLawCoordinates(const Context& cx, const Spec& spec, const FitOutcome& curveFit,
                                    const std::vector<size_t>& idx, long& fits, FitStart from, FitOutput output,
                                    double retryTolerance);
// Whether a second pass in C1, η, v_c replaces a fit in the curve coordinates: it succeeded, and
// the first failed or it reached a lower cost. The costs compared are the solver's, the same sum
// in both coordinates and set for FitOutput::ValuesOnly too, whose `ss` is not computed.
bool lawFitIsBetter(const FitOutcome& curveFit, const FitOutcome& lawFit);
// Whether a successful fit ended where it started: its cost not lowered by a relative 1e-12
// (the solver took no step).
bool neverMoved(const FitOutcome& f);
// `loo`, if given, is replaced by the leave-one-run-out refits' parameter values (one per run).
ModelErrors errorsOf(const Context& cx, const Spec& spec, const FitOutcome& full, const std::vector<size_t>& fitIdx,
                     const std::vector<size_t>& valIdx, long& fits,
                     std::vector<std::map<std::string, double>>* loo = nullptr);
// The structure tests (both channels) only with StructureCheck::Run: the loop's working
// diagnostics need the correlations and τ_int, the reports all of it.
Diagnostics diagnoseModel(const Context& cx, const Spec& spec, const FitOutcome& f, std::vector<std::vector<double>>* preds,
                          StructureCheck structure = StructureCheck::Run);
// The baseline's start: μ from the data (median |F|/t_N at the faster half of the slip rates) and
// C1, η in proportion to the start law's; with `from`, every free law value from that law instead
// of the options' start (the rest of the start map is left to the options).
std::map<std::string, double> baselineStart(const Context& cx, const std::vector<size_t>& fitIdx,
                                            const RateStateParams* from = nullptr);
// "lower" or "upper" when effect e's size parameter (params[0]) in `vals` sits on that physical
// bound (a lower bound of 0, where the effect vanishes, does not count), else empty.
std::string sizeBound(const Context& cx, const std::string& e, const std::map<std::string, double>& vals);
// Another start for a candidate fit of effect e: `vals` (the current model's values) with the
// effect's parameters from `scanned`, and its size where the effect vanishes (boundSide empty:
// the current model's own point) or halfway from there to the bound it ended on (log-halfway
// for a log-scaled size).
std::map<std::string, double> retryStart(const Context& cx, const std::string& e, std::map<std::string, double> vals,
                                         const std::map<std::string, double>& scanned, const std::string& boundSide);
// `vals` with effect e's parameters at their start values: the catalogue's initial value (in this
// data set's units of μ), or the baseline value a parameter continues (viscous_damping's ζ).
std::map<std::string, double> effectStart(const Context& cx, const std::string& e, std::map<std::string, double> vals);
// The candidate's start: each log-scaled parameter of `effect` scanned over its range (alone and
// with D_c or ε_T) around `vals`, the lowest sum of squares over the runs idx kept. `previous`
// (optional: the candidate's own fit before the current model was refitted) replaces the scanned
// point when it fits the runs better (ties: the scanned point).
std::map<std::string, double> scannedStart(const Context& cx, const Spec& s2, const std::string& effect,
                                           std::map<std::string, double> vals, const std::vector<size_t>& idx,
                                           const std::map<std::string, double>* previous = nullptr);

void prepareSegments(const IdentifyRun& r, size_t dec, const IdentifyOptions& opt, Prepared& p);
void prepareLawMasks(double vStick_mps, Prepared& p);
// Prepared::stepSlip of a run decimated by `dec` (p's decimated samples set): the recorded slip,
// linear between recorded samples, at the ends of the `substeps` law steps of every interval.
void prepareStepSlip(const IdentifyRun& r, size_t dec, int substeps, Prepared& p);

// n_eff of the criterion below: the n samples, capped by neffCap, at least 2.
double effectiveCount(double n, double neffCap);
double bic(double ss, double n, double neffCap, int p);
// Whether a restart from a held-out refit's point (IdentifyOptions::heldOutRestart; baseline or
// candidate) is worth taking: that point lowers the BIC by more than the margin an effect must
// clear (`bicGain` = BIC of the full fit minus BIC at that point).
bool restartWorthIt(double bicGain, double bicMargin);
// A candidate refitted from a held-out refit's point keeps the noise-null verdict of its first
// fit (the refit only lowers its sum of squares further); the gain it reports is the refit's:
// the first gain plus what the refit lowered the sum of squares by (only when the null ran).
void creditRestartGain(CandidateScore& sc, double ssFirst, double ssRefit);
// Correlation of effect e's size parameter (params[0]) with every other free parameter of the
// fit that is not e's own, keyed by the parameter's name, or by the effect's name for another
// effect's size parameter (empty when e's size is not free). pairCorrelation: also defined
// when the fit is not identifiable, with the undetermined directions held.
std::map<std::string, double> sizeCorrelations(const FitResult& fit, const std::string& e);
// The added effect whose size trades off with the candidate's in their joint fit: the one with
// the largest variance inflation 1/(1 − r²) of the two sizes above maxVif (empty: none).
std::string confoundedWith(const CandidateScore& sc, const std::vector<std::string>& added, double maxVif);
// The baseline parameter (a sizeCorrelation key that is neither an effect nor an effect's
// parameter) whose correlation with the candidate's size has the largest variance inflation
// above maxVif; empty if none.
std::string baselineTradeOff(const CandidateScore& sc, double maxVif);
// The value of an effect's size parameter q at which the effect is absent in this data set's
// model (q.vanishing, except where a baseline parameter covers part of the range).
double effectVanishes(const Context& cx, const std::string& effect, const EffectParam& q);
constexpr int kMinUnitsForTests = 3;  // runs needed for the paired test and the jackknife (≥ 2 degrees of freedom)
bool passesSelection(const Context& cx, CandidateScore& sc, const FitOutcome& fit, const ModelErrors& ref,
                     const ModelErrors& with, const std::vector<std::map<std::string, double>>& loo,
                     const std::vector<size_t>& units, double tauInt);
// The fit runs' operating point (effects/effect.hpp): the duration-weighted median of the stick
// episodes that begin after a slip and end in one, stuck meaning |V| below
// IdentifyOptions::stickVelocity_mps.
OperatingPoint operatingPoint(const Context& cx);
// Test (3) alone: the effect's size (EffectSize, else its first parameter) in `fit` differs from the value at which the effect
// vanishes by more than t_{1−α/2} standard errors (the jackknife over `loo` when it has at least
// kMinUnitsForTests fits and is the larger, else the Jacobian's × sqrt(τ_int)). Fills sc's size
// figures; false with sc.reason set when it does not.
bool passesSizeTest(const Context& cx, CandidateScore& sc, const FitOutcome& fit,
                    const std::vector<std::map<std::string, double>>& loo, double tauInt);
// The p of a paired held-out test as test (2) judges it (IdentifyOptions::heldOutMidP): the exact
// sign-flip test's (mid-)p where it can decide (2^−K below heldOutAlpha), else the t-test's; `exact`
// says which.
double heldOutPValue(const PairedTest& pt, const IdentifyOptions& opt, bool& exact);
// The "unexplained" verdict (IdentifyResult::unexplained): the final residual's structure that
// the runs' state predicts from run to run (Diagnostics::structure) passes what an effect's
// held-out gain must pass (test (2) with its relevance margin): with at least kMinUnitsForTests
// runs the paired test at heldOutAlpha, with 2 every run better; and a mean gain of at least
// minHeldOutGain of the MSE. Structure smaller than that could not be added as an effect either.
// `why` says what was found either way.
bool structureRemains(const StructureTest& st, const IdentifyOptions& opt, std::string& why);

// The recovery self-test (self_test.hpp) around the fitted baseline `base` of `spec`; neffCap as
// the loop's BIC uses it.
SelfTestResult runSelfTest(const Context& cx, const Spec& spec, const FitOutcome& base, const std::vector<size_t>& fitIdx,
                           const std::vector<std::string>& cands, double neffCap);

dsp::Sos predictionFilterAt(const FilterSettings& fs, double rate_Hz);
bool prepareContext(std::vector<IdentifyRun>& runs, const IdentifyOptions& opt, Context& cx, int& decimation,
                    std::string& why);

}  // namespace stickslip::identify::detail
