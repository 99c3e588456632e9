// The `fit.json` report (issue 5), one layout for `stickslip-cli fit --report` and the GUI's
// Identify panel: per law the parameters (value, stderr, stderr_iid, free, unit), the
// correlation matrix of the free ones, identifiability, per-run RMS/NRMSE with roles, pooled
// fit and validation NRMSE, and the solver summary.
#pragma once

#include <nlohmann/json.hpp>
#include <vector>

#include "fit.hpp"
#include "predict.hpp"

namespace stickslip::identify {

// One law's fit: {"model", "setup", "parameters", "stderr_convention", "tau_int",
// "correlation": {"names", "matrix"}, "identifiable", "identifiability", "condition_number",
// "runs": [{"file", "role", "samples", "rms", "nrmse", ...}], "fit_nrmse", "validation_nrmse",
// "solver"}. Non-finite numbers are written as null.
nlohmann::json toJson(const DatasetFit& fit);

// The report body for one or two laws fitted to the same runs (primary first): the primary
// law's block at top level; with two, "model" = "both", "primary_model", the second law's block
// under "coulomb" and a per-run "comparison" of the two NRMSEs. Empty object for no fits.
nlohmann::json fitReportJson(const std::vector<const DatasetFit*>& fits);

// A solve's summary, the block both reports write under "solver": {"summary" (Ceres' brief
// report and one line per start: cost, iterations, evaluations), "converged", "cost",
// "residual_rms", "residuals", "starts", "start_costs" (each start's final cost, null where it
// failed), "stopped_early", "best_start", "evaluations", "wall_time_s"}.
nlohmann::json toJson(const FitResult& fit);

// How predictions were made (stride, substeps, warm-up, dt, segments, filtered prediction).
nlohmann::json toJson(const PredictSettings& p);

}  // namespace stickslip::identify
