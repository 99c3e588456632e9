// Owns the computations behind the views; the GUI thread never computes.
//
// Kinds of job: Run (time series, loops, phase portrait, rig, spectrum, autocorrelation and,
// when the step divides the forcing period, the Poincaré section the run records), Poincaré
// section (only for the other settings), bifurcation Sweep, periodicity Map. At most one job of each kind is in
// flight. Parameter changes (Run and Poincaré) are throttled on the leading edge: a change
// starts its job at once when no job of that kind is in flight; while one is, changes are
// merged (the newest parameters win), the stale job is cancelled through its own
// std::atomic<bool> (the core's RunControl::cancel), and the newest request starts as soon
// as the cancelled job returns. Every job works on its own copy of the parameters; results
// come back as value types through queued signals.
//
// Progressive refinement: a Run job whose error-controlled tolerance is tighter than
// kPreviewTolerance first runs at kPreviewTolerance and posts that outcome (RunOutcome::preview)
// before it runs at the tolerance asked for. While a slider is dragged, the newer settings cancel
// the refinement and each change is drawn from its preview; once the drag stops, the refined run
// replaces the preview.
#pragma once

#include <QElapsedTimer>
#include <QFuture>
#include <QObject>
#include <QThreadPool>
#include <array>
#include <atomic>
#include <memory>

#include "job_results.hpp"

namespace stickslip::gui {

enum class JobKind { Run = 0, Poincare = 1, Sweep = 2, Map = 3 };
constexpr int kJobKinds = 4;

class SimulationController : public QObject {
    Q_OBJECT
public:
    // Tolerance of a Run job's first frame (see the header comment): its displacement error
    // (bench_core) is 1.8e-4 of max|x| on the bench set and 1.5e-3 on the Fig. 20 preset, about
    // one pixel of a plot 700 px tall, and the refined run replaces it once the drag stops.
    static constexpr double kPreviewTolerance = 1e-3;
    // Whether a Run job of these settings posts a preview first.
    static bool previewFirst(const ModelSettings& settings);

    explicit SimulationController(QObject* parent = nullptr);
    ~SimulationController() override;   // cancels every job and waits for it

    // Whether parameter changes also compute the Poincaré section in its own job when the run
    // cannot record it (costly for long runs).
    void setPoincareEnabled(bool on) { poincareEnabled_ = on; }
    // The run of these settings records the Poincaré section of the Poincaré view (phase 0,
    // settle = transient cycles, cycles as recorded): dynamics set-up, the step divides the
    // forcing period, whole numbers of transient and recorded cycles.
    static bool sectionFromRun(const ModelSettings& settings);

    bool isBusy(JobKind kind) const { return slots_[int(kind)].busy; }
    bool isIdle() const;
    // Jobs launched and jobs cancelled so far, per kind (tests, status).
    int launchedCount(JobKind kind) const { return slots_[int(kind)].launched; }
    int cancelledCount(JobKind kind) const { return slots_[int(kind)].cancelledJobs; }

public slots:
    // New parameters for the Run (and Poincaré) views.
    void requestRun(const stickslip::gui::ModelSettings& settings);
    // Start a sweep / map with these settings; one already running is cancelled first.
    void startSweep(const stickslip::gui::ModelSettings& settings, const stickslip::SweepOptions& options);
    void startMap(const stickslip::gui::ModelSettings& settings, const stickslip::MapOptions& options);
    void cancel(stickslip::gui::JobKind kind);
    void cancelAll();

signals:
    void runStarted(quint64 generation);
    void runFinished(const stickslip::gui::RunOutcome& outcome);
    void poincareFinished(const stickslip::gui::PoincareOutcome& outcome);
    void sweepProgress(double fraction);
    void sweepFinished(const stickslip::gui::SweepOutcome& outcome);
    void mapProgress(double fraction);
    void mapFinished(const stickslip::gui::MapOutcome& outcome);

private:
    struct Slot {
        std::shared_ptr<std::atomic<bool>> cancel;  // token of the job in flight
        bool busy = false;
        quint64 generation = 0;
        int launched = 0;
        int cancelledJobs = 0;
        bool hasPending = false;                    // Run/Poincaré: newer settings wait
    };
    void fire();                       // start pending jobs whose kind is free, cancel stale ones
    void launchRun(const ModelSettings& s);
    void launchPoincare(const ModelSettings& s);
    void jobReturned(JobKind kind, quint64 generation, bool wasCancelled);
    std::shared_ptr<std::atomic<bool>> beginJob(JobKind kind, quint64& generation);

    std::array<Slot, kJobKinds> slots_;
    ModelSettings pending_;
    QThreadPool pool_;
    bool poincareEnabled_ = true;
};

}  // namespace stickslip::gui

Q_DECLARE_METATYPE(stickslip::SweepOptions)
Q_DECLARE_METATYPE(stickslip::MapOptions)
