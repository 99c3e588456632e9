// `stickslip-cli fit`: read measured runs, clean them as the paper did, fit the rate-state
// and/or Coulomb law with Ceres, and write a JSON report (and optionally the residuals).
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>

#include "commands.hpp"
#include "measured_data.hpp"
#include "core/identify/fit.hpp"
#include "core/identify/fit_report.hpp"
#include "core/identify/preprocess.hpp"
#include "core/io/csv_table.hpp"
#include "core/io/dataset.hpp"
#include "core/io/units.hpp"

namespace stickslip::cli {

namespace {

using namespace stickslip::identify;
using io::Signal;

struct FitOptions {
    std::vector<std::string> data, validateOn, columns, units, runSets, sets;
    std::string setup, model = "rate-state", free = "mu,eta,Dc,vc,epsT", manifest, report, residuals;
    double splitTime = 0.0;
    PreprocessSettings pre;
    bool noBandStop = false, noLowPass = false, noSteadyTrim = false, noFilterPrediction = false;
    PredictSettings predict;
    int multistarts = 3, maxIterations = 40, agreeingStarts = 2;
    std::string initialState = "fitted";
    double relativeStep = 1e-4;
    bool jackknife = false;
    std::string coordinates = "curve";
    std::string robust = "none";
    double robustScale = 1.0;
    uint64_t seed = 20260101;
};

std::vector<std::string> splitComma(const std::string& s) {
    std::vector<std::string> out;
    std::stringstream in(s);
    std::string item;
    while (std::getline(in, item, ','))
        if (!item.empty()) out.push_back(item);
    return out;
}

void runFit(const FitOptions& o, int& exitCode) {
    auto fail = [&](const std::string& msg, int code) {
        std::cerr << "stickslip-cli fit: " << msg << "\n";
        exitCode = code;
    };
    io::Dataset fitData, valData;
    SetupKind setup = SetupKind::Prescribed;
    if (!loadMeasuredData("fit", o, fitData, valData, setup, exitCode)) return;
    PreprocessSettings pre = o.pre;
    if (o.noBandStop) pre.filters.bandStop = false;
    if (o.noLowPass) pre.filters.lowPass = false;
    if (o.noSteadyTrim) pre.trim.steadyAmplitude = false;
    std::vector<CleanRun> fitRuns, valRuns;
    nlohmann::json preJson = toJson(pre);
    nlohmann::json perRun = nlohmann::json::array();
    auto clean = [&](const io::Dataset& ds, std::vector<CleanRun>& out) {
        for (const io::Run& r : ds.runs) {
            CleanRun c;
            std::string e;
            if (!preprocessRun(r, pre, c, &e)) { fail(e, kBadArguments); return false; }
            double tN = 0;
            if (!c.run.setting("tN", tN))
                { fail(r.file + ": t_N unknown: give a normal_force_N or band_tension_N column, a manifest, or --run-set " + r.name() + ":tN=VALUE", kBadArguments); return false; }
            nlohmann::json settings = nlohmann::json::object();
            for (const auto& [k, v] : c.run.settings) settings[k] = {{"value", v}, {"source", c.run.settingSource[k]}};
            perRun.push_back({{"file", r.file}, {"sample_rate_Hz", 1.0 / c.dt_s}, {"fit_window_s", {c.run[Signal::Time][c.begin], c.run[Signal::Time][c.end - 1]}},
                              {"period_s", c.period_s}, {"resampled", c.resampled}, {"notes", c.notes}, {"settings", settings}});
            out.push_back(std::move(c));
        }
        return true;
    };
    if (!clean(fitData, fitRuns) || !clean(valData, valRuns)) return;
    if (o.splitTime > 0.0) {
        const std::string e = holdOutLaterParts(fitRuns, valRuns, o.splitTime);
        if (!e.empty()) return fail("--split-time: " + e, kBadArguments);
    }
    preJson["runs"] = perRun;

    DatasetFitSettings st;
    st.setup = setup;
    st.free = splitComma(o.free);
    st.predict = o.predict;
    if (o.noFilterPrediction) st.predict.filterPrediction = false;
    st.predict.fitInitialState = o.initialState == "fitted";
    st.multistarts = o.multistarts;
    st.agreeingStarts = o.agreeingStarts;
    st.relativeStep = o.relativeStep;
    st.jackknife = o.jackknife;
    st.curveCoordinates = o.coordinates == "curve";
    st.maxIterations = o.maxIterations;
    st.seed = o.seed;
    st.lossScale = o.robustScale;
    if (o.robust == "huber") st.loss = LossKind::Huber;
    else if (o.robust == "cauchy") st.loss = LossKind::Cauchy;
    else if (o.robust != "none") return fail("--robust " + o.robust + ": must be none, huber or cauchy", kBadArguments);
    for (const std::string& kv : o.sets) {
        const auto eq = kv.find('=');
        double v = 0;
        std::string e;
        if (eq == std::string::npos) return fail("--set " + kv + ": expected KEY=VALUE", kBadArguments);
        const std::string key = kv.substr(0, eq);
        if (key == "zeta") {
            char* end = nullptr;
            const std::string txt = kv.substr(eq + 1);
            v = std::strtod(txt.c_str(), &end);
            if (end == txt.c_str() || *end != '\0' || !(v >= 0.0)) return fail("--set " + kv + ": zeta must be a number >= 0", kBadArguments);
        } else if (!io::parseParamValue(key, kv.substr(eq + 1), v, &e)) return fail("--set " + kv + ": " + e, kBadArguments);
        st.start[key] = v;
    }
    for (const std::string& n : st.free) {
        FitParameter fp;
        if (n != "zeta" && !defaultParameter(n, setup, fp))
            return fail("--free " + n + ": unknown parameter (known: mu C1 eta Dc vc epsT r m zeta)", kBadArguments);
    }
    std::vector<LawKind> laws;
    if (o.model == "rate-state") laws = {LawKind::RateState};
    else if (o.model == "coulomb") laws = {LawKind::Coulomb};
    else if (o.model == "both") laws = {LawKind::RateState, LawKind::Coulomb};
    else return fail("--model " + o.model + ": must be rate-state, coulomb or both", kBadArguments);

    std::vector<DatasetFit> fits;
    for (LawKind law : laws) {
        st.law = law;
        std::cerr << "fitting " << toString(law) << " (" << toString(setup) << ", " << fitRuns.size() << " fit runs, "
                  << valRuns.size() << " validation runs)...\n";
        DatasetFit f = fitDataset(fitRuns, valRuns, st);
        if (!f.ok) return fail(std::string(toString(law)) + ": " + f.message, kRunFailed);
        std::cerr << "  " << toString(law) << ": fit NRMSE " << f.fitNrmse << ", validation NRMSE " << f.validationNrmse
                  << ", " << f.fit.identifiabilityMessage << "\n";
        if (!f.stderrWarning.empty()) std::cerr << "  warning: " << f.stderrWarning << "\n";
        fits.push_back(std::move(f));
    }
    std::vector<const DatasetFit*> fitted;
    for (const DatasetFit& f : fits) fitted.push_back(&f);
    nlohmann::json rep = fitReportJson(fitted);
    rep["preprocessing"] = preJson;
    rep["prediction"] = toJson(st.predict);
    rep["t_N_convention"] = setup == SetupKind::Prescribed
        ? "t_N of each run is its known load (normal force column, else the band tension column, else manifest/--run-set); "
          "mu, C1 and eta are per unit of that load, so for a band brake mu absorbs the band's force amplification"
        : "t_N of each run from the normal force column (mean), else the manifest";
    rep["validation"] = !o.validateOn.empty() ? "by run (--validate-on)" : (o.splitTime > 0 ? "by time (--split-time)" : "none");
    std::string err;
    if (!io::writeFileAtomically(o.report, rep.dump(1) + "\n", &err)) return fail(err, kBadInput);
    if (!o.residuals.empty()) {
        std::ostringstream csv;
        const bool dyn = setup == SetupKind::Dynamics;
        csv << "# residuals of the " << toString(laws.front()) << " fit (measured - predicted)\n";
        csv << "run,role,time_s,measured_force_N,predicted_force_N,residual_force_N";
        if (dyn) csv << ",measured_disp_m,predicted_disp_m,residual_disp_m";
        csv << "\n";
        csv.precision(9);
        auto dump = [&](const std::vector<CleanRun>& runs, const char* role) {
            for (const CleanRun& c : runs) {
                Prediction p;
                scoreRun(c, setup, fits.front().model, st.predict, role, &p);
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
        dump(fitRuns, "fit");
        dump(valRuns, "validation");
        if (!io::writeFileAtomically(o.residuals, csv.str(), &err)) return fail(err, kBadInput);
    }
    exitCode = kOk;
}

}  // namespace

void addFitCommand(CLI::App& root, int& exitCode) {
    auto o = std::make_shared<FitOptions>();
    auto* cmd = root.add_subcommand("fit", "Fit the friction law to measured runs (import, preprocessing, Ceres least squares)");
    cmd->add_option("--data", o->data, "measured runs (CSV), fitted jointly")->required()->expected(1, -1);
    cmd->add_option("--setup", o->setup, "prescribed (slip in, force out) or dynamics (stage in, slider and force out); default from the columns");
    cmd->add_option("--model", o->model, "rate-state, coulomb or both")->capture_default_str();
    cmd->add_option("--free", o->free, "free parameters: mu,C1,eta,Dc,vc,epsT,r,m,zeta")->capture_default_str();
    cmd->add_option("--columns", o->columns, "SIGNAL=COLUMN mappings, e.g. friction=Fx (signals: time stage_disp slider_disp slip rel_vel stage_vel slider_vel friction normal tension slider_accel)");
    cmd->add_option("--units", o->units, "SIGNAL=UNIT, e.g. stage_disp=mm");
    cmd->add_option("--manifest", o->manifest, "dataset manifest JSON (per run k, A, f, tN; nominal mass)");
    cmd->add_option("--run-set", o->runSets, "FILE:KEY=VALUE known setting of one run, e.g. run_01.csv:tN=6.2N");
    cmd->add_option("--set", o->sets, "KEY=VALUE starting (or, if not free, fixed) model value, e.g. C1=0.25");
    cmd->add_option("--validate-on", o->validateOn, "held-out runs (CSV) scored with the fitted model")->expected(1, -1);
    cmd->add_option("--split-time", o->splitTime, "hold out the last (1-F) of every fit window for validation (0 = off)");
    cmd->add_option("--report", o->report, "fit report (JSON)")->required();
    cmd->add_option("--residuals", o->residuals, "residuals (CSV)");
    cmd->add_flag("--no-bandstop", o->noBandStop, "switch the mains band-stop off");
    cmd->add_option("--bandstop-hz", o->pre.filters.bandStopCenter_Hz, "band-stop centre [Hz]")->capture_default_str();
    cmd->add_option("--bandstop-width", o->pre.filters.bandStopWidth_Hz, "band-stop width [Hz]")->capture_default_str();
    cmd->add_option("--bandstop-order", o->pre.filters.bandStopOrder, "band-stop prototype order")->capture_default_str();
    cmd->add_flag("--no-lowpass", o->noLowPass, "switch the low-pass off");
    cmd->add_option("--lowpass-hz", o->pre.filters.lowPass_Hz, "low-pass cut-off [Hz]")->capture_default_str();
    cmd->add_option("--lowpass-order", o->pre.filters.lowPassOrder, "low-pass order")->capture_default_str();
    cmd->add_option("--trim-start", o->pre.trim.start_s, "drop this many seconds at the start [s]");
    cmd->add_option("--trim-end", o->pre.trim.end_s, "drop this many seconds at the end [s]");
    cmd->add_option("--stage-harmonics", o->pre.stageFourierOrder, "dynamics: stage input = Fourier fit with this many harmonics (0 = measured)")->capture_default_str();
    cmd->add_flag("--no-filter-prediction", o->noFilterPrediction, "compare the raw prediction with the cleaned measurement (default: pass the prediction through the same filter)");
    cmd->add_flag("--no-steady-trim", o->noSteadyTrim, "keep ramps (do not trim to the steady drive amplitude)");
    cmd->add_option("--stride", o->predict.stride, "prescribed: decimation of the measured samples")->capture_default_str();
    cmd->add_option("--substeps", o->predict.substeps, "prescribed: law steps per decimated sample")->capture_default_str();
    cmd->add_option("--segment", o->predict.segment_s, "dynamics: shooting segment length [s]")->capture_default_str();
    cmd->add_option("--segment-spacing", o->predict.segmentSpacing_s, "dynamics: segment start spacing [s]")->capture_default_str();
    cmd->add_option("--dt", o->predict.dt_s, "dynamics: integration step [s]")->capture_default_str();
    cmd->add_option("--slip-start", o->predict.slipStartFraction,
                    "dynamics: start each segment where |V| >= this fraction of the run's peak slip rate (0 = nominal times)")
        ->capture_default_str();
    cmd->add_option("--initial-state", o->initialState,
                    "dynamics: segment initial x, x' as measured, or fitted per segment (nuisance parameters, profiled out)")
        ->check(CLI::IsMember({"measured", "fitted"}))
        ->capture_default_str();
    cmd->add_option("--multistarts", o->multistarts, "starting points, at most (first = defaults/data estimate)")->capture_default_str();
    cmd->add_option("--agreeing-starts", o->agreeingStarts,
                    "stop the multistart once this many starts ended at the same best cost (0 = run every start)")
        ->capture_default_str();
    cmd->add_option("--max-iterations", o->maxIterations, "solver iterations per start")->capture_default_str();
    cmd->add_flag("--jackknife", o->jackknife,
                  "repeat the whole fit leaving each run out (>= 3 fit runs, K more fits); stderr = the larger of Jacobian and jackknife");
    cmd->add_option("--coordinates", o->coordinates,
                    "dynamics, rate-state with C1, eta, vc free: solve in the steady-state curve's slope eta-C1/vc and curvature C1/vc^2 "
                    "with vc (curve), or in C1, eta, vc (plain); reported in C1, eta, vc either way")
        ->check(CLI::IsMember({"curve", "plain"}))
        ->capture_default_str();
    cmd->add_option("--fd-step", o->relativeStep, "central-difference step, relative to the internal parameter")->capture_default_str();
    cmd->add_option("--robust", o->robust, "robust loss: none, huber or cauchy")->capture_default_str();
    cmd->add_option("--robust-scale", o->robustScale, "robust loss scale (normalised residual units)")->capture_default_str();
    cmd->add_option("--seed", o->seed, "seed of the random starts")->capture_default_str();
    cmd->callback([o, &exitCode] { runFit(*o, exitCode); });
}

}  // namespace stickslip::cli
