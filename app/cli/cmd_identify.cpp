// `stickslip-cli identify`: residual → missing effect → extended model → error before and
// after (issue 6). Same inputs as `fit`; without --validate-on, runs are held out in turn.
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "commands.hpp"
#include "measured_data.hpp"
#include "core/identify/fit.hpp"
#include "core/identify/identify.hpp"
#include "core/identify/preprocess.hpp"
#include "core/identify/report_html.hpp"
#include "core/io/csv_table.hpp"
#include "core/io/dataset.hpp"

namespace stickslip::cli {

namespace {

struct IdentifyCliOptions {
    std::vector<std::string> data, validateOn, columns, units, runSets, candidates;
    std::string setup, manifest, report, html, free = "mu,C1,eta,Dc,vc,epsT", dynamicsResidual = "equation-error";
    identify::PreprocessSettings pre;
    bool noBandStop = false, noLowPass = false, noSteadyTrim = false, quiet = false;
    identify::IdentifyOptions id;
};

std::vector<std::string> splitComma(const std::string& s) {
    std::vector<std::string> out;
    std::string cur;
    for (char c : s + ",") {
        if (c == ',') { if (!cur.empty()) out.push_back(cur); cur.clear(); }
        else if (c != ' ') cur += c;
    }
    return out;
}

void runIdentify(const IdentifyCliOptions& o, int& exitCode) {
    using namespace identify;
    using io::Signal;
    auto fail = [&](const std::string& msg, int code) {
        std::cerr << "stickslip-cli identify: " << msg << "\n";
        exitCode = code;
    };
    IdentifyOptions idOpt = o.id;
    if (o.dynamicsResidual == "auto") idOpt.dynamicsResidual = DynamicsResidual::Auto;
    else if (o.dynamicsResidual == "equation-error") idOpt.dynamicsResidual = DynamicsResidual::EquationError;
    else if (o.dynamicsResidual == "segments") idOpt.dynamicsResidual = DynamicsResidual::Segments;
    else {
        fail("--dynamics-residual: '" + o.dynamicsResidual + "' is not one of auto, equation-error, segments", kBadArguments);
        return;
    }
    io::Dataset fitData, valData;
    SetupKind setup = SetupKind::Prescribed;
    if (!loadMeasuredData("identify", o, fitData, valData, setup, exitCode)) return;
    PreprocessSettings pre = o.pre;
    if (o.noBandStop) pre.filters.bandStop = false;
    if (o.noLowPass) pre.filters.lowPass = false;
    if (o.noSteadyTrim) pre.trim.steadyAmplitude = false;
    std::vector<IdentifyRun> runs;
    auto add = [&](const io::Dataset& ds, bool validation) {
        for (const io::Run& r : ds.runs) {
            CleanRun c;
            std::string e;
            if (!preprocessRun(r, pre, c, &e)) { fail(e, kBadArguments); return false; }
            double tN = 0;
            if (!c.run.setting("tN", tN)) {
                fail(r.file + ": t_N unknown: give a normal_force_N or band_tension_N column, a manifest, or --run-set " +
                         r.name() + ":tN=VALUE",
                     kBadArguments);
                return false;
            }
            IdentifyRun ir;
            if (!makeIdentifyRun(c, setup, ir, &e)) { fail(e, kBadInput); return false; }
            ir.validation = validation;
            runs.push_back(std::move(ir));
        }
        return true;
    };
    if (!add(fitData, false) || !add(valData, true)) return;

    IdentifyOptions opt = idOpt;
    opt.freeLaw = splitComma(o.free);
    for (const std::string& n : opt.freeLaw) {
        FitParameter fp;
        if (!defaultParameter(n, setup, fp) || n == "m" || n == "k" || n == "c" || n == "tN")
            return fail("--free " + n + ": not a law parameter (mu, C1, eta, Dc, vc, epsT, r)", kBadArguments);
    }
    opt.candidates = o.candidates;
    for (const std::string& c : opt.candidates) {
        EffectInfo info;
        if (!findEffect(c, info)) return fail("--candidates " + c + ": not in the catalogue", kBadArguments);
    }
    if (!o.quiet)
        opt.progress = [](const std::string& stage, double f) {
            std::cerr << "identify: " << stage << " (" << static_cast<int>(100 * f) << "%)\n";
        };
    const IdentifyResult res = identifyEffects(std::move(runs), opt);
    if (!res.ok) return fail(res.message, res.cancelled ? kCancelled : kRunFailed);
    nlohmann::json j = toJson(res);
    j["preprocessing"] = toJson(pre);
    j["inputs"] = {{"data", o.data}, {"validate_on", o.validateOn}, {"manifest", o.manifest}};
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
    cmd->add_option("--data", o->data, "measured runs (CSV), in recording order")->required()->expected(1, -1);
    cmd->add_option("--setup", o->setup, "prescribed or dynamics; default from the columns");
    cmd->add_option("--columns", o->columns, "SIGNAL=COLUMN mappings, e.g. friction=Fx");
    cmd->add_option("--units", o->units, "SIGNAL=UNIT, e.g. stage_disp=mm");
    cmd->add_option("--manifest", o->manifest, "dataset manifest JSON (per run k, A, f, tN; nominal mass)");
    cmd->add_option("--run-set", o->runSets, "FILE:KEY=VALUE known setting of one run");
    cmd->add_option("--validate-on", o->validateOn, "held-out runs (CSV); without it runs are held out in turn")->expected(1, -1);
    cmd->add_option("--report", o->report, "report (JSON)")->required();
    cmd->add_option("--html", o->html, "self-contained HTML report");
    cmd->add_option("--free", o->free, "free baseline law parameters")->capture_default_str();
    cmd->add_option("--candidates", o->candidates, "restrict the candidates (catalogue names)")->delimiter(',');
    cmd->add_option("--max-effects", o->id.maxEffects, "at most this many effects")->capture_default_str();
    cmd->add_option("--bic-margin", o->id.bicMargin, "an effect must lower BIC by more than this")->capture_default_str();
    cmd->add_option("--null-alpha", o->id.nullAlpha,
                    "an effect's gain must exceed the (1 - this) quantile of what noise replicas of the runs give, in (0, 1)")
        ->capture_default_str();
    cmd->add_option("--null-replicas", o->id.nullReplicas, "noise replicas of the null distribution (0: off)")
        ->capture_default_str();
    cmd->add_option("--held-out-alpha", o->id.heldOutAlpha,
                    "level of the one-sided paired test over held-out runs an effect must pass, in (0, 1)")->capture_default_str();
    cmd->add_option("--identifiability-alpha", o->id.identifiabilityAlpha,
                    "level of the size test (effect parameter vs its jackknife s.e.), in (0, 1)")->capture_default_str();
    cmd->add_option("--decimate", o->id.decimate, "use every n-th sample")->capture_default_str();
    cmd->add_option("--substeps", o->id.substeps, "prescribed: law steps per used sample")->capture_default_str();
    cmd->add_option("--multistarts", o->id.multistarts, "starting points per fit")->capture_default_str();
    cmd->add_option("--dynamics-residual", o->dynamicsResidual,
                    "dynamics set-up: equation-error (default: the law run along the measured slip, every effect applicable, "
                    "+ the rig's equation of motion), auto (contact effects scored on re-initialised simulated segments; "
                    "experimental) or segments")->capture_default_str();
    cmd->add_option("--max-segments", o->id.maxSegmentsPerRun, "segment residual: at most this many segments per run")
        ->capture_default_str();
    cmd->add_option("--seed", o->id.seed, "random seed (the loop is reproducible)")->capture_default_str();
    cmd->add_option("--epsT", o->id.start.epsT_N_per_m, "tangential penalty stiffness: start value, or the value held when not in --free [N/m]")->capture_default_str();
    cmd->add_option("--Dc", o->id.start.Dc_m, "critical slip distance: start value, or the value held when not in --free [m]")->capture_default_str();
    cmd->add_flag("--no-bandstop", o->noBandStop, "switch the mains band-stop off");
    cmd->add_flag("--no-lowpass", o->noLowPass, "switch the low-pass off");
    cmd->add_flag("--no-steady-trim", o->noSteadyTrim, "keep ramps");
    cmd->add_flag("--quiet", o->quiet, "no progress on stderr");
    cmd->callback([o, &exitCode] { runIdentify(*o, exitCode); });
}

}  // namespace stickslip::cli
