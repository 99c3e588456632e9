// Results of the controller's jobs: value types that travel from the worker threads to the
// GUI thread through queued signals (registered with qRegisterMetaType in main/tests).
#pragma once

#include <QMetaType>
#include <vector>

#include "core/analysis/periodicity_map.hpp"
#include "core/analysis/poincare.hpp"
#include "core/analysis/sweep.hpp"
#include "core/integrate/run_result.hpp"
#include "model_settings.hpp"

namespace stickslip::gui {

// One law's run and what is derived from it on the worker.
struct ModelRun {
    LawKind law = LawKind::RateState;
    RunResult run;
    std::vector<double> spectrumFreq_Hz, spectrumPsd;  // PSD of the slider displacement x
    std::vector<double> acfLag_s, acf;                 // normalised autocorrelation of x
    PoincareSection section;   // phase-0 section recorded by the run (RunOutcome::sectionInRun)
};

struct RunOutcome {
    quint64 generation = 0;
    ModelSettings settings;      // what was run
    std::vector<ModelRun> runs;  // primary law first
    // The Poincaré section comes with the runs (ModelRun::section; the step divides the
    // forcing period): no separate Poincaré job for these settings.
    bool sectionInRun = false;
    double elapsed_ms = 0;       // wall time of the job on the worker
    double cpu_ms = 0;           // CPU time of the job's own thread (the overlaid law's thread not counted)
    // A first frame at SimulationController::kPreviewTolerance, shown while the run at the
    // requested (tighter) tolerance is computed; `settings.tolerance` is the preview's, and
    // `requestedTolerance` the one the refined run of the same job will have.
    bool preview = false;
    double requestedTolerance = 0;
    bool ok() const;
    QString failureText() const;  // every failed run's message, in words ("" if all ok)
};

struct PoincareOutcome {
    quint64 generation = 0;
    ModelSettings settings;
    std::vector<std::pair<LawKind, PoincareSection>> sections;
    double elapsed_ms = 0;
};

struct SweepOutcome {
    quint64 generation = 0;
    ModelSettings settings;
    SweepOptions options;
    std::vector<std::pair<LawKind, SweepResult>> results;
    double elapsed_ms = 0;
    bool cancelled() const;
};

struct MapOutcome {
    quint64 generation = 0;
    ModelSettings settings;
    MapOptions options;
    PeriodicityMap map;
    double elapsed_ms = 0;
};

}  // namespace stickslip::gui

Q_DECLARE_METATYPE(stickslip::gui::RunOutcome)
Q_DECLARE_METATYPE(stickslip::gui::PoincareOutcome)
Q_DECLARE_METATYPE(stickslip::gui::SweepOutcome)
Q_DECLARE_METATYPE(stickslip::gui::MapOutcome)
