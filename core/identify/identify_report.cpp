// The identify report as JSON (identify.hpp).
#include <cmath>
#include <cstdio>

#include "identify.hpp"
#include "fit_report.hpp"

#include "fit_internal.hpp"

namespace stickslip::identify {

namespace {

nlohmann::json num(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

nlohmann::json toJson(const std::vector<ParamEstimate>& ps) {
    nlohmann::json j = nlohmann::json::object();
    for (const ParamEstimate& p : ps) j[p.name] = {{"value", num(p.value)}, {"stderr", num(p.stderr_)}};
    return j;
}

nlohmann::json toJson(const ModelErrors& e) {
    nlohmann::json runs = nlohmann::json::array();
    for (const RunError& r : e.runs)
        runs.push_back({{"file", r.file}, {"role", r.role}, {"rms_N", num(r.rms_N)}, {"nrmse", num(r.nrmse)},
                        {"held_out_nrmse", num(r.heldOutNrmse)}});
    return {{"fit_nrmse", num(e.fitNrmse)}, {"validation_nrmse", num(e.validationNrmse)}, {"runs", runs},
            {"held_out_refits_retried", e.retriedRefits}, {"held_out_refits_unmoved", e.unmovedRefits},
            {"held_out_law_coordinate_passes", e.lawPasses}};
}

}  // namespace

static nlohmann::json structureJson(const StructureTest& s) {
    nlohmann::json sig = nlohmann::json::array();
    for (const SignalGain& g : s.bySignal) sig.push_back({{"signal", g.signal}, {"mean_log_mse_ratio", num(g.meanLogRatio)}});
    nlohmann::json ratios = nlohmann::json::array();
    for (double d : s.logRatios) ratios.push_back(num(d));
    return {{"test", "runs held out in turn; residual predicted by the step function (at one of five resolutions) or line per sign of the candidate signal that best predicts the other runs from each other"},
            {"runs", s.runs},
            {"bins", s.bins},
            {"log_mse_ratio_per_run", ratios},
            {"signal_per_run", s.chosen},
            {"mean_log_mse_ratio", num(s.test.meanLogRatio)},
            {"t", num(s.test.t)},
            {"p_t", num(s.test.pValue)},
            {"p_exact", num(s.test.exactP)},
            {"p_mid", num(s.test.midP)},
            {"signals_alone", sig}};
}

nlohmann::json toJson(const Diagnostics& d, bool withSeries) {
    nlohmann::json corr = nlohmann::json::object();
    for (const SignalCorrelation& c : d.correlations) corr[c.signal] = num(c.correlation);
    nlohmann::json j = {{"rms", num(d.rms)},
                        {"correlations", corr},
                        {"whiteness",
                         {{"test", "Ljung-Box"},
                          {"lags", d.whiteness.lags},
                          {"decimation", d.whiteness.decimation},
                          {"Q", num(d.whiteness.ljungBoxQ)},
                          {"p_value", num(d.whiteness.pValue)},
                          {"white", d.whiteness.white},
                          {"structure_ratio", num(d.whiteness.structureRatio)}}},
                        {"structure", structureJson(d.structure)},
                        {"structure_eom", structureJson(d.structureEom)},
                        {"integrated_acf_time_samples", num(d.integratedAcfTime)},
                        {"spectrum_harmonic_fraction", num(d.spectrum.harmonicFraction)},
                        {"forcing_harmonics_Hz", d.spectrum.harmonics_Hz}};
    if (withSeries) {
        j["acf"] = d.whiteness.acf;
        // Spectrum up to 150 Hz (the measurement bandwidth).
        nlohmann::json f = nlohmann::json::array(), p = nlohmann::json::array();
        for (size_t k = 0; k < d.spectrum.frequency_Hz.size() && d.spectrum.frequency_Hz[k] <= 150.0; ++k) {
            f.push_back(d.spectrum.frequency_Hz[k]);
            p.push_back(d.spectrum.power[k]);
        }
        j["spectrum"] = {{"frequency_Hz", f}, {"power", p}};
    }
    return j;
}

std::string selectionRule(const IdentifyResult& r) {
    auto g = [](double v) { return detail::fmt(v, "%g"); };
    return "An effect is added only if it lowers the BIC (n_eff = min(n / tau_int, slip episodes)) by more than " +
           g(r.bicMargin) + " AND lowers the sum of squares by more than the " + g(100.0 * (1.0 - r.nullAlpha)) +
           " % quantile of what " + std::to_string(r.nullReplicas) +
           " noise replicas of these runs give (AR(1) noise per run and channel, level and colour from the current residual, "
           "linearised candidate model) AND lowers the held-out NRMSE (leave-one-run-out, or the validation runs) consistently "
           "over the K held-out runs (one-sided p < " + g(r.heldOutAlpha) +
           " on the runs' ln MSE ratios: the exact sign-flip test" + (r.heldOutMidP ? std::string(", by its mid-p,") : std::string()) +
           " when 2^-K < " + g(r.heldOutAlpha) + ", else the paired t-test) AND by at least " + g(100.0 * r.minHeldOutGain) +
           " % of the held-out MSE on average over those runs (relevance margin) AND its size parameter differs from the value "
           "at which the effect vanishes by more than t_(K-1, 1-alpha/2) standard errors (alpha = " + g(r.identifiabilityAlpha) +
           "; the jackknife over the leave-one-run-out fits or, where larger, the Jacobian's x sqrt(tau_int)). Once the rounds "
           "end, an added effect whose size fails that test on the final fit (Jacobian x sqrt(tau_int)) and whose BIC against "
           "the final model refitted without it is not lower by more than the margin is dropped again (the backward check).";
}

namespace {

// The baseline's parameters, note and bound verdicts.
nlohmann::json baselineJson(const IdentifyResult& r) {
    nlohmann::json j = {{"model", "rate-state"}, {"parameters", toJson(r.baseline)}};
    if (!r.baselineNote.empty()) j["note"] = r.baselineNote;
    for (const BoundVerdict& b : r.baselineBounds)
        j["at_bound"].push_back({{"parameter", b.name},
                                {"side", b.side},
                                {"bound", num(b.bound)},
                                {"second_start", num(b.retryStart)},
                                {"second_start_ended_at", num(b.retryValue)},
                                {"bic_gain_of_second_start", num(b.bicGain)},
                                {"refitted_from_second_start", b.refitted},
                                {"left_later_to", num(b.leftLaterTo)},
                                {"verdict", b.verdict()}});
    j["first_fit_solver"] = toJson(r.baselineFirstFit);
    return j;
}

// One effect added: its parameters, the residual correlations that pointed to it, its scores.
nlohmann::json addedJson(const AddedEffect& e) {
    nlohmann::json pointed = nlohmann::json::object();
    for (const SignalCorrelation& c : e.pointedBy) pointed[c.signal] = num(c.correlation);
    nlohmann::json a({{"name", e.name},
                     {"parameters", toJson(e.params)},
                     {"diagnostics", {{"correlations_before", pointed}}},
                     {"delta_bic", num(e.deltaBic)},
                     {"held_out_nrmse_before", num(e.heldOutBefore)},
                     {"held_out_nrmse_after", num(e.heldOutAfter)},
                     {"confounded_with", e.confoundedWith}});
    if (e.lawStep.checked())
        a["law_step_check"] = {{"refinement", e.lawStep.refinement},
                               {"fit_ss_before", num(e.lawStep.ssBefore)},
                               {"fit_ss_after", num(e.lawStep.ssAfter)},
                               {"fit_ss_before_refined", num(e.lawStep.ssBeforeRefined)},
                               {"fit_ss_after_refined", num(e.lawStep.ssAfterRefined)},
                               {"gain", num(e.lawStep.gain())},
                               {"gain_refined", num(e.lawStep.gainRefined())}};
    if (!e.note.empty()) a["note"] = e.note;
    return a;
}

// One candidate: every test of the selection rule with its numbers, and the verdict.
nlohmann::json candidateJson(const CandidateScore& c) {
    return nlohmann::json({{"name", c.name},
                          {"round", c.round},
                          {"applicable", c.applicable},
                          {"accepted", c.accepted},
                          {"score", {{"delta_bic", num(c.deltaBic)}, {"fit_nrmse", num(c.fitNrmse)},
                                     {"n_eff", c.neff > 0 ? num(c.neff) : nlohmann::json(nullptr)},
                                     {"n_eff_limit", c.neffLimit.empty() ? nlohmann::json(nullptr) : nlohmann::json(c.neffLimit)},
                                     {"held_out_nrmse", c.heldOutNrmse >= 0 ? num(c.heldOutNrmse) : nlohmann::json(nullptr)}}},
                          {"residual", c.residual},
                          {"fit", {{"wall_s", num(c.fitWall_s)}, {"fits", c.fits}}},
                          {"held_out_test", c.heldOutUnits == 0 ? nlohmann::json(nullptr)
                                                                : nlohmann::json{{"runs", c.heldOutUnits},
                                                                                 {"mean_log_mse_ratio", num(c.heldOutMeanLogRatio)},
                                                                                 {"t", num(c.heldOutT)},
                                                                                 {"p_one_sided", num(c.heldOutP)},
                                                                                 {"test", !c.heldOutExact ? "paired t" : c.heldOutMidP ? "exact sign-flip, mid-p" : "exact sign-flip"},
                                                                                 {"p_exact", num(c.heldOutExactP)},
                                                                                 {"log_mse_ratio_per_run", [&] {
                                                                                      nlohmann::json a = nlohmann::json::array();
                                                                                      for (double v : c.heldOutLogRatios) a.push_back(num(v));
                                                                                      return a;
                                                                                  }()}}},
                          {"noise_null", c.nullReplicas == 0 ? nlohmann::json(nullptr)
                                                             : nlohmann::json{{"gain", num(c.gain)},
                                                                              {"null_quantile", num(c.nullGain)},
                                                                              {"numerics_gain", c.numericsGain >= 0 ? num(c.numericsGain) : nlohmann::json(nullptr)},
                                                                              {"own_minimum_gain", c.ownMinimumGain >= 0 ? num(c.ownMinimumGain) : nlohmann::json(nullptr)},
                                                                              {"replicas", c.nullReplicas}}},
                          {"simulated_null", c.simulatedNullGain == CandidateScore::kNoTest && c.simulatedNullNote.empty()
                                                 ? nlohmann::json(nullptr)
                                                 : nlohmann::json{{"gains", [&] {
                                                                       nlohmann::json a = nlohmann::json::array();
                                                                       for (double v : c.simulatedGains) a.push_back(num(v));
                                                                       return a;
                                                                   }()},
                                                                  {"quantile", c.simulatedNullGain == CandidateScore::kNoTest
                                                                                   ? nlohmann::json(nullptr)
                                                                                   : num(c.simulatedNullGain)},
                                                                  {"model", [&] {
                                                                       nlohmann::json o = nlohmann::json::object();
                                                                       for (const auto& [n, v] : c.simulatedNullModel) o[n] = num(v);
                                                                       return o;
                                                                   }()},
                                                                  {"note", c.simulatedNullNote}}},
                          {"size_test", c.sizeParam.empty() ? nlohmann::json(nullptr)
                                                            : nlohmann::json{{"parameter", c.sizeParam},
                                                                             {"value", num(c.sizeValue)},
                                                                             {"vanishes_at", num(c.sizeNull)},
                                                                             {"stderr", num(c.sizeStderr)},
                                                                             {"stderr_kind", c.sizeStderrKind},
                                                                             {"critical_t", num(c.sizeCritical)}}},
                          {"parameters", toJson(c.params)},
                          {"size_correlation", [&] {
                               nlohmann::json o = nlohmann::json::object();
                               for (const auto& [n, v] : c.sizeCorrelation) o[n] = num(v);
                               return o;
                           }()},
                          {"start_note", c.startNote.empty() ? nlohmann::json(nullptr) : nlohmann::json(c.startNote)},
                          {"confounded_with", c.confoundedWith.empty() ? nlohmann::json(nullptr) : nlohmann::json(c.confoundedWith)},
                          {"trades_off_with_baseline", c.tradesOffWithBaseline.empty()
                                                           ? nlohmann::json(nullptr)
                                                           : nlohmann::json(c.tradesOffWithBaseline)},
                          {"rejected_because", c.accepted ? nlohmann::json(nullptr) : nlohmann::json(c.reason)}});
}

// The selection rule and its settings.
nlohmann::json selectionJson(const IdentifyResult& r) {
    return {{"criterion", selectionRule(r)},
                      {"null_alpha", num(r.nullAlpha)}, {"null_replicas", r.nullReplicas}, {"bic_margin", num(r.bicMargin)}, {"null_numerics", r.nullNumerics}, {"restart_margin", num(r.restartMargin)},
                      {"held_out_alpha", num(r.heldOutAlpha)}, {"held_out_mid_p", r.heldOutMidP}, {"min_held_out_gain", num(r.minHeldOutGain)}, {"identifiability_alpha", num(r.identifiabilityAlpha)},
                      {"tau_int_samples", num(r.tauInt)},
                      {"slip_episodes", r.slipEpisodes}, {"decimation", r.decimation}, {"law_channel_edge_guard_samples", r.edgeGuard}, {"jacobian", r.jacobian},
                      {"line_search_steps", r.lineSearchSteps}, {"loo_function_tolerance", num(r.looFunctionTolerance)},
                      {"coordinates", r.coordinates},
                      {"state_step", r.stateStep}, {"law_input", r.lawInput},
                      {"residual", r.residual}, {"segments", r.segmentsUsed}};
}

}  // namespace

nlohmann::json toJson(const IdentifyResult& r) {
    nlohmann::json j;
    j["ok"] = r.ok;
    if (!r.message.empty()) j["message"] = r.message;
    j["setup"] = r.setup;
    j["baseline"] = baselineJson(r);
    if (r.polish.refitted)
        j["final_polish"] = {{"kept", r.polish.kept},
                             {"fit_ss_before", num(r.polish.ssBefore)},
                             {"fit_ss_refit", num(r.polish.ssRefit)},
                             {"held_out_nrmse_before", num(r.polish.heldOutBefore)},
                             {"held_out_nrmse_refit", num(r.polish.heldOutRefit)}};
    j["before"] = toJson(r.before);
    j["after"] = toJson(r.after);
    j["final_parameters"] = toJson(r.final);
    if (r.selfTest.ran) j["self_test"] = toJson(r.selfTest);
    nlohmann::json added = nlohmann::json::array();
    for (const AddedEffect& e : r.effectsAdded) added.push_back(addedJson(e));
    j["effects_added"] = added;
    nlohmann::json cands = nlohmann::json::array();
    for (const CandidateScore& c : r.candidates) cands.push_back(candidateJson(c));
    j["candidates"] = cands;
    j["diagnostics"] = {{"before", toJson(r.diagnosticsBefore, true)}, {"after", toJson(r.diagnosticsAfter, true)}};
    j["unexplained"] = r.unexplained;
    if (r.unexplained) j["unexplained_reason"] = r.unexplainedReason;
    j["structure_note"] = r.structureNote;
    if (r.lawResolution.checked) {
        nlohmann::json runs = nlohmann::json::array();
        for (const LawResolution::Run& x : r.lawResolution.runs)
            runs.push_back({{"file", x.file}, {"change_N", x.change_N}, {"noise_N", x.noise_N}, {"resolved", x.resolved()}});
        j["law_resolution"] = {{"refinement", r.lawResolution.refinement},
                               {"resolved", r.lawResolution.resolved()},
                               {"runs", runs}};
    }
    j["selection"] = selectionJson(r);
    j["wall_time_s"] = r.wallTime_s;
    j["fits"] = r.fits;
    nlohmann::json stages = nlohmann::json::array();
    for (const IdentifyStage& st : r.timeline)
        stages.push_back({{"stage", st.label}, {"start_s", st.start_s}, {"wall_s", st.end_s - st.start_s}, {"fits", st.fits}});
    j["timeline"] = stages;
    return j;
}


std::string baselineTradeOffText(const CandidateScore& c) {
    if (c.tradesOffWithBaseline.empty()) return {};
    const auto it = c.sizeCorrelation.find(c.tradesOffWithBaseline);
    char r[32];
    std::snprintf(r, sizeof r, "%.3f", it != c.sizeCorrelation.end() ? it->second : 0.0);
    return "its size trades off with the baseline's " + c.tradesOffWithBaseline + " (correlation " + r +
           "): the data cannot tell the two apart";
}

std::string lawResolutionText(const LawResolution& r) {
    if (!r.checked || r.resolved()) return {};
    std::string runs;
    for (const LawResolution::Run& x : r.runs) {
        if (x.resolved()) continue;
        char b[160];
        std::snprintf(b, sizeof b, "%s%s %.3g N against %.3g N", runs.empty() ? "" : ", ", x.file.c_str(), x.change_N,
                      x.noise_N);
        runs += b;
    }
    return "the law channel is not resolved at the fits' step: with every law step split in " +
           std::to_string(r.refinement) + " the final model's prediction changes by more than the residual's noise level (" +
           runs + "): the fitted prediction is the step's, not the law's, and part of the residual may be numerical "
           "rather than a missing effect (a contact whose strength falls with slip rate faster than its viscous "
           "term and its stiffness can hold is unstable under its own law and oscillates at a rate the step sets); "
           "run again with more law steps (stickslip-cli identify --substeps N, or --decimate 1) and see whether the "
           "fit and the structure stay";
}

std::string lawStepText(const AddedEffect& e) {
    if (!e.lawStep.checked()) return {};
    char b[160];
    std::snprintf(b, sizeof b,
                  "removes %.1f %% of the fit's sum of squares at the law's step, %.1f %% with every law step split in %d",
                  100.0 * e.lawStep.gain(), 100.0 * e.lawStep.gainRefined(), e.lawStep.refinement);
    return b;
}

std::string verdictOf(const CandidateScore& c) {
    std::string v = c.accepted ? "added" : c.reason;
    if (const std::string t = baselineTradeOffText(c); !t.empty()) v += "; " + t;
    return v;
}

}  // namespace stickslip::identify
