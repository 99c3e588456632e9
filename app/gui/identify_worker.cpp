#include "identify_worker.hpp"

#include <QElapsedTimer>
#include <QMetaObject>
#include <QtConcurrent/QtConcurrentRun>
#include <algorithm>
#include <cmath>

#include "core/io/units.hpp"
#include "core/identify/fit_report.hpp"
#include "core/identify/pipeline.hpp"
#include "core/integrate/run_result.hpp"

namespace stickslip::gui {

using namespace stickslip::identify;
using io::Signal;

size_t MeasuredRuns::fitCount() const {
    size_t n = 0;
    for (size_t i = 0; i < data.runs.size(); ++i) n += (i < validation.size() && validation[i]) ? 0 : 1;
    return n;
}

size_t MeasuredRuns::validationCount() const { return data.runs.size() - fitCount(); }

SetupKind guessSetup(const io::Dataset& data) {
    return !data.runs.empty() && data.runs.front().has(Signal::SliderDisp) ? SetupKind::Dynamics : SetupKind::Prescribed;
}

bool cleanRuns(const MeasuredRuns& runs, std::vector<CleanRun>& fit, std::vector<CleanRun>& validation, std::string* error,
               const std::atomic<bool>* cancel) {
    fit.clear();
    validation.clear();
    for (size_t i = 0; i < runs.data.runs.size(); ++i) {
        if (stickslip::cancelRequested(cancel)) {
            if (error) *error = "cancelled";
            return false;
        }
        const io::Run& r = runs.data.runs[i];
        CleanRun c;
        if (!preprocessRun(r, runs.pre, c, error)) return false;
        double tN = 0;
        if (!c.run.setting("tN", tN)) {
            if (error)
                *error = r.file + ": t_N unknown: give a normal_force_N or band_tension_N column, a manifest, or set tN for " +
                         r.name();
            return false;
        }
        (i < runs.validation.size() && runs.validation[i] ? validation : fit).push_back(std::move(c));
    }
    if (fit.empty()) {
        if (error) *error = "no run to fit: every run is marked for validation";
        return false;
    }
    return true;
}

namespace {

// The report's preprocessing.runs[] (as `stickslip-cli fit|identify --report`): fitted runs, then
// held-out ones, each with its cleaning notes.
nlohmann::json cleanedRunsJson(const MeasuredRuns& runs, const std::vector<CleanRun>& fit, const std::vector<CleanRun>& val) {
    nlohmann::json out = nlohmann::json::array();
    std::vector<std::string> fitFiles, valFiles;
    for (size_t i = 0; i < runs.data.runs.size(); ++i)
        (i < runs.validation.size() && runs.validation[i] ? valFiles : fitFiles).push_back(runs.data.runs[i].file);
    for (size_t i = 0; i < fit.size() && i < fitFiles.size(); ++i) out.push_back(identify::cleanRunSummary(fit[i], fitFiles[i]));
    for (size_t i = 0; i < val.size() && i < valFiles.size(); ++i) out.push_back(identify::cleanRunSummary(val[i], valFiles[i]));
    return out;
}

RunOverlay overlayOf(const CleanRun& c, const std::string& role, SetupKind setup, const ModelSpec& model,
                     const PredictSettings& predict) {
    RunOverlay o;
    o.file = c.run.name();
    o.role = role;
    Prediction p;
    scoreRun(c, setup, model, predict, role, &p);
    if (!p.ok) return o;
    const auto& t = c.run[Signal::Time];
    const auto& F = c.run[Signal::Friction];
    for (size_t k = 0; k < p.index.size() && k < p.force_N.size(); ++k) {
        o.t_s.push_back(t[p.index[k]]);
        o.measured_N.push_back(F[p.index[k]]);
        o.predicted_N.push_back(p.force_N[k]);
        o.slip_m.push_back(c.run.has(Signal::Slip) ? c.run[Signal::Slip][p.index[k]] : NAN);
        o.relVel_mps.push_back(c.run.has(Signal::RelVel) ? c.run[Signal::RelVel][p.index[k]] : NAN);
    }
    return o;
}


// One law's fit as the Fit tab draws it: overlays of every run and the residual diagnostics.
LawFit lawFitOf(LawKind law, const identify::DatasetFit& fit, const std::vector<CleanRun>& fitRuns,
                const std::vector<CleanRun>& valRuns, const DatasetFitSettings& st) {
    LawFit lf;
    lf.law = law;
    lf.fit = fit;
    for (const CleanRun& c : fitRuns) lf.overlays.push_back(overlayOf(c, "fit", st.setup, lf.fit.model, st.predict));
    for (const CleanRun& c : valRuns) lf.overlays.push_back(overlayOf(c, "validation", st.setup, lf.fit.model, st.predict));
    std::vector<DiagnosticRun> diag;
    // Prescribed: the scored samples are evenly spaced, so the spectrum means something
    // (dynamics scores short shooting segments).
    for (size_t k = 0; st.setup == SetupKind::Prescribed && k < fitRuns.size() && k < lf.overlays.size(); ++k) {
        const RunOverlay& o = lf.overlays[k];
        if (o.t_s.size() < 16) continue;
        DiagnosticRun d;
        d.t_s = o.t_s;
        for (size_t j = 0; j < o.t_s.size(); ++j) d.residual.push_back(o.measured_N[j] - o.predicted_N[j]);
        d.slip_m = o.slip_m;
        d.relVel_mps = o.relVel_mps;
        fitRuns[k].run.setting("tN", d.normalForce_N);
        fitRuns[k].run.setting("f", d.forcingFrequency_Hz);
        d.runIndex = static_cast<int>(k);
        diag.push_back(std::move(d));
    }
    if (!diag.empty()) lf.diagnostics = diagnose(diag);
    return lf;
}

double msSince(const QElapsedTimer& t) { return t.nsecsElapsed() / 1.0e6; }

}  // namespace

FitOutcome runFitJob(const FitRequest& request, const std::atomic<bool>* cancel, const JobProgress& progress) {
    QElapsedTimer clock;
    clock.start();
    FitOutcome out;
    out.request = request;
    auto report = [&](double f, const std::string& stage) {
        if (progress) progress(f, stage);
    };
    report(0.0, "preprocessing");
    std::vector<CleanRun> fitRuns, valRuns;
    std::string why;
    if (!cleanRuns(request.runs, fitRuns, valRuns, &why, cancel)) {
        out.cancelled = stickslip::cancelRequested(cancel);
        out.message = QString::fromStdString(why);
        out.elapsed_ms = msSince(clock);
        return out;
    }
    out.cleanedRuns = cleanedRunsJson(request.runs, fitRuns, valRuns);
    if (request.splitTime > 0.0) {
        const std::string e = holdOutLaterParts(fitRuns, valRuns, request.splitTime);
        if (!e.empty()) {
            out.message = QString::fromStdString(e);
            return out;
        }
    }
    if (request.laws.empty()) {
        out.message = QStringLiteral("no model chosen");
        return out;
    }
    // The shared loop (identify::fitLaws, as `stickslip-cli fit`); per law, the overlays and the
    // residual diagnostics the Fit tab draws.
    const double nLaws = static_cast<double>(request.laws.size());
    DatasetFitSettings st = request.settings;
    st.setup = request.runs.setup;
    st.cancel = cancel;
    st.progress = [&](double g) {
        const size_t i = std::min(static_cast<size_t>(g * nLaws), request.laws.size() - 1);
        const double f = g * nLaws - static_cast<double>(i);
        report((static_cast<double>(i) + 0.95 * f) / nLaws, std::string("fitting ") + toString(request.laws[i]));
    };
    auto fitted = [&](size_t i, const identify::DatasetFit& fit) {
        report((static_cast<double>(i) + 0.95) / nLaws, "predicting " + std::string(toString(request.laws[i])));
        out.fits.push_back(lawFitOf(request.laws[i], fit, fitRuns, valRuns, st));
    };
    std::vector<identify::DatasetFit> fits;
    identify::PipelineStatus status;
    if (!identify::fitLaws(fitRuns, valRuns, st, request.laws, fits, status, {}, fitted) &&
        !stickslip::cancelRequested(cancel)) {
        out.message = QString::fromStdString(status.message);
        out.elapsed_ms = msSince(clock);
        return out;
    }
    out.elapsed_ms = msSince(clock);
    if (stickslip::cancelRequested(cancel)) {
        out.cancelled = true;
        out.fits.clear();
        out.message = QStringLiteral("cancelled");
        return out;
    }
    out.ok = true;
    report(1.0, "done");
    return out;
}

IdentifyOutcome runIdentifyJob(const IdentifyRequest& request, const std::atomic<bool>* cancel, const JobProgress& progress) {
    QElapsedTimer clock;
    clock.start();
    IdentifyOutcome out;
    out.request = request;
    if (progress) progress(0.0, "preprocessing");
    std::vector<CleanRun> fitRuns, valRuns;
    std::string why;
    if (!cleanRuns(request.runs, fitRuns, valRuns, &why, cancel)) {
        out.cancelled = stickslip::cancelRequested(cancel);
        out.message = QString::fromStdString(why);
        out.elapsed_ms = msSince(clock);
        return out;
    }
    out.cleanedRuns = cleanedRunsJson(request.runs, fitRuns, valRuns);
    std::vector<IdentifyRun> runs;
    // Recording order matters (wear drift): keep the runs in the order they were loaded.
    size_t fi = 0, vi = 0;
    for (size_t i = 0; i < request.runs.data.runs.size(); ++i) {
        const bool val = i < request.runs.validation.size() && request.runs.validation[i];
        const CleanRun& c = val ? valRuns[vi++] : fitRuns[fi++];
        IdentifyRun ir;
        if (!makeIdentifyRun(c, request.runs.setup, ir, &why)) {
            out.message = QString::fromStdString(why);
            return out;
        }
        ir.validation = val;
        runs.push_back(std::move(ir));
    }
    IdentifyOptions opt = request.options;
    opt.cancel = cancel;
    opt.progress = [&](const std::string& stage, double f) {
        if (progress) progress(f, stage);
    };
    out.result = identifyEffects(std::move(runs), opt);
    out.elapsed_ms = msSince(clock);
    out.cancelled = out.result.cancelled || stickslip::cancelRequested(cancel);
    out.ok = out.result.ok && !out.cancelled;
    if (out.cancelled) out.message = QStringLiteral("cancelled");
    else if (!out.ok) out.message = QString::fromStdString(out.result.message);
    return out;
}

nlohmann::json fitReportJson(const FitOutcome& o) {
    if (o.fits.empty()) return nlohmann::json::object();
    std::vector<const DatasetFit*> fitted;
    for (const auto& lf : o.fits) fitted.push_back(&lf.fit);
    nlohmann::json rep = fitReportJson(fitted);  // the layout of `stickslip-cli fit --report`
    rep["preprocessing"] = toJson(o.request.runs.pre);
    rep["preprocessing"]["runs"] = o.cleanedRuns;
    rep["prediction"] = toJson(o.request.settings.predict);
    rep["validation"] = o.request.runs.validationCount() > 0 ? "by run"
                        : (o.request.splitTime > 0 ? "by time" : "none");
    nlohmann::json files = nlohmann::json::array();
    for (const io::Run& r : o.request.runs.data.runs) files.push_back(r.file);
    rep["inputs"] = {{"data", files}, {"manifest", o.request.runs.data.manifestPath}};
    rep["robust_loss"] = o.request.settings.loss == LossKind::Huber ? "huber" : o.request.settings.loss == LossKind::Cauchy ? "cauchy" : "none";
    rep["created_by"] = "stickslip GUI (Identify panel)";
    return rep;
}

nlohmann::json identifyReportJson(const IdentifyOutcome& o) {
    nlohmann::json j = toJson(o.result);
    j["preprocessing"] = toJson(o.request.runs.pre);
    j["preprocessing"]["runs"] = o.cleanedRuns;
    nlohmann::json data = nlohmann::json::array(), val = nlohmann::json::array();
    for (size_t i = 0; i < o.request.runs.data.runs.size(); ++i)
        (i < o.request.runs.validation.size() && o.request.runs.validation[i] ? val : data).push_back(o.request.runs.data.runs[i].file);
    j["inputs"] = {{"data", data}, {"validate_on", val}, {"manifest", o.request.runs.data.manifestPath}};
    return j;
}

// ---------------------------------------------------------------------------------------

IdentifyWorker::IdentifyWorker(QObject* parent) : QObject(parent) {
    qRegisterMetaType<FitOutcome>();
    qRegisterMetaType<IdentifyOutcome>();
    pool_.setMaxThreadCount(1);
}

IdentifyWorker::~IdentifyWorker() {
    cancel();
    pool_.waitForDone();
}

void IdentifyWorker::cancel() {
    if (cancel_) cancel_->store(true);
}

void IdentifyWorker::waitForDone() { pool_.waitForDone(); }

JobProgress IdentifyWorker::progressSink(quint64 id) {
    // Throttled: at most one queued update per 0.5 % or stage change.
    auto last = std::make_shared<std::pair<double, std::string>>(-1.0, std::string());
    return [this, id, last](double f, const std::string& stage) {
        if (stage == last->second && std::abs(f - last->first) < 0.005) return;
        *last = {f, stage};
        const QString s = QString::fromStdString(stage);
        QMetaObject::invokeMethod(
            this,
            [this, id, f, s] {
                if (id == lastId_) emit progress(f, s);
            },
            Qt::QueuedConnection);
    };
}

// Cancels the job in flight, then runs `job(request, cancel, progress)` on the pool and emits
// `finished` with its outcome on this object's thread, unless a newer job superseded it.
template <class Request, class Outcome>
quint64 IdentifyWorker::launch(const Request& request,
                               Outcome (*job)(const Request&, const std::atomic<bool>*, const JobProgress&),
                               void (IdentifyWorker::*finished)(const Outcome&)) {
    cancel();
    const quint64 id = ++lastId_;
    auto token = std::make_shared<std::atomic<bool>>(false);
    cancel_ = token;
    busy_ = true;
    JobProgress sink = progressSink(id);
    QtConcurrent::run(&pool_, [this, request, token, id, sink, job, finished] {
        Outcome out = job(request, token.get(), sink);
        out.id = id;
        QMetaObject::invokeMethod(
            this,
            [this, out = std::move(out), finished] {
                if (out.id != lastId_) return;  // superseded
                busy_ = false;
                emit(this->*finished)(out);
            },
            Qt::QueuedConnection);
    });
    return id;
}

quint64 IdentifyWorker::startFit(const FitRequest& request) {
    return launch(request, &runFitJob, &IdentifyWorker::fitFinished);
}

quint64 IdentifyWorker::startIdentify(const IdentifyRequest& request) {
    return launch(request, &runIdentifyJob, &IdentifyWorker::identifyFinished);
}

}  // namespace stickslip::gui
