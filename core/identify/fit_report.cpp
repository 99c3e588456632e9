#include "fit_report.hpp"

#include <cmath>
#include <string>

#include "core/io/units.hpp"

namespace stickslip::identify {

namespace {

// A law's key as a JSON name: "rate-state" → "rate_state".
std::string jsonName(LawKind law) {
    std::string s = toString(law);
    for (char& c : s)
        if (c == '-') c = '_';
    return s;
}
nlohmann::json numOrNull(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }
}  // namespace

nlohmann::json toJson(const DatasetFit& f) {
    nlohmann::json j;
    j["model"] = toString(f.model.law);
    j["setup"] = toString(f.setup);
    nlohmann::json params = nlohmann::json::object();
    for (size_t i = 0; i < f.fit.names.size(); ++i) {
        const std::string& n = f.fit.names[i];
        std::string unit;
        if (n != "zeta") io::paramUnit(n, unit);
        params[n] = {{"value", f.fit.values[i]},
                     {"stderr", numOrNull(i < f.fit.stderrs.size() ? f.fit.stderrs[i] : NAN)},
                     {"stderr_iid", numOrNull(i < f.stderrsIid.size() ? f.stderrsIid[i] : NAN)},
                     {"stderr_jacobian", numOrNull(i < f.stderrsJacobian.size() ? f.stderrsJacobian[i] : NAN)},
                     {"stderr_jackknife", numOrNull(i < f.stderrsJackknife.size() ? f.stderrsJackknife[i] : NAN)},
                     {"free", i < f.fit.free.size() && static_cast<bool>(f.fit.free[i])},
                     {"unit", unit}};
    }
    if (f.model.law == LawKind::RateState && f.model.tieC1ToMu && !f.model.values.count("C1") && f.model.values.count("mu"))
        params["C1"] = {{"value", f.model.values.at("mu")}, {"stderr", nullptr}, {"free", false}, {"unit", ""}, {"tied_to", "mu"}};
    j["parameters"] = params;
    j["stderr_convention"] =
        "stderr = Jacobian standard error x sqrt(tau_int), tau_int = integrated autocorrelation time of the residuals at "
        "the optimum (n_eff = n / tau_int), or the jackknife over runs (stderr_jackknife, leave-one-run-out refits) where "
        "that is larger; stderr_jacobian = the first, stderr_iid = Jacobian value for independent residuals. The "
        "Jacobian value assumes one quadratic minimum; where the cost has several (the dynamics fit of C1, eta, vc: on "
        "the synthetic D05 5-15 Jacobian standard errors apart) only the jackknife is honest";
    j["jackknife_fits"] = f.jackknifeFits;
    j["stderr_warning"] = f.stderrWarning.empty() ? nlohmann::json(nullptr) : nlohmann::json(f.stderrWarning);
    j["tau_int"] = numOrNull(f.tauInt);
    nlohmann::json corr = nlohmann::json::array();
    const size_t p = f.fit.freeNames.size();
    for (size_t a = 0; a < p; ++a) {
        nlohmann::json row = nlohmann::json::array();
        for (size_t b = 0; b < p; ++b)
            row.push_back(numOrNull(f.fit.correlation.size() == p * p ? f.fit.correlation[a * p + b] : NAN));
        corr.push_back(row);
    }
    j["correlation"] = {{"names", f.fit.freeNames}, {"matrix", corr}};
    j["identifiable"] = f.fit.identifiable;
    j["identifiability"] = f.fit.identifiabilityMessage;
    j["condition_number"] = numOrNull(f.fit.conditionNumber);
    nlohmann::json runs = nlohmann::json::array();
    for (const RunScore& r : f.runs) {
        nlohmann::json o = {{"file", r.file},       {"role", r.role},
                            {"samples", r.samples}, {"rms", numOrNull(r.rms_N)},
                            {"nrmse", numOrNull(r.nrmse)}, {"rms_force_N", numOrNull(r.rms_N)},
                            {"nrmse_force", numOrNull(r.nrmseForce)}};
        if (f.setup == SetupKind::Dynamics) {
            o["rms_disp_m"] = numOrNull(r.rms_m);
            o["nrmse_disp"] = numOrNull(r.nrmseDisp);
        }
        if (!r.ok) o["error"] = r.message;
        runs.push_back(o);
    }
    j["runs"] = runs;
    j["fit_nrmse"] = numOrNull(f.fitNrmse);
    j["validation_nrmse"] = numOrNull(f.validationNrmse);
    j["solver"] = toJson(f.fit);
    return j;
}

nlohmann::json toJson(const FitResult& fit) {
    nlohmann::json costs = nlohmann::json::array();
    for (double c : fit.startCosts) costs.push_back(numOrNull(c));
    return {{"summary", fit.solverSummary}, {"converged", fit.converged},
            {"cost", numOrNull(fit.cost)},  {"residual_rms", numOrNull(fit.rms)},
            {"residuals", fit.residualCount}, {"starts", fit.startsTried},
            {"start_costs", costs},          {"stopped_early", fit.stoppedEarly},
            {"best_start", fit.bestStart},   {"evaluations", fit.residualEvaluations},
            {"wall_time_s", fit.wallTime_s}};
}

nlohmann::json fitReportJson(const std::vector<const DatasetFit*>& fits) {
    if (fits.empty() || !fits.front()) return nlohmann::json::object();
    nlohmann::json rep = toJson(*fits.front());
    if (fits.size() > 1 && fits[1]) {
        const DatasetFit& a = *fits[0];
        const DatasetFit& b = *fits[1];
        rep["model"] = "both";
        rep["primary_model"] = toString(a.model.law);
        rep["coulomb"] = toJson(b);
        nlohmann::json cmp = nlohmann::json::array();
        for (size_t i = 0; i < a.runs.size() && i < b.runs.size(); ++i)
            cmp.push_back({{"file", a.runs[i].file},
                           {"role", a.runs[i].role},
                           {"nrmse_" + jsonName(a.model.law), numOrNull(a.runs[i].nrmse)},
                           {"nrmse_" + jsonName(b.model.law), numOrNull(b.runs[i].nrmse)}});
        rep["comparison"] = cmp;
    }
    return rep;
}

nlohmann::json toJson(const PredictSettings& p) {
    return {{"stride", p.stride},
            {"substeps", p.substeps},
            {"warmup_s", p.warmup_s},
            {"dt_s", p.dt_s},
            {"segment_s", p.segment_s},
            {"segment_spacing_s", p.segmentSpacing_s},
            {"residual_stride", p.residualStride},
            {"slip_start_fraction", p.slipStartFraction},
            {"fit_initial_state", p.fitInitialState},
            {"initial_state_iterations", p.initialStateIterations},
            {"filter_prediction", p.filterPrediction}};
}

}  // namespace stickslip::identify
