// Nonlinear least squares with bounds, several starts and honest uncertainties (issue 5).
//
// Two layers:
//  1. A GENERIC engine, fitLeastSquares(FitProblem): any residual callback over named,
//     bounded parameters (free or fixed), solved with Ceres (numeric central differences
//     through the callback), parameters internally scaled (log for positive scale
//     parameters) so the problem is well conditioned, several deterministic starting points,
//     optional robust loss. Standard errors and correlations come from (JᵀJ)⁻¹ σ̂² at the
//     optimum, with σ̂² = 2·cost/(m − p); a near-singular JᵀJ is reported as "not
//     identifiable" (no standard errors) rather than printed as meaningless numbers.
//     The identify loop (missing effects) reuses this engine with its own residuals.
//  2. Dataset-level helpers: fit a friction law to a Dataset in either set-up (prescribed
//     slip or dynamics with multiple shooting), per-run RMS / NRMSE, held-out validation.
// All Ceres code lives in fit.cpp; the standard errors at the optimum are in fit_uncertainty.cpp
// (Eigen), the internals the two share in fit_internal.hpp.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "../integrate/run_result.hpp"
#include "../params.hpp"
#include "predict.hpp"

namespace stickslip::identify {

// How the solver sees a parameter internally (the user always sees physical values).
enum class ParamScale {
    Linear,  // z = (value − lower)/(upper − lower) style affine scaling by the range
    Log,     // z = log(value): for positive scale parameters (η, D_c, v_c, ε_T, …); needs lower > 0
};

// One named parameter with physical bounds. Fixed parameters are passed to the residual
// callback unchanged.
struct FitParameter {
    std::string name;          // e.g. "mu", "eta", "Dc", "vc", "epsT", "k", "m", "c"
    double value = 0.0;        // starting value (and the value used when fixed), physical units
    double lower = 0.0;        // lower bound, physical units
    double upper = 1.0;        // upper bound, physical units (> lower)
    bool free = true;          // fitted (true) or held at `value` (false)
    ParamScale scale = ParamScale::Linear;
};

enum class LossKind { None, Huber, Cauchy };

// How the solver's Jacobian is differenced while it iterates: central (2p displaced points,
// error O(δ²)) or forward (p points plus the residual the step already has, error O(δ), as
// MINPACK's lmdif does). The standard errors at the optimum use central differences (without
// FitProblem::analyticJacobian).
enum class JacobianKind { Central, Forward };

// The residual callback receives ALL parameter values (free and fixed) in the order of
// FitProblem::parameters, in physical units, and fills `residuals` (size residualCount).
// Return false when the model cannot be evaluated there (simulation failure): the solver
// then treats the point as infeasible and steps back.
using ResidualFunction = std::function<bool(const std::vector<double>& params, std::vector<double>& residuals)>;
// Optional: the residuals at several parameter points at once (the 2p points of a numeric
// Jacobian), for callers that can spread the work over threads. Same contract as
// ResidualFunction for every point: residuals[i] for params[i] (sized residualCount on entry),
// ok[i] = 0 where the model cannot be evaluated. The results must not depend on how the work
// is scheduled.
using BatchResidualFunction = std::function<void(const std::vector<std::vector<double>>& params,
                                                 std::vector<std::vector<double>>& residuals, std::vector<char>& ok)>;
// Optional: the Jacobian of the residuals at one point, ∂r_i/∂θ_j (row-major, residualCount ×
// parameters.size(), columns of fixed parameters unused), in physical units, from the same
// model run as `residuals` (e.g. forward sensitivities). Return false where it cannot be
// formed: that point's Jacobian is then differenced as without it.
using JacobianFunction = std::function<bool(const std::vector<double>& params, std::vector<double>& jacobian)>;

// A grid search on one free parameter before the local solver (first start only): the cost is
// evaluated at the start with `name` set to each of `values` (others unchanged, all points in
// one batch), and the solver starts from the lowest. For a parameter whose cost has several
// narrow valleys (the contact stiffness ε_T sets the frequency of the stick ringing, which the
// model must match in phase) a local solver from a fixed start stays in the nearest valley.
struct ParameterScan {
    std::string name;
    std::vector<double> values;  // physical units
};

struct FitProblem {
    std::vector<FitParameter> parameters;
    std::vector<ParameterScan> scans;  // applied in order, each from the best point of the last
    ResidualFunction residuals;
    BatchResidualFunction batchResiduals;  // optional (else `residuals` is called point by point)
    // Optional: the Jacobian while the solver iterates and for the standard errors at the
    // optimum, instead of `jacobian`'s differences and the central ones.
    JacobianFunction analyticJacobian;
    size_t residualCount = 0;
    // Nuisance parameters the residual callback estimates itself for every point (variable
    // projection, e.g. the shooting segments' initial states): they use up residual degrees of
    // freedom, so σ̂² = Σ r² / (m − p − profiledParameters).
    size_t profiledParameters = 0;

    int multistarts = 3;               // starting points: the given values + (multistarts−1) random in the box
    LossKind loss = LossKind::None;    // robust loss on each residual
    double lossScale = 1.0;            // residual size at which the robust loss bends
    uint64_t seed = 20260101;          // deterministic random starts
    int maxIterations = 60;            // per start
    // Contractions of the projected line search Ceres runs after each trust-region step of a
    // bounded problem (Solver::Options::max_num_line_search_step_size_iterations, default 20).
    // A step the trust region then rejects spends them all: on the synthetic sets most of a
    // warm-started fit's residual evaluations (docs/identify-results.md, session 60).
    int maxLineSearchSteps = 20;
    double functionTolerance = 1e-9;   // relative cost change to stop
    double parameterTolerance = 1e-9;  // relative step (internal scale) to stop
    double relativeStep = 1e-4;        // difference step, relative to the internal parameter
    JacobianKind jacobian = JacobianKind::Central;  // the solver's Jacobian while it iterates
    // Stop the multistart early once `agreeingStarts` starts (≥ 2) have ended at the same cost
    // within sameCostTolerance (relative) and no start has been lower: further random starts are
    // then unlikely to find another minimum. 0 = always run all `multistarts` starts.
    int agreeingStarts = 0;
    double sameCostTolerance = 1e-6;
    double conditionLimit = 1e10;      // cond(JᵀJ, scaled to unit diagonal) above this: not identifiable
    // false: only the optimum is wanted (a refit whose values alone are used, e.g. a
    // leave-one-run-out refit). The 2p-point Jacobian after the solve is skipped: stderrs are
    // NaN, correlation and scaledNormal empty, identifiable false, rms from the cost (plain
    // loss only, else NaN). The optimum itself does not depend on this.
    bool uncertainty = true;
    const std::atomic<bool>* cancel = nullptr;        // polled between solver iterations
    std::function<void(double fraction)> progress;    // 0..1 over all starts

    // Every problem with the set-up (bounds, sizes, missing callback), empty if usable.
    ParamIssues validate() const;
};

enum class FitStatus { Ok, Failed, Cancelled };

struct FitResult {
    FitStatus status = FitStatus::Failed;
    std::string message;                    // why it failed; empty when Ok

    std::vector<std::string> names;         // all parameters, in problem order
    std::vector<double> values;             // best values (physical units), all parameters
    std::vector<bool> free;                 // which ones were fitted
    std::vector<double> stderrs;            // 1-σ standard errors; 0 for fixed, NaN when not identifiable
    // Correlation among the FREE parameters (freeNames order), row-major, size nFree².
    std::vector<std::string> freeNames;
    std::vector<double> correlation;
    bool identifiable = false;              // JᵀJ well conditioned at the optimum
    std::string identifiabilityMessage;     // e.g. "not identifiable: cond(JᵀJ) = 3e14; nearly dependent: eta, vc"
    double conditionNumber = 0.0;           // of the unit-diagonal-scaled JᵀJ
    // That unit-diagonal-scaled JᵀJ of the free parameters (row-major, nFree²; a zero row and
    // column for a parameter without effect on the residuals) and the limit it was judged
    // against: what pairCorrelation needs when the fit is not identifiable.
    std::vector<double> scaledNormal;
    double conditionLimit = 0.0;

    double cost = 0.0;                      // ½ Σ ρ(r²) at the optimum (Ceres convention)
    double initialCost = 0.0;               // the same at the best start's first point (after the scans)
    double rms = 0.0;                       // sqrt(Σ r² / m), plain residuals
    size_t residualCount = 0;
    bool converged = false;                 // best start ended with Ceres CONVERGENCE
    int startsTried = 0;
    int bestStart = -1;                     // index of the start that gave the optimum (0 = given values)
    std::vector<double> startCosts;         // final cost of every start tried
    bool stoppedEarly = false;              // agreeingStarts starts agreed before all multistarts ran
    std::string solverSummary;              // Ceres BriefReport of the best start (+ one line per start)
    double wallTime_s = 0.0;
    long residualEvaluations = 0;           // residual vectors computed (repeated points are reused, not counted)

    bool ok() const { return status == FitStatus::Ok; }
    double value(const std::string& name) const;   // NaN if no such parameter
    double stderrOf(const std::string& name) const;
};

// Solve the problem. Never throws; failure and cancellation come back as a status.
FitResult fitLeastSquares(const FitProblem& problem);

// Correlation of the estimates of free parameters i and j (indices into freeNames).
// Identifiable fit: the correlation matrix's entry. Otherwise the pair's correlation when the
// other parameters may absorb only what the data determine: the Schur complement of the pair in
// the scaled JᵀJ, the others' block pseudo-inverted with eigenvalues below λ_max/conditionLimit
// dropped (a direction the data do not determine is held, not traded). This equals the
// correlation matrix's entry when the fit is identifiable, and tends to ±1 when the pair itself
// is the undetermined direction. NaN when either parameter is determined by the others alone
// or has no effect, or without a scaled JᵀJ.
double pairCorrelation(const FitResult& fit, size_t i, size_t j);

// Standard physical bounds and scale for a named model parameter (keys as in params.hpp
// setParam: mu C1 eta Dc vc epsT k m c tN). `setup` widens μ/η/C1 for the prescribed
// set-up where t_N is only a reference load. Unknown name: returns false.
bool defaultParameter(const std::string& name, SetupKind setup, FitParameter& out);

// `points` values log-spaced from lower to upper inclusive (lower > 0, points ≥ 2).
std::vector<double> logGrid(double lower, double upper, int points);

// ---------------------------------------------------------------------------------------
// Dataset level: a friction law fitted jointly to cleaned runs (shared law parameters, each
// run with its own known settings), scored per run on fit and held-out validation data.

// The default ε_T scan of the dynamics set-up: 1e4–1e7 N/m, from the compliant 1.1e4 of
// MODEL.md to a decade above the paper's "as large as practical" 1e6; 16 values per decade.
inline constexpr double kEpsTScanLower = 1e4, kEpsTScanUpper = 1e7;
inline constexpr int kEpsTScanPoints = 49;
// The v_c scan in the steady-state-curve coordinates (DatasetFitSettings::curveCoordinates: the
// slope and curvature at V = 0 held, so C1 and η follow v_c): 0.01–1 m/s, 8 values per decade.
inline constexpr double kVcScanLower = 0.01, kVcScanUpper = 1.0;
inline constexpr int kVcScanPoints = 17;

struct DatasetFitSettings {
    SetupKind setup = SetupKind::Prescribed;
    LawKind law = LawKind::RateState;
    // Free parameters (names as in defaultParameter, plus "zeta" = rig damping ratio).
    // Names that the chosen law does not have (eta, Dc, vc, C1, r for Coulomb) are dropped.
    std::vector<std::string> free = {"mu", "eta", "Dc", "vc", "epsT"};
    std::map<std::string, double> start;  // starting (or fixed) values overriding the defaults
    bool tieC1ToMu = true;                // C1 = μ unless C1 is free or given in `start`
    bool estimateStart = true;            // μ start from the data (median |F|/t_N while sliding)
    PredictSettings predict;
    // Dynamics set-up, rate-state law: start the free sliding-law parameters (μ, C1, η, v_c) and
    // m* from the equation-error fit of identify.hpp (the rigid-contact law along the measured
    // slip velocity while sliding, and the equation of motion m* ẍ + c ẋ + k x = F with the
    // measured acceleration), a fast fit (≈ 4 s on D05). m* matters most: with ε_T it sets the
    // stick ringing, so the ε_T scan is informative only with m* near its value. The
    // equation-error C1, η, v_c lie on a valley of their own (on D05 they moved from 0.31, 1.13,
    // 0.12 to 1.40, 3.76, 0.27 when 0.25 s more was trimmed from each run's ends). Values in
    // `start` win; only with estimateStart.
    bool equationErrorStart = true;
    // Dynamics set-up, rate-state law with C1, η and v_c all free: the solver moves in the coordinates of the
    // steady-state curve μ_ss(V) = μ + C1 (e^{−V/v_c} − 1) + η V (Eq. 5) instead, its slope at
    // V = 0, s = η − C1/v_c (s/m, linear in [−50, 50]), and curvature κ = C1/v_c² (s²/m², log),
    // with v_c itself: C1 = κ v_c², η = s + κ v_c. The data fix s and κ well and v_c poorly, so
    // the cost has a long valley that is curved in (C1, η, v_c) and straight along v_c here; a
    // trust-region solver crawls along the curved one (on D05 it stopped at cost 1.015, 60
    // iterations, C1 = 0.75, while from the answer key it reached 1.0105). A point whose C1 or
    // η leaves its physical bounds cannot be evaluated. Values, standard errors (delta method)
    // and correlations are reported for C1, η, v_c as usual. With autoScan, v_c is then scanned
    // (kVcScan) after ε_T. Not in the prescribed set-up, where η and C1/v_c per unit reference
    // load span decades (s would need a range far wider than [−50, 50]).
    bool curveCoordinates = true;
    // Grid searches before the local fit (FitProblem::scans). autoScan adds, in the dynamics
    // set-up with ε_T free and no scan of it given, ε_T over kEpsTScan (log grid): ε_T sets the
    // stick ringing sqrt((k + ε_T)/m*), and the cost has narrow valleys in it (on D05 the fit
    // from ε_T = 1e6 stayed at 9e5 with cost 3.6; the answer key's valley, cost ≈ 1, is less
    // than a factor 1.3 wide).
    std::vector<ParameterScan> scans;
    bool autoScan = true;
    int multistarts = 3;
    // Up to `multistarts` starts: stop once this many have ended at the same best cost (within
    // 1e-6 relative, FitProblem::agreeingStarts): two independent starts, one from the data
    // estimate and one random, that reach the same minimum make a third unlikely to find a
    // lower one. The solver summary (report JSON "solver.summary") says when it stopped early.
    // 0 = always run all starts.
    int agreeingStarts = 2;
    LossKind loss = LossKind::None;
    double lossScale = 1.0;
    uint64_t seed = 20260101;
    int maxIterations = 40;
    double relativeStep = 1e-4;  // central-difference step (FitProblem::relativeStep)
    // Jackknife over runs: with K ≥ 3 fit runs, repeat the whole fit K times leaving one run out
    // and report stderr = max(Jacobian × sqrt(τ_int), jackknife) per parameter. The Jacobian value
    // assumes the cost is quadratic over the confidence region; where it is not it is too small
    // (on D05 the C1–η–v_c–D_c valley holds several minima, Δχ² ≈ 10–50 apart, that the Jacobian
    // puts 5–12 standard errors apart). Each refit repeats the procedure (starts from its own
    // runs' data, the same scans and multistarts), not a warm start from the full-data optimum:
    // the estimator whose spread is wanted is the whole procedure, and warm-started refits stay
    // in the full-data fit's local minimum (on D05 μ's jackknife s.e. was then 0.00066 for an
    // error of 0.0023). Runs are the independent units (separate recordings). Costs K fits.
    bool jackknife = false;
    // Predictions run on this many threads at once: every (parameter point, run) pair is one
    // task, so a single evaluation spreads its runs and a numeric Jacobian its 2p displaced
    // points over the threads (results do not depend on it). 0 = hardware_concurrency().
    int threads = 0;
    const std::atomic<bool>* cancel = nullptr;
    std::function<void(double)> progress;
};

// Errors of one run. NRMSE = RMS error / RMS of the measured signal over the scored samples.
// In the dynamics set-up `nrmse` combines both channels: sqrt((nrmse_F² + nrmse_x²)/2).
struct RunScore {
    std::string file;
    std::string role;           // "fit" or "validation"
    size_t samples = 0;
    double rms_N = 0.0;         // force RMS error
    double nrmseForce = 0.0;
    double rms_m = 0.0;         // slider displacement RMS error (dynamics; else 0)
    double nrmseDisp = 0.0;
    double nrmse = 0.0;
    bool ok = false;
    std::string message;
};

struct DatasetFit {
    bool ok = false;
    std::string message;
    SetupKind setup = SetupKind::Prescribed;
    ModelSpec model;                 // the fitted values (free and fixed)
    FitResult fit;
    std::vector<RunScore> runs;      // fit runs first, then validation runs
    double fitNrmse = 0.0;           // pooled over the fit runs: √(Σ n_k NRMSE_k² / Σ n_k)
    double validationNrmse = 0.0;    // pooled over the validation runs (NaN when none)
    // Honest standard errors. The Jacobian formula assumes independent residuals; neighbouring
    // residuals of one run (one shooting segment) are correlated (filtered noise, a wrong
    // initial state persisting through a segment). tauInt = 1 + 2 Σ ρ_k (pooled autocorrelation
    // of the residuals at the optimum within contiguous stretches, summed until ρ_k < 0.05) is
    // the number of residuals per independent one (n_eff = n/τ_int), and the REPORTED
    // fit.stderrs are the Jacobian ones times sqrt(tauInt) (≥ 1). stderrsIid keeps the
    // Jacobian (independent-residual) values, in fit.names order.
    double tauInt = 1.0;
    std::vector<double> stderrsIid;
    // Jackknife over runs (DatasetFitSettings::jackknife), in fit.names order (NaN when not
    // run or for fixed parameters); stderrsJacobian = Jacobian × sqrt(τ_int). The reported
    // fit.stderrs are the larger of the two.
    std::vector<double> stderrsJackknife, stderrsJacobian;
    int jackknifeFits = 0;
    // Non-empty when the reported standard errors are known to be too small: a dynamics fit with
    // C1, η, v_c free (steady-state-curve coordinates) without the jackknife.
    std::string stderrWarning;
};

DatasetFit fitDataset(const std::vector<CleanRun>& fitRuns, const std::vector<CleanRun>& validationRuns,
                      const DatasetFitSettings& settings);

RunScore scoreRun(const CleanRun& run, SetupKind setup, const ModelSpec& model, const PredictSettings& predict,
                  const std::string& role, Prediction* prediction = nullptr);

// Held-out validation by time: the first `fraction` of the fit window is kept for fitting, the
// rest becomes a validation run (same data, later window).
std::pair<CleanRun, CleanRun> splitByTime(const CleanRun& run, double fraction);

// splitByTime on every fit run: the later parts (file name + "#later") are appended to
// `validationRuns`. Returns an error message (empty on success); `fraction` must be in (0, 1).
std::string holdOutLaterParts(std::vector<CleanRun>& fitRuns, std::vector<CleanRun>& validationRuns, double fraction);

}  // namespace stickslip::identify
