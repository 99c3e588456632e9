// `stickslip-cli identify`: residual → missing effect → extended model → error before and
// after (issue 6). Same inputs as `fit`; without --validate-on, runs are held out in turn.
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "cancel.hpp"
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
    exitCode = kOk;
}

}  // namespace

void addIdentifyCommand(CLI::App& root, int& exitCode) {
    auto o = std::make_shared<IdentifyCliOptions>();
    auto* cmd = root.add_subcommand("identify", "find effects the model lacks: residual -> effect -> refit, errors before/after");
    cmd->add_option("--data", o->req.in.data, "measured runs (CSV), in recording order")->required()->expected(1, -1);
    cmd->add_option("--setup", o->req.in.setup, "prescribed or dynamics; default from the columns");
    cmd->add_option("--columns", o->req.in.columns, "SIGNAL=COLUMN mappings, e.g. friction=Fx");
    cmd->add_option("--units", o->req.in.units, "SIGNAL=UNIT, e.g. stage_disp=mm");
    cmd->add_option("--manifest", o->req.in.manifest, "dataset manifest JSON (per run k, A, f, tN; nominal mass)");
    cmd->add_option("--run-set", o->req.in.runSets, "FILE:KEY=VALUE known setting of one run");
    cmd->add_option("--validate-on", o->req.in.validateOn, "held-out runs (CSV); without it runs are held out in turn")->expected(1, -1);
    cmd->add_option("--report", o->report, "report (JSON)")->required();
    cmd->add_option("--html", o->html, "self-contained HTML report");
    cmd->add_option("--free", o->req.free, "free baseline law parameters")->capture_default_str();
    cmd->add_option("--candidates", o->req.candidates, "restrict the candidates (catalogue names)")->delimiter(',');
    cmd->add_option("--max-effects", o->req.options.maxEffects, "at most this many effects")->capture_default_str();
    cmd->add_option("--bic-margin", o->req.options.bicMargin, "an effect must lower BIC by more than this")->capture_default_str();
    cmd->add_option("--null-alpha", o->req.options.nullAlpha,
                    "an effect's gain must exceed the (1 - this) quantile of what noise replicas of the runs give, in (0, 1)")
        ->capture_default_str();
    cmd->add_option("--null-replicas", o->req.options.nullReplicas, "noise replicas of the null distribution (0: off)")
        ->capture_default_str();
    cmd->add_option("--held-out-alpha", o->req.options.heldOutAlpha,
                    "level of the one-sided paired test over held-out runs an effect must pass, in (0, 1)")->capture_default_str();
    cmd->add_option("--identifiability-alpha", o->req.options.identifiabilityAlpha,
                    "level of the size test (effect parameter vs its jackknife s.e.), in (0, 1)")->capture_default_str();
    cmd->add_option("--decimate", o->req.options.decimate, "use every n-th sample")->capture_default_str();
    cmd->add_option("--substeps", o->req.options.substeps, "prescribed: law steps per used sample")->capture_default_str();
    cmd->add_option("--multistarts", o->req.options.multistarts, "starting points per fit")->capture_default_str();
    cmd->add_option("--dynamics-residual", o->req.dynamicsResidual,
                    "dynamics set-up: equation-error (default: the law run along the measured slip, every effect applicable, "
                    "+ the rig's equation of motion), auto (contact effects scored on re-initialised simulated segments; "
                    "experimental) or segments")->capture_default_str();
    cmd->add_option("--max-segments", o->req.options.maxSegmentsPerRun, "segment residual: at most this many segments per run")
        ->capture_default_str();
    cmd->add_option("--seed", o->req.options.seed, "random seed (the loop is reproducible)")->capture_default_str();
    cmd->add_option("--epsT", o->req.options.start.epsT_N_per_m, "tangential penalty stiffness: start value, or the value held when not in --free [N/m]")->capture_default_str();
    cmd->add_option("--Dc", o->req.options.start.Dc_m, "critical slip distance: start value, or the value held when not in --free [m]")->capture_default_str();
    cmd->add_flag("--no-bandstop", o->req.cleaning.noBandStop, "switch the mains band-stop off");
    cmd->add_flag("--no-lowpass", o->req.cleaning.noLowPass, "switch the low-pass off");
    cmd->add_flag("--no-steady-trim", o->req.cleaning.noSteadyTrim, "keep ramps");
    cmd->add_flag("--quiet", o->quiet, "no progress on stderr");
    cmd->callback([o, &exitCode] { runIdentify(*o, exitCode); });
}

}  // namespace stickslip::cli
