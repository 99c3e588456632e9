#include "../friction/friction_law.hpp"
#include "pipeline.hpp"

#include <cstdlib>
#include <sstream>

#include "../analysis/parallel.hpp"
#include "../io/units.hpp"
#include "fit_report.hpp"

namespace stickslip::identify {

using io::Signal;

namespace {

bool fail(PipelineStatus& st, PipelineCode code, const std::string& msg) {
    st.code = code;
    st.message = msg;
    return false;
}

// Cleans every run of `ds`; each must know its t_N. The runs are cleaned in parallel (each into
// its own slot; the stage's harmonic fit and its frequency search take a few tenths of a second
// a run), then checked in order, so that the first bad run is the one reported.
bool cleanRuns(const io::Dataset& ds, const PreprocessSettings& pre, std::vector<CleanRun>& out,
               PipelineStatus& st) {
    const size_t n = ds.runs.size();
    std::vector<CleanRun> clean(n);
    std::vector<std::string> errors(n);
    std::vector<char> ok(n, 0);
    parallelFor(n, 0, [&](size_t i) { ok[i] = preprocessRun(ds.runs[i], pre, clean[i], &errors[i]) ? 1 : 0; });
    for (size_t i = 0; i < n; ++i) {
        const io::Run& r = ds.runs[i];
        if (!ok[i]) return fail(st, PipelineCode::BadArguments, errors[i]);
        double tN = 0;
        if (!clean[i].run.setting("tN", tN))
            return fail(st, PipelineCode::BadArguments,
                        r.file + ": t_N unknown: give a normal_force_N or band_tension_N column, a manifest, or --run-set " +
                            r.name() + ":tN=VALUE");
    }
    for (CleanRun& c : clean) out.push_back(std::move(c));
    return true;
}

// The solver settings of a fit request (everything but setup and law).
bool fitSettings(const FitRequest& o, SetupKind setup, DatasetFitSettings& st, PipelineStatus& status) {
    st.setup = setup;
    st.free = splitList(o.free);
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
    st.cancel = o.cancel;
    if (o.robust == "huber") st.loss = LossKind::Huber;
    else if (o.robust == "cauchy") st.loss = LossKind::Cauchy;
    else if (o.robust != "none")
        return fail(status, PipelineCode::BadArguments, "--robust " + o.robust + ": must be none, huber or cauchy");
    for (const std::string& kv : o.sets) {
        const auto eq = kv.find('=');
        double v = 0;
        std::string e;
        if (eq == std::string::npos) return fail(status, PipelineCode::BadArguments, "--set " + kv + ": expected KEY=VALUE");
        const std::string key = kv.substr(0, eq);
        if (key == "zeta") {
            char* end = nullptr;
            const std::string txt = kv.substr(eq + 1);
            v = std::strtod(txt.c_str(), &end);
            if (end == txt.c_str() || *end != '\0' || !(v >= 0.0))
                return fail(status, PipelineCode::BadArguments, "--set " + kv + ": zeta must be a number >= 0");
        } else if (!io::parseParamValue(key, kv.substr(eq + 1), v, &e)) {
            return fail(status, PipelineCode::BadArguments, "--set " + kv + ": " + e);
        }
        st.start[key] = v;
    }
    for (const std::string& n : st.free) {
        FitParameter fp;
        if (n != "zeta" && !defaultParameter(n, setup, fp))
            return fail(status, PipelineCode::BadArguments,
                        "--free " + n + ": unknown parameter (known: " + fitParamKeys() + " zeta)");
    }
    return true;
}

}  // namespace

nlohmann::json cleanRunSummary(const CleanRun& c, const std::string& file) {
    nlohmann::json settings = nlohmann::json::object();
    for (const auto& [k, v] : c.run.settings) {
        const auto src = c.run.settingSource.find(k);
        settings[k] = {{"value", v}, {"source", src == c.run.settingSource.end() ? std::string() : src->second}};
    }
    return {{"file", file}, {"sample_rate_Hz", 1.0 / c.dt_s},
            {"fit_window_s", {c.run[Signal::Time][c.begin], c.run[Signal::Time][c.end - 1]}},
            {"period_s", c.period_s}, {"resampled", c.resampled}, {"notes", c.notes}, {"settings", settings}};
}

namespace {

// A report's preprocessing.runs[]: the fitted runs, then the held-out ones (cleaned[i] from data.runs[i]).
nlohmann::json cleanRunsJson(const std::vector<CleanRun>& fit, const io::Dataset& fitData, const std::vector<CleanRun>& val,
                             const io::Dataset& valData) {
    nlohmann::json out = nlohmann::json::array();
    for (size_t i = 0; i < fit.size(); ++i) out.push_back(cleanRunSummary(fit[i], fitData.runs[i].file));
    for (size_t i = 0; i < val.size(); ++i) out.push_back(cleanRunSummary(val[i], valData.runs[i].file));
    return out;
}

}  // namespace

std::vector<std::string> splitList(const std::string& s) {
    std::vector<std::string> out;
    std::string cur;
    for (char c : s + ",") {
        if (c == ',') {
            if (!cur.empty()) out.push_back(cur);
            cur.clear();
        } else if (c != ' ') {
            cur += c;
        }
    }
    return out;
}

PreprocessSettings CleaningOptions::effective() const {
    PreprocessSettings p = pre;
    if (noBandStop) p.filters.bandStop = false;
    if (noLowPass) p.filters.lowPass = false;
    if (noSteadyTrim) p.trim.steadyAmplitude = false;
    return p;
}

bool loadMeasuredInputs(const MeasuredInputs& o, io::Dataset& fitData, io::Dataset& valData, SetupKind& setup,
                        PipelineStatus& st) {
    if (o.data.empty()) return fail(st, PipelineCode::BadArguments, "no data files given");
    io::DatasetOptions dopt;
    dopt.manifestPath = o.manifest;
    dopt.runSets = o.runSets;
    std::string why;
    for (const auto& c : o.columns)
        if (!dopt.mapping.addColumns(c, &why)) return fail(st, PipelineCode::BadArguments, why);
    for (const auto& u : o.units)
        if (!dopt.mapping.addUnits(u, &why)) return fail(st, PipelineCode::BadArguments, why);
    io::DatasetError derr;
    if (!io::loadDataset(o.data, dopt, fitData, derr))
        return fail(st, derr.file == "--run-set" ? PipelineCode::BadArguments : PipelineCode::BadInput, derr.what());
    if (!o.validateOn.empty()) {
        io::DatasetOptions vopt = dopt;
        vopt.runSets.clear();
        if (!io::loadDataset(o.validateOn, vopt, valData, derr)) return fail(st, PipelineCode::BadInput, derr.what());
        for (const std::string& spec : o.runSets) {  // run-sets may name validation files too
            std::string w;
            io::applyRunSet(valData, spec, &w);
        }
    }
    setup = SetupKind::Prescribed;
    if (!o.setup.empty()) {
        if (!parseSetupKind(o.setup, setup))
            return fail(st, PipelineCode::BadArguments, "--setup " + o.setup + ": must be prescribed or dynamics");
    } else if (fitData.runs.front().has(Signal::SliderDisp)) {
        setup = SetupKind::Dynamics;
    }
    return true;
}

bool runFitRequest(const FitRequest& o, FitOutcome& out, PipelineStatus& status) {
    out = FitOutcome{};  // cleanRuns appends; cleanRunSummary pairs out.fitRuns[i] with fitData.runs[i]
    io::Dataset fitData, valData;
    if (!loadMeasuredInputs(o.in, fitData, valData, out.setup, status)) return false;
    const PreprocessSettings pre = o.cleaning.effective();
    nlohmann::json preJson = toJson(pre);
    if (!cleanRuns(fitData, pre, out.fitRuns, status) || !cleanRuns(valData, pre, out.validationRuns, status))
        return false;
    const nlohmann::json perRun = cleanRunsJson(out.fitRuns, fitData, out.validationRuns, valData);
    if (o.splitTime > 0.0) {
        const std::string e = holdOutLaterParts(out.fitRuns, out.validationRuns, o.splitTime);
        if (!e.empty()) return fail(status, PipelineCode::BadArguments, "--split-time: " + e);
    }
    preJson["runs"] = perRun;
    DatasetFitSettings& st = out.settings;
    if (!fitSettings(o, out.setup, st, status)) return false;
    std::vector<LawKind> laws(1, LawKind::RateState);
    if (o.model == "both") laws = {LawKind::RateState, LawKind::Coulomb};
    else if (!parseLawKind(o.model, laws[0])) {
        std::string names;
        for (const LawInfo& i : lawRegistry()) names += std::string(i.key) + ", ";
        return fail(status, PipelineCode::BadArguments, "--model " + o.model + ": must be " + names + "or both");
    }

    if (!fitLaws(out.fitRuns, out.validationRuns, st, laws, out.fits, status, o.log)) return false;
    std::vector<const DatasetFit*> fitted;
    for (const DatasetFit& f : out.fits) fitted.push_back(&f);
    nlohmann::json& rep = out.report;
    rep = fitReportJson(fitted);
    rep["preprocessing"] = preJson;
    rep["prediction"] = toJson(st.predict);
    rep["t_N_convention"] = out.setup == SetupKind::Prescribed
        ? "t_N of each run is its known load (normal force column, else the band tension column, else manifest/--run-set); "
          "mu, C1 and eta are per unit of that load, so for a band brake mu absorbs the band's force amplification"
        : "t_N of each run from the normal force column (mean), else the manifest";
    rep["validation"] = !o.in.validateOn.empty() ? "by run (--validate-on)" : (o.splitTime > 0 ? "by time (--split-time)" : "none");
    return true;
}

bool fitLaws(const std::vector<CleanRun>& fitRuns, const std::vector<CleanRun>& validationRuns, DatasetFitSettings st,
             const std::vector<LawKind>& laws, std::vector<DatasetFit>& out, PipelineStatus& status,
             const std::function<void(const std::string&)>& log,
             const std::function<void(size_t, const DatasetFit&)>& fitted) {
    const std::function<void(double)> progress = st.progress;
    const double nLaws = static_cast<double>(std::max<size_t>(laws.size(), 1));
    for (size_t i = 0; i < laws.size(); ++i) {
        if (cancelRequested(st.cancel)) return fail(status, PipelineCode::Cancelled, "cancelled");
        st.law = laws[i];
        if (progress)
            st.progress = [&progress, i, nLaws](double f) { progress((static_cast<double>(i) + f) / nLaws); };
        if (log)
            log(std::string("fitting ") + toString(st.law) + " (" + toString(st.setup) + ", " +
                std::to_string(fitRuns.size()) + " fit runs, " + std::to_string(validationRuns.size()) +
                " validation runs)...");
        DatasetFit f = fitDataset(fitRuns, validationRuns, st);
        if (!f.ok) {
            const bool cancelled = cancelRequested(st.cancel);
            return fail(status, cancelled ? PipelineCode::Cancelled : PipelineCode::RunFailed,
                        std::string(toString(st.law)) + ": " + f.message);
        }
        if (log) {
            std::ostringstream line;  // default stream formatting, as the CLI always printed it
            line << "  " << toString(st.law) << ": fit NRMSE " << f.fitNrmse << ", validation NRMSE "
                 << f.validationNrmse << ", " << f.fit.identifiabilityMessage;
            log(line.str());
            if (!f.stderrWarning.empty()) log("  warning: " + f.stderrWarning);
        }
        out.push_back(std::move(f));
        if (fitted) fitted(i, out.back());
    }
    return true;
}

bool runIdentifyRequest(const IdentifyRequest& o, IdentifyResult& res, nlohmann::json& report, PipelineStatus& status) {
    IdentifyOptions opt = o.options;
    if (o.dynamicsResidual == "auto") opt.dynamicsResidual = DynamicsResidual::Auto;
    else if (o.dynamicsResidual == "equation-error") opt.dynamicsResidual = DynamicsResidual::EquationError;
    else if (o.dynamicsResidual == "segments") opt.dynamicsResidual = DynamicsResidual::Segments;
    else
        return fail(status, PipelineCode::BadArguments,
                    "--dynamics-residual: '" + o.dynamicsResidual + "' is not one of auto, equation-error, segments");
    if (o.selfTest) {
        if (o.selfTestReplicas < 1 || o.selfTestReplicas > 10000)
            return fail(status, PipelineCode::BadArguments,
                        "--self-test-replicas = " + std::to_string(o.selfTestReplicas) + " is outside the allowed range [1, 10000]");
        opt.selfTest.replicas = o.selfTestReplicas;
        opt.selfTest.levels = o.selfTestLevels;
        opt.selfTest.sizes.clear();
        opt.selfTest.shape.clear();
        if (std::string e; !opt.selfTest.parseStated(o.selfTestSizes, e))
            return fail(status, PipelineCode::BadArguments, "--self-test-size " + e);
    }
    if (const ParamIssues why = opt.validate(); !why.empty())
        return fail(status, PipelineCode::BadArguments, formatIssues(why));
    io::Dataset fitData, valData;
    SetupKind setup = SetupKind::Prescribed;
    if (!loadMeasuredInputs(o.in, fitData, valData, setup, status)) return false;
    const PreprocessSettings pre = o.cleaning.effective();
    std::vector<CleanRun> fitClean, valClean;
    if (!cleanRuns(fitData, pre, fitClean, status) || !cleanRuns(valData, pre, valClean, status)) return false;
    std::vector<IdentifyRun> runs;
    for (int pass = 0; pass < 2; ++pass) {
        const io::Dataset& raw = pass == 0 ? fitData : valData;
        const std::vector<CleanRun>& clean = pass == 0 ? fitClean : valClean;
        for (size_t i = 0; i < clean.size(); ++i) {
            IdentifyRun ir;
            std::string e;
            if (!makeIdentifyRun(clean[i], setup, ir, &e)) return fail(status, PipelineCode::BadInput, e);
            ir.validation = pass == 1;
            // Only the simulated null reads the recording: no copy of it otherwise.
            if (opt.simulatedNullReplicas > 0) ir.recording = std::make_shared<const io::Run>(raw.runs[i]);
            runs.push_back(std::move(ir));
        }
    }
    // Replicas of the recordings (the simulated null) are cleaned exactly as the data were.
    opt.reprepare = recordingPreparer(pre, setup);
    opt.freeLaw = splitList(o.free);
    for (const std::string& n : opt.freeLaw) {
        FitParameter fp;
        if (!defaultParameter(n, setup, fp) || n == "m" || n == "k" || n == "c" || n == "tN")
            return fail(status, PipelineCode::BadArguments, "--free " + n + ": not a law parameter (mu, C1, eta, Dc, vc, epsT, r)");
    }
    opt.candidates = o.candidates;
    for (const std::string& c : opt.candidates) {
        EffectInfo info;
        if (!findEffect(c, info)) return fail(status, PipelineCode::BadArguments, "--candidates " + c + ": not in the catalogue");
    }
    res = identifyEffects(std::move(runs), opt);
    if (!res.ok) return fail(status, res.cancelled ? PipelineCode::Cancelled : PipelineCode::RunFailed, res.message);
    if (res.selfTest.ran && !res.selfTest.ok)
        return fail(status, res.cancelled ? PipelineCode::Cancelled : PipelineCode::RunFailed, "self-test: " + res.selfTest.message);
    report = toJson(res);
    report["preprocessing"] = toJson(pre);
    report["preprocessing"]["runs"] = cleanRunsJson(fitClean, fitData, valClean, valData);
    report["inputs"] = {{"data", o.in.data}, {"validate_on", o.in.validateOn}, {"manifest", o.in.manifest}};
    return true;
}

}  // namespace stickslip::identify
