// `stickslip-cli identify`: residual → missing effect → extended model → error before and
// after (issue 6). Same inputs as `fit`; without --validate-on, runs are held out in turn.
#include <cstdio>
#include <iostream>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "cancel.hpp"
#include "cli_common.hpp"
#include "commands.hpp"
#include "core/identify/fit.hpp"
#include "core/identify/identify.hpp"
#include "core/identify/pipeline.hpp"
#include "core/identify/preprocess.hpp"
#include "core/identify/report_html.hpp"
#include "core/io/csv_table.hpp"
#include "core/io/dataset.hpp"

namespace stickslip::cli {

namespace {

using namespace identify;

struct IdentifyCliOptions {
    IdentifyRequest req;
    std::string report, html;
    bool quiet = false;
};

void printSelfTest(const SelfTestResult& st) {
    if (!st.ran) return;
    if (!st.ok) {
        std::cout << "self-test: " << st.message << "\n";
        return;
    }
    std::printf("self-test (%d replicas per row; noise RMS %.4g; n_eff %.0f):\n", st.rows.empty() ? 0 : st.rows.front().replicas,
                st.noiseRms, st.neff);
    std::printf("  %-22s %-26s %11s %6s %8s %9s %9s %7s\n", "effect", "size parameter", "size", "SNR", "visible", "detected",
                "confused", "missed");
    for (const SelfTestRow& w : st.rows)
        std::printf("  %-22s %-26s %11.4g %6.2f %8.2f %4d/%-4d %9d %7d%s%s\n", w.effect.c_str(),
                    (w.sizeParam + " [" + w.unit + "]").c_str(), w.size, w.snr, w.visibleSnr, w.detected, w.replicas, w.confused,
                    w.missed, w.note.empty() ? "" : "  ", w.note.c_str());
    std::set<std::string> shown;  // an effect's stated shape, once
    for (const SelfTestRow& w : st.rows)
        if (shown.insert(w.effect).second)
            for (const auto& [name, v] : w.shape) std::printf("  (%s injected with %s = %.4g)\n", w.effect.c_str(), name.c_str(), v);
    std::printf("  (SNR: RMS of the injected signal / RMS of the baseline residual; visible: of the part the baseline's "
                "refit cannot mimic)\n");
    std::printf("  false alarms on %d replicas without an effect: %d\n", st.falseAlarmReplicas, st.falseAlarms);
}

void runIdentify(const IdentifyCliOptions& o, int& exitCode) {
    auto fail = [&](const std::string& msg, int code) {
        std::cerr << "stickslip-cli identify: " << msg << "\n";
        exitCode = code;
    };
    IdentifyRequest req = o.req;
    if (!o.quiet)
        req.options.progress = [](const std::string& stage, double f) {
            std::cerr << "identify: " << stage << " (" << static_cast<int>(100 * f) << "%)\n";
        };
    req.options.cancel = &cancelFlag();
    IdentifyResult res;
    nlohmann::json j;
    PipelineStatus st;
    if (!runIdentifyRequest(req, res, j, st)) {
        const int code = st.code == PipelineCode::BadArguments ? kBadArguments
                         : st.code == PipelineCode::BadInput   ? kBadInput
                         : st.code == PipelineCode::Cancelled  ? kCancelled
                                                               : kRunFailed;
        return fail(st.message, code);
    }
    if (cancelRequested()) return fail("cancelled; no output written", kCancelled);
    std::string err;
    if (!io::writeFileAtomically(o.report, j.dump(1) + "\n", &err)) return fail(o.report + ": " + err, kBadInput);
    if (!o.html.empty() && !io::writeFileAtomically(o.html, renderHtmlReport(res), &err))
        return fail(o.html + ": " + err, kBadInput);
    std::cout << "effects added:";
    if (res.effectsAdded.empty()) std::cout << " none";
    for (const auto& e : res.effectsAdded) std::cout << " " << e.name;
    std::cout << "\nbefore: fit NRMSE " << res.before.fitNrmse << ", held-out NRMSE " << res.before.validationNrmse
              << "\nafter:  fit NRMSE " << res.after.fitNrmse << ", held-out NRMSE " << res.after.validationNrmse
              << "\nunexplained structure: " << (res.unexplained ? "yes" : "no") << "\nwall time " << res.wallTime_s
              << " s, " << res.fits << " fits\n";
    if (const std::string t = lawResolutionText(res.lawResolution); !t.empty()) std::cout << "warning: " << t << "\n";
    for (const auto& [label, e] : {std::pair{"before", &res.before}, std::pair{"after", &res.after}})
        if (e->unmovedRefits > 0)
            std::cout << "warning: " << label << ": on " << e->unmovedRefits << " run(s) the held-out error is within "
                      << kUnmovedRelative << " of the in-sample one: leaving the run out barely changed the fit (a refit "
                      << "that took no step was done again at tolerances of " << kLooRetryTolerance << ")\n";
    for (const BoundVerdict& b : res.baselineBounds)
        std::cout << "baseline " << b.name << " ended on its " << b.side << " bound " << b.bound << ": "
                  << b.verdict() << " (a second start from " << b.retryStart << " ended at " << b.retryValue
                  << ", BIC lower by " << b.bicGain << (b.refitted ? "; the baseline refitted there" : "")
                  << (b.leftLater() ? "; the baseline adopted later has it at " + std::to_string(b.leftLaterTo) : std::string())
                  << ")\n";
    for (const auto& e : res.effectsAdded)
        if (const std::string t = lawStepText(e); !t.empty()) std::cout << e.name << ": " << t << "\n";
    for (const auto& e : res.effectsAdded)
        for (const std::string& c : e.confoundedWith)
            std::cout << "confounded: " << c << " trades off with " << e.name << " (not added; " << e.name
                      << "'s size may stand for both)\n";
    std::map<std::string, const CandidateScore*> last;  // each candidate's latest round
    for (const CandidateScore& c : res.candidates) last[c.name] = &c;
    for (const auto& [name, c] : last)
        if (!c->tradesOffWithBaseline.empty())
            std::cout << name << ": " << baselineTradeOffText(*c) << "\n";
    printSelfTest(res.selfTest);
    exitCode = kOk;
}

}  // namespace

void addIdentifyCommand(CLI::App& root, int& exitCode) {
    auto o = std::make_shared<IdentifyCliOptions>();
    auto* cmd = root.add_subcommand("identify", "find effects the model lacks: residual -> effect -> refit, errors before/after");
    // A flag with a negation (--on,!--off): CLI11 shows only the negation's "{false}", so the help
    // names the default side itself.
    auto twoWayFlag = [cmd](const std::string& on, const std::string& off, bool& value, const std::string& doc) {
        cmd->add_flag(on + ",!" + off, value, doc)->default_str(value ? on : off);
    };
    addMeasuredInputOptions(cmd, o->req.in, "measured runs (CSV), in recording order",
                            "held-out runs (CSV); without it runs are held out in turn");
    addCleaningOptions(cmd, o->req.cleaning);
    cmd->add_option("--report", o->report, "report (JSON)")->required();
    cmd->add_option("--html", o->html, "self-contained HTML report");
    cmd->add_option("--free", o->req.free, "free baseline law parameters")->capture_default_str();
    cmd->add_option("--candidates", o->req.candidates, "restrict the candidates (catalogue names)")->delimiter(',');
    cmd->add_option("--max-effects", o->req.options.maxEffects, "at most this many effects")->capture_default_str();
    cmd->add_option("--bic-margin", o->req.options.bicMargin, "an effect must lower BIC by more than this")->capture_default_str();
    cmd->add_option("--restart-margin", o->req.options.restartMargin,
                    "a model is refitted from another point (--held-out-restart) only when that point lowers its BIC by more "
                    "than this")->capture_default_str();
    cmd->add_option("--null-alpha", o->req.options.nullAlpha,
                    "an effect's gain must exceed the (1 - this) quantile of what noise replicas of the runs give, in (0, 1)")
        ->capture_default_str();
    cmd->add_option("--null-replicas", o->req.options.nullReplicas, "noise replicas of the null distribution (0: off)")
        ->capture_default_str();
    cmd->add_option("--simulated-null-replicas", o->req.options.simulatedNullReplicas,
                    "dynamics: replicas of the recordings, simulated from the current model (corrected by its fit's own "
                    "bias) with their noise and cleaned and fitted as the data were, whose gains a candidate about to be "
                    "added must exceed (0: off), in [0, 1000]")->capture_default_str();
    cmd->add_option("--simulated-null-bias-steps", o->req.options.simulatedNullBiasSteps,
                    "simulated null: fixed-point steps that move the replicas' model until their fits land where the "
                    "data's fit did (indirect inference), in [0, 20]")->capture_default_str();
    twoWayFlag("--mask-edge-guard", "--no-mask-edge-guard", o->req.options.maskEdgeGuard,
               "dynamics: compare the law channel only on sliding samples farther than the prediction filter's "
               "memory (its DC group delay) from a stuck one, where the filtered prediction is not a blend of model "
               "and measurement (off by default)");
    twoWayFlag("--stick-rig-prediction", "--no-stick-rig-prediction", o->req.options.stickRigPrediction,
               "dynamics: predict the law channel as the model's whole force through the cleaning filters, with the "
               "equation of motion's force where the contact is stuck instead of the cleaned measurement, so the "
               "prediction next to slip onsets and stops is the model's on both sides (off by default)");
    twoWayFlag("--null-numerics", "--no-null-numerics", o->req.options.nullNumerics,
               "the noise replicas also carry the residual's numerical part (the residual minus that of the same model "
               "predicted from every recorded sample, or with 4x the law steps, refitted to the same samples), so an "
               "effect that only absorbs the prediction's discretisation error is not added (default)");
    cmd->add_option("--held-out-alpha", o->req.options.heldOutAlpha,
                    "level of the one-sided paired test over held-out runs an effect must pass, in (0, 1)")->capture_default_str();
    twoWayFlag("--held-out-mid-p", "--held-out-plain-p", o->req.options.heldOutMidP,
               "the exact sign-flip test of the held-out runs uses its mid-p, P(S > s) + P(S = s)/2, the usual correction for "
               "a test with 2^K outcomes, when K >= 5 runs (default); --held-out-plain-p: P(S >= s), which with 5 runs at 5 % demands all 5 better");
    cmd->add_option("--min-held-out-gain", o->req.options.minHeldOutGain,
                    "relevance margin: an effect must also lower the held-out MSE by at least this fraction on average "
                    "over the held-out runs, in [0, 1); 0: significance alone")->capture_default_str();
    cmd->add_option("--identifiability-alpha", o->req.options.identifiabilityAlpha,
                    "level of the size test (effect parameter vs its jackknife s.e.), in (0, 1)")->capture_default_str();
    cmd->add_option("--confounded-vif", o->req.options.confoundedVif,
                    "a candidate whose size trades off with an added effect's (variance inflation 1/(1 - r^2) above this) "
                    "is reported confounded, not added; > 1")->capture_default_str();
    cmd->add_option("--decimate", o->req.options.decimate, "use every n-th sample")->capture_default_str();
    cmd->add_option("--substeps", o->req.options.substeps, "prescribed: law steps per used sample")->capture_default_str();
    cmd->add_option("--multistarts", o->req.options.multistarts, "starting points per fit")->capture_default_str();
    twoWayFlag("--exact-state-step", "--backward-euler-state-step", o->req.options.exactStateStep,
               "the law's state alpha advanced exactly for a slip rate constant over each step (default), or by the "
               "paper's backward Euler, whose relaxation is far off once a step slips more than D_c");
    twoWayFlag("--recorded-step-slip", "--linear-step-slip", o->req.options.recordedStepSlip,
               "decimated prescribed runs: the law's slip between used samples read off the recorded slip (default), or the line "
               "between used samples, which cuts the corners of every stick");
    twoWayFlag("--forward-jacobian", "--central-jacobian", o->req.options.forwardJacobian,
               "the solver's Jacobian by forward differences (default: p residual runs per Jacobian) or by central "
               "differences (2p, slower); standard errors and leave-one-run-out refits use central differences either way");
    cmd->add_option("--line-search-steps", o->req.options.lineSearchSteps,
                    "the fits' projected line search: at most this many step contractions per trust-region step "
                    "(Ceres' default 20; a rejected step spends them all)")->capture_default_str();
    cmd->add_option("--loo-function-tolerance", o->req.options.looFunctionTolerance,
                    "the leave-one-run-out refits' relative cost tolerance; a refit that stops at the full fit is done "
                    "again at 1e-12, and one that meets the edge of the steady-state curve's coordinates is continued "
                    "in C1, eta, v_c (the report counts them: held_out_refits_retried, held_out_law_coordinate_passes, held_out_refits_unmoved)")
        ->capture_default_str();
    cmd->add_flag("--sensitivity-jacobian", o->req.options.analyticJacobian,
                  "the solver's Jacobian while it iterates from forward sensitivities carried through the return map "
                  "(one law run per run instead of one per parameter; not the segment residual); not yet the default");
    twoWayFlag("--curve-coordinates", "--law-coordinates", o->req.options.curveCoordinates,
               "fits warm-started from a fitted model move in the steady-state curve's coordinates C1/vc^2 and "
               "eta - C1/vc (default, both set-ups, as fit --setup dynamics does) or in C1, eta themselves");
    twoWayFlag("--held-out-restart", "--no-held-out-restart", o->req.options.heldOutRestart,
               "refit the baseline, and a candidate before it is judged, from a leave-one-run-out refit's point, "
               "and the current model from a round's candidate's point with its effect removed, when that point fits "
               "all runs better than the fit by more than --restart-margin in BIC (the fit stopped in a worse minimum); "
               "on by default");
    cmd->add_option("--dynamics-residual", o->req.dynamicsResidual,
                    "dynamics set-up: equation-error (default: the law run along the measured slip, every effect applicable, "
                    "+ the rig's equation of motion), auto (contact effects scored on re-initialised simulated segments; "
                    "experimental) or segments")->capture_default_str();
    cmd->add_option("--max-segments", o->req.options.maxSegmentsPerRun, "segment residual: at most this many segments per run")
        ->capture_default_str();
    cmd->add_option("--seed", o->req.options.seed, "random seed (the loop is reproducible)")->capture_default_str();
    cmd->add_option("--epsT", o->req.options.start.epsT_N_per_m, "tangential penalty stiffness: start value, or the value held when not in --free [N/m]")->capture_default_str();
    cmd->add_option("--Dc", o->req.options.start.Dc_m, "critical slip distance: start value, or the value held when not in --free [m]")->capture_default_str();
    cmd->add_flag("--self-test", o->req.selfTest,
                  "recovery self-test: inject each candidate effect into replicas of these runs (fitted baseline + "
                  "effect + noise of the baseline residual) and report how often the selection detects it, confuses it "
                  "or raises a false alarm (report: self_test)");
    cmd->add_option("--self-test-replicas", o->req.selfTestReplicas, "self-test: replicas per effect and level, in [1, 10000]")
        ->capture_default_str();
    cmd->add_option("--self-test-levels", o->req.selfTestLevels,
                    "self-test: injected signal RMS over the baseline residual RMS, one row per level, in (0, 100]")
        ->delimiter(',')->capture_default_str();
    cmd->add_option("--self-test-size", o->req.selfTestSizes,
                    "self-test: EFFECT=VALUE, the stated size of an effect's size parameter (SI units), instead of the levels; "
                    "EFFECT.PARAMETER=VALUE sets another of its parameters in the injection (default: its start), "
                    "e.g. stick_healing=0.01 stick_healing.tc_s=0.002")
        ->expected(1, -1);
    cmd->add_flag("--quiet", o->quiet, "no progress on stderr");
    cmd->callback([o, &exitCode] { runIdentify(*o, exitCode); });
}

}  // namespace stickslip::cli
