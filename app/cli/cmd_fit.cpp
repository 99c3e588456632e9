// `stickslip-cli fit`: read measured runs, clean them as the paper did, fit the rate-state
// and/or Coulomb law with Ceres, and write a JSON report (and optionally the residuals).
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>

#include "cancel.hpp"
#include "cli_common.hpp"
#include "commands.hpp"
#include "core/identify/fit.hpp"
#include "core/identify/fit_report.hpp"
#include "core/identify/pipeline.hpp"
#include "core/identify/preprocess.hpp"
#include "core/io/csv_table.hpp"
#include "core/io/dataset.hpp"
#include "core/io/units.hpp"

namespace stickslip::cli {

namespace {

using namespace stickslip::identify;
using io::Signal;

struct FitOptions {
    FitRequest req;
    std::string report, residuals;
};

int exitFor(PipelineCode c) {
    switch (c) {
        case PipelineCode::Ok: return kOk;
        case PipelineCode::BadArguments: return kBadArguments;
        case PipelineCode::BadInput: return kBadInput;
        case PipelineCode::Cancelled: return kCancelled;
        case PipelineCode::RunFailed: break;
    }
    return kRunFailed;
}

// Residuals of the first law's fit (measured - predicted), fit runs then validation runs.
std::string residualsCsv(const FitOutcome& r) {
    std::ostringstream csv;
    const bool dyn = r.setup == SetupKind::Dynamics;
    csv << "# residuals of the " << toString(r.fits.front().model.law) << " fit (measured - predicted)\n";
    csv << "run,role,time_s,measured_force_N,predicted_force_N,residual_force_N";
    if (dyn) csv << ",measured_disp_m,predicted_disp_m,residual_disp_m";
    csv << "\n";
    csv.precision(9);
    auto dump = [&](const std::vector<CleanRun>& runs, const char* role) {
        for (const CleanRun& c : runs) {
            Prediction p;
            scoreRun(c, r.setup, r.fits.front().model, r.settings.predict, role, &p);
            for (size_t k = 0; p.ok && k < p.index.size(); ++k) {
                const size_t i = p.index[k];
                const double F = c.run[Signal::Friction][i];
                csv << c.run.name() << ',' << role << ',' << c.run[Signal::Time][i] << ',' << F << ',' << p.force_N[k] << ',' << F - p.force_N[k];
                if (dyn) {
                    const double x = c.run[Signal::SliderDisp][i];
                    csv << ',' << x << ',' << p.slider_m[k] << ',' << x - p.slider_m[k];
                }
                csv << "\n";
            }
        }
    };
    dump(r.fitRuns, "fit");
    dump(r.validationRuns, "validation");
    return csv.str();
}

void runFit(const FitOptions& o, int& exitCode) {
    auto fail = [&](const std::string& msg, int code) {
        std::cerr << "stickslip-cli fit: " << msg << "\n";
        exitCode = code;
    };
    FitRequest req = o.req;
    req.log = [](const std::string& line) { std::cerr << line << "\n"; };
    req.cancel = &cancelFlag();
    FitOutcome out;
    PipelineStatus st;
    if (!runFitRequest(req, out, st)) return fail(st.message, exitFor(st.code));
    if (cancelRequested()) return fail("cancelled; no output written", kCancelled);
    std::string err;
    if (!io::writeFileAtomically(o.report, out.report.dump(1) + "\n", &err)) return fail(err, kBadInput);
    if (!o.residuals.empty() && !io::writeFileAtomically(o.residuals, residualsCsv(out), &err)) return fail(err, kBadInput);
    exitCode = kOk;
}

}  // namespace

void addFitCommand(CLI::App& root, int& exitCode) {
    auto o = std::make_shared<FitOptions>();
    auto* cmd = root.add_subcommand("fit", "Fit the friction law to measured runs (import, preprocessing, Ceres least squares)");
    addMeasuredInputOptions(cmd, o->req.in, "measured runs (CSV), fitted jointly",
                            "held-out runs (CSV) scored with the fitted model");
    addCleaningOptions(cmd, o->req.cleaning);
    cmd->add_option("--model", o->req.model, "a law (rate-state, coulomb, dieterich-ruina, …) or both (rate-state and Coulomb)")->capture_default_str();
    cmd->add_option("--free", o->req.free,
                    "free parameters (a law's keys it lacks are dropped): " + fitParamKeys() +
                        " zeta; e.g. mu,a,b,Dc,epsT for --model dieterich-ruina")->capture_default_str();
    cmd->add_option("--set", o->req.sets, "KEY=VALUE starting (or, if not free, fixed) model value, e.g. C1=0.25");
    cmd->add_option("--split-time", o->req.splitTime, "hold out the last (1-F) of every fit window for validation (0 = off)");
    cmd->add_option("--report", o->report, "fit report (JSON)")->required();
    cmd->add_option("--residuals", o->residuals, "residuals (CSV)");
    cmd->add_flag("--no-filter-prediction", o->req.noFilterPrediction, "compare the raw prediction with the cleaned measurement (default: pass the prediction through the same filter)");
    cmd->add_option("--stride", o->req.predict.stride, "prescribed: decimation of the measured samples")->capture_default_str();
    cmd->add_option("--substeps", o->req.predict.substeps, "prescribed: law steps per decimated sample")->capture_default_str();
    cmd->add_option("--segment", o->req.predict.segment_s, "dynamics: shooting segment length [s]")->capture_default_str();
    cmd->add_option("--segment-spacing", o->req.predict.segmentSpacing_s, "dynamics: segment start spacing [s]")->capture_default_str();
    cmd->add_option("--dt", o->req.predict.dt_s, "dynamics: integration step [s]")->capture_default_str();
    cmd->add_option("--slip-start", o->req.predict.slipStartFraction,
                    "dynamics: start each segment where |V| >= this fraction of the run's peak slip rate (0 = nominal times)")
        ->capture_default_str();
    cmd->add_option("--initial-state", o->req.initialState,
                    "dynamics: segment initial x, x' as measured, or fitted per segment (nuisance parameters, profiled out)")
        ->check(CLI::IsMember({"measured", "fitted"}))
        ->capture_default_str();
    cmd->add_option("--multistarts", o->req.multistarts, "starting points, at most (first = defaults/data estimate)")->capture_default_str();
    cmd->add_option("--agreeing-starts", o->req.agreeingStarts,
                    "stop the multistart once this many starts ended at the same best cost (0 = run every start)")
        ->capture_default_str();
    cmd->add_option("--max-iterations", o->req.maxIterations, "solver iterations per start")->capture_default_str();
    cmd->add_flag("--jackknife", o->req.jackknife,
                  "repeat the whole fit leaving each run out (>= 3 fit runs, K more fits); stderr = the larger of Jacobian and jackknife");
    cmd->add_option("--coordinates", o->req.coordinates,
                    "dynamics, rate-state with C1, eta, vc free: solve in the steady-state curve's slope eta-C1/vc and curvature C1/vc^2 "
                    "with vc (curve), or in C1, eta, vc (plain); reported in C1, eta, vc either way")
        ->check(CLI::IsMember({"curve", "plain"}))
        ->capture_default_str();
    cmd->add_option("--fd-step", o->req.relativeStep, "central-difference step, relative to the internal parameter")->capture_default_str();
    cmd->add_option("--robust", o->req.robust, "robust loss: none, huber or cauchy")->capture_default_str();
    cmd->add_option("--robust-scale", o->req.robustScale, "robust loss scale (normalised residual units)")->capture_default_str();
    cmd->add_option("--seed", o->req.seed, "seed of the random starts")->capture_default_str();
    cmd->callback([o, &exitCode] { runFit(*o, exitCode); });
}

}  // namespace stickslip::cli
