#include "simulation_controller.hpp"

#include <QtConcurrent/QtConcurrentRun>
#include <algorithm>
#include <cmath>
#include <ctime>
#include <future>

#include "core/analysis/correlation.hpp"
#include "core/analysis/spectrum.hpp"
#include "core/integrate/simulate.hpp"

namespace stickslip::gui {

namespace {

// Spectrum and autocorrelation of the signal that moves in this set-up: the slider
// displacement x for the rig, F/t_N for the block with prescribed slip (where x ≡ 0).
void analyse(ModelRun& mr, SetupKind setup) {
    const auto& s = mr.run.samples;
    if (!mr.run.ok() || s.size() < 64) return;
    const double dt = s[1].t_s - s[0].t_s;
    if (!(dt > 0.0)) return;
    std::vector<double> x(s.size());
    for (size_t i = 0; i < s.size(); ++i) x[i] = setup == SetupKind::Dynamics ? s[i].slider_m : s[i].ratio;
    PowerSpectrum ps = powerSpectrum(x, 1.0 / dt);
    if (ps.ok) {
        mr.spectrumFreq_Hz = std::move(ps.frequency_Hz);
        mr.spectrumPsd = std::move(ps.psd);
    }
    Correlation ac = autocorrelation(x, 1.0 / dt, s.size() / 2);
    mr.acfLag_s = std::move(ac.lag_s);
    mr.acf = std::move(ac.r);
}

double msSince(const QElapsedTimer& t) { return t.nsecsElapsed() / 1.0e6; }

// CPU time of the calling thread [ms] (what the job cost, whatever the machine's load).
double threadCpuMs() {
    timespec ts{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return ts.tv_sec * 1e3 + ts.tv_nsec / 1e6;
}

}  // namespace

bool RunOutcome::ok() const {
    return std::all_of(runs.begin(), runs.end(), [](const ModelRun& r) { return r.run.ok(); });
}

QString RunOutcome::failureText() const {
    QStringList parts;
    for (const auto& r : runs) {
        if (r.run.ok()) continue;
        parts << QStringLiteral("%1 run %2: %3")
                     .arg(QString::fromLatin1(stickslip::toString(r.law)),
                          QString::fromLatin1(stickslip::toString(r.run.status)),
                          QString::fromStdString(r.run.message).replace('\n', "; "));
    }
    return parts.join(" | ");
}

bool SweepOutcome::cancelled() const {
    return std::any_of(results.begin(), results.end(),
                       [](const auto& r) { return r.second.status == RunStatus::Cancelled; });
}

SimulationController::SimulationController(QObject* parent) : QObject(parent) {
    // Value types crossing threads through queued signals.
    qRegisterMetaType<ModelSettings>();
    qRegisterMetaType<RunOutcome>();
    qRegisterMetaType<PoincareOutcome>();
    qRegisterMetaType<SweepOutcome>();
    qRegisterMetaType<MapOutcome>();
    qRegisterMetaType<SweepOptions>();
    qRegisterMetaType<MapOptions>();
    // One thread per kind of job, so a long sweep never queues a parameter change.
    pool_.setMaxThreadCount(kJobKinds);
}

SimulationController::~SimulationController() {
    cancelAll();
    pool_.waitForDone();
}

bool SimulationController::isIdle() const {
    return std::none_of(slots_.begin(), slots_.end(), [](const Slot& s) {
               return s.busy || s.hasPending;
           });
}

bool SimulationController::sectionFromRun(const ModelSettings& settings) {
    // A fixed-step run records once-per-period states when dt divides T; an error-controlled
    // run always does (from its dense output at exactly t = kT).
    const SimParams p = settings.paramsFor(settings.primaryLaw());
    return p.setup == SetupKind::Dynamics && (p.integration.tolerance > 0.0 || stepsPerPeriodDividing(p) > 0) &&
           p.transientCycles == std::round(p.transientCycles) && p.cycles == std::round(p.cycles) && p.cycles >= 1;
}

void SimulationController::requestRun(const ModelSettings& settings) {
    pending_ = settings;
    slots_[int(JobKind::Run)].hasPending = true;
    // The run brings the section when it can; then a section job of older settings is stale.
    const bool ownJob = poincareEnabled_ && !sectionFromRun(settings);
    if (!ownJob) cancel(JobKind::Poincare);
    slots_[int(JobKind::Poincare)].hasPending = ownJob;
    // Leading edge: a free kind starts now; a busy one cancels its stale job and starts the
    // newest settings when that returns (a drag becomes one job per job duration, no delay).
    fire();
}

void SimulationController::fire() {
    for (JobKind kind : {JobKind::Run, JobKind::Poincare}) {
        Slot& s = slots_[int(kind)];
        if (!s.hasPending) continue;
        if (s.busy) {
            // Stale: ask it to stop; the newest settings start when it returns.
            if (s.cancel && !s.cancel->exchange(true)) ++s.cancelledJobs;
            continue;
        }
        s.hasPending = false;
        if (kind == JobKind::Run) launchRun(pending_);
        else launchPoincare(pending_);
    }
}

std::shared_ptr<std::atomic<bool>> SimulationController::beginJob(JobKind kind, quint64& generation) {
    Slot& s = slots_[int(kind)];
    s.cancel = std::make_shared<std::atomic<bool>>(false);
    s.busy = true;
    ++s.launched;
    generation = ++s.generation;
    return s.cancel;
}

void SimulationController::jobReturned(JobKind kind, quint64 generation, bool wasCancelled) {
    Slot& s = slots_[int(kind)];
    if (generation == s.generation) s.busy = false;
    Q_UNUSED(wasCancelled);
    // Newer settings waited for this job: start them now.
    if ((kind == JobKind::Run || kind == JobKind::Poincare) && s.hasPending) fire();
}

bool SimulationController::previewFirst(const ModelSettings& settings) {
    return settings.params.setup == SetupKind::Dynamics && settings.tolerance > 0.0 &&
           settings.tolerance < kPreviewTolerance;
}

namespace {

// The runs of one Run job (every law of the settings), with their analyses.
RunOutcome computeRun(const ModelSettings& settings, quint64 gen, const RunControl& ctl) {
    QElapsedTimer clock;
    clock.start();
    const double cpu0 = threadCpuMs();
    RunOutcome out;
    out.generation = gen;
    out.settings = settings;
    out.requestedTolerance = settings.tolerance;
    out.sectionInRun = SimulationController::sectionFromRun(settings);
    const auto laws = settings.laws();
    out.runs.resize(laws.size());
    auto one = [&](size_t i) {
        out.runs[i].law = laws[i];
        out.runs[i].run = simulate(settings.paramsFor(laws[i]), ctl);
        if (out.sectionInRun) out.runs[i].section = sectionOfRun(out.runs[i].run, settings.params.drive.period());
        analyse(out.runs[i], settings.params.setup);
    };
    if (laws.size() == 2) {
        // The overlaid model runs beside the primary one (2 cores).
        auto second = std::async(std::launch::async, [&] { one(1); });
        one(0);
        second.get();
    } else {
        one(0);
    }
    out.elapsed_ms = msSince(clock);
    out.cpu_ms = threadCpuMs() - cpu0;
    return out;
}

}  // namespace

void SimulationController::launchRun(const ModelSettings& settings) {
    quint64 gen = 0;
    auto token = beginJob(JobKind::Run, gen);
    emit runStarted(gen);
    QtConcurrent::run(&pool_, [this, token, gen, settings]() {
        RunControl ctl;
        ctl.cancel = token.get();
        if (previewFirst(settings)) {
            ModelSettings coarse = settings;
            coarse.tolerance = kPreviewTolerance;
            RunOutcome first = computeRun(coarse, gen, ctl);
            first.preview = true;
            first.requestedTolerance = settings.tolerance;
            if (!token->load())
                QMetaObject::invokeMethod(
                    this, [this, first = std::move(first)]() { emit runFinished(first); }, Qt::QueuedConnection);
        }
        RunOutcome out = token->load() ? RunOutcome{} : computeRun(settings, gen, ctl);
        out.generation = gen;
        const bool cancelled = token->load();
        QMetaObject::invokeMethod(
            this,
            [this, out = std::move(out), cancelled]() {
                jobReturned(JobKind::Run, out.generation, cancelled);
                if (!cancelled) emit runFinished(out);
            },
            Qt::QueuedConnection);
    });
}

void SimulationController::launchPoincare(const ModelSettings& settings) {
    quint64 gen = 0;
    auto token = beginJob(JobKind::Poincare, gen);
    QtConcurrent::run(&pool_, [this, token, gen, settings]() {
        QElapsedTimer clock;
        clock.start();
        RunControl ctl;
        ctl.cancel = token.get();
        PoincareOutcome out;
        out.generation = gen;
        out.settings = settings;
        if (settings.params.setup == SetupKind::Dynamics) {
            // One point per forcing period over the same cycles the run records.
            PoincareOptions opt;
            opt.settleCycles = std::lround(settings.params.transientCycles);
            opt.cycles = std::max(1L, std::lround(settings.params.cycles));
            opt.phase_rad = 0.0;
            for (LawKind law : settings.laws())
                out.sections.emplace_back(law, poincareSection(settings.paramsFor(law), opt, ctl));
        }
        out.elapsed_ms = msSince(clock);
        const bool cancelled = token->load();
        QMetaObject::invokeMethod(
            this,
            [this, out = std::move(out), cancelled]() {
                jobReturned(JobKind::Poincare, out.generation, cancelled);
                if (!cancelled) emit poincareFinished(out);
            },
            Qt::QueuedConnection);
    });
}

void SimulationController::startSweep(const ModelSettings& settings, const SweepOptions& options) {
    cancel(JobKind::Sweep);
    quint64 gen = 0;
    auto token = beginJob(JobKind::Sweep, gen);
    auto lastShown = std::make_shared<std::atomic<int>>(-1);
    QtConcurrent::run(&pool_, [this, token, gen, settings, options, lastShown]() {
        QElapsedTimer clock;
        clock.start();
        SweepOutcome out;
        out.generation = gen;
        out.settings = settings;
        out.options = options;
        const auto laws = settings.laws();
        for (size_t i = 0; i < laws.size(); ++i) {
            RunControl ctl;
            ctl.cancel = token.get();
            // Overall fraction over the laws; reported in whole per mille to keep the queue short.
            ctl.progress = [this, i, n = laws.size(), lastShown](double f) {
                const int pm = static_cast<int>((i + f) / n * 1000.0);
                if (lastShown->exchange(pm) == pm) return;
                QMetaObject::invokeMethod(this, [this, pm] { emit sweepProgress(pm / 1000.0); }, Qt::QueuedConnection);
            };
            out.results.emplace_back(laws[i], bifurcationSweep(settings.paramsFor(laws[i]), options, ctl));
            if (token->load()) break;
        }
        out.elapsed_ms = msSince(clock);
        const bool cancelled = token->load();
        QMetaObject::invokeMethod(
            this,
            [this, out = std::move(out), cancelled]() {
                const bool current = out.generation == slots_[int(JobKind::Sweep)].generation;
                jobReturned(JobKind::Sweep, out.generation, cancelled);
                // A cancelled sweep still reports what it finished (the dialog shows it);
                // one replaced by a newer sweep does not.
                if (current) emit sweepFinished(out);
            },
            Qt::QueuedConnection);
    });
}

void SimulationController::startMap(const ModelSettings& settings, const MapOptions& options) {
    cancel(JobKind::Map);
    quint64 gen = 0;
    auto token = beginJob(JobKind::Map, gen);
    auto lastShown = std::make_shared<std::atomic<int>>(-1);
    QtConcurrent::run(&pool_, [this, token, gen, settings, options, lastShown]() {
        QElapsedTimer clock;
        clock.start();
        MapOutcome out;
        out.generation = gen;
        out.settings = settings;
        out.options = options;
        RunControl ctl;
        ctl.cancel = token.get();
        ctl.progress = [this, lastShown](double f) {
            const int pm = static_cast<int>(f * 1000.0);
            if (lastShown->exchange(pm) == pm) return;
            QMetaObject::invokeMethod(this, [this, pm] { emit mapProgress(pm / 1000.0); }, Qt::QueuedConnection);
        };
        out.map = periodicityMap(settings.paramsFor(settings.laws().front()), options, ctl);
        out.elapsed_ms = msSince(clock);
        const bool cancelled = token->load();
        QMetaObject::invokeMethod(
            this,
            [this, out = std::move(out), cancelled]() {
                const bool current = out.generation == slots_[int(JobKind::Map)].generation;
                jobReturned(JobKind::Map, out.generation, cancelled);
                if (current) emit mapFinished(out);
            },
            Qt::QueuedConnection);
    });
}

void SimulationController::cancel(JobKind kind) {
    Slot& s = slots_[int(kind)];
    s.hasPending = false;
    if (s.busy && s.cancel && !s.cancel->exchange(true)) ++s.cancelledJobs;
}

void SimulationController::cancelAll() {
    for (int k = 0; k < kJobKinds; ++k) cancel(static_cast<JobKind>(k));
}

}  // namespace stickslip::gui
