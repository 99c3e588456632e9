// The identification jobs of the Identify panel (issues 5 and 6) and the value types they
// return. The pipeline is the one `stickslip-cli fit` and `stickslip-cli identify` run:
// loaded runs -> preprocessRun -> fitDataset (per law) / makeIdentifyRun -> identifyEffects,
// so the GUI and the CLI give the same numbers for the same settings. Jobs run on the
// worker's own thread pool with a cancel token; progress and results reach the GUI thread
// through queued calls, as value types.
#pragma once

#include <QMetaType>
#include <QObject>
#include <QString>
#include <QThreadPool>
#include <atomic>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/identify/fit.hpp"
#include "core/identify/identify.hpp"
#include "core/identify/preprocess.hpp"
#include "core/io/dataset.hpp"

namespace stickslip::gui {

// Measured runs as the panel holds them.
struct MeasuredRuns {
    io::Dataset data;                          // every loaded run, in recording order
    std::vector<bool> validation;              // per run: held out (scored, never fitted)
    SetupKind setup = SetupKind::Prescribed;
    identify::PreprocessSettings pre;
    size_t fitCount() const;
    size_t validationCount() const;
};

// Dynamics when the first run has a slider displacement (as the CLI decides without --setup).
SetupKind guessSetup(const io::Dataset& data);

// Cleans the runs the way the CLI does; every run needs a known t_N. `validation` selects
// which runs go where. False with a message naming the file otherwise.
// `cancel` is polled between runs (false with the message "cancelled").
bool cleanRuns(const MeasuredRuns& runs, std::vector<identify::CleanRun>& fit, std::vector<identify::CleanRun>& validation,
               std::string* error, const std::atomic<bool>* cancel = nullptr);

// Measured and predicted force of one run at the scored samples.
struct RunOverlay {
    std::string file, role;
    std::vector<double> t_s, measured_N, predicted_N;
    std::vector<double> slip_m, relVel_mps;  // at the same samples (diagnostics)
};

struct LawFit {
    LawKind law = LawKind::RateState;
    identify::DatasetFit fit;
    std::vector<RunOverlay> overlays;  // fit runs first, then validation runs (as fit.runs)
    identify::Diagnostics diagnostics; // of the fit runs' residuals (measured − predicted)
};

struct FitRequest {
    MeasuredRuns runs;
    std::vector<LawKind> laws = {LawKind::RateState};  // one, or rate-state and Coulomb side by side
    identify::DatasetFitSettings settings;             // cancel and progress are set by the job
    double splitTime = 0.0;                            // in (0, 1): hold out the later part of every fit window
};

struct FitOutcome {
    quint64 id = 0;
    bool ok = false;
    bool cancelled = false;
    QString message;               // why it failed
    FitRequest request;            // what was run (the settings, for the report)
    std::vector<LawFit> fits;      // in request.laws order
    nlohmann::json cleanedRuns = nlohmann::json::array();  // identify::cleanRunSummary per run, fitted then held out
    double elapsed_ms = 0;
};

struct IdentifyRequest {
    MeasuredRuns runs;
    identify::IdentifyOptions options;  // cancel and progress are set by the job
};

struct IdentifyOutcome {
    quint64 id = 0;
    bool ok = false;
    bool cancelled = false;
    QString message;
    IdentifyRequest request;
    identify::IdentifyResult result;
    nlohmann::json cleanedRuns = nlohmann::json::array();  // identify::cleanRunSummary per run, fitted then held out
    double elapsed_ms = 0;
};

using JobProgress = std::function<void(double fraction, const std::string& stage)>;

// The jobs themselves (pure functions of the request; run on any thread).
FitOutcome runFitJob(const FitRequest& request, const std::atomic<bool>* cancel, const JobProgress& progress);
IdentifyOutcome runIdentifyJob(const IdentifyRequest& request, const std::atomic<bool>* cancel,
                               const JobProgress& progress);

// Reports. The fit report has the keys of `stickslip-cli fit --report`; the identify report
// is identify::toJson(result) plus the preprocessing, as `stickslip-cli identify --report`.
nlohmann::json fitReportJson(const FitOutcome& outcome);
nlohmann::json identifyReportJson(const IdentifyOutcome& outcome);

// Runs one job at a time on its own thread; a new job cancels the running one.
class IdentifyWorker : public QObject {
    Q_OBJECT
public:
    explicit IdentifyWorker(QObject* parent = nullptr);
    ~IdentifyWorker() override;  // cancels and waits

    quint64 startFit(const FitRequest& request);
    quint64 startIdentify(const IdentifyRequest& request);
    void cancel();
    bool isBusy() const { return busy_; }
    // Blocks until no job runs (tests, shutdown).
    void waitForDone();

signals:
    void progress(double fraction, const QString& stage);
    void fitFinished(const stickslip::gui::FitOutcome& outcome);
    void identifyFinished(const stickslip::gui::IdentifyOutcome& outcome);

private:
    JobProgress progressSink(quint64 id);
    template <class Request, class Outcome>
    quint64 launch(const Request& request, Outcome (*job)(const Request&, const std::atomic<bool>*, const JobProgress&),
                   void (IdentifyWorker::*finished)(const Outcome&));
    QThreadPool pool_;
    std::shared_ptr<std::atomic<bool>> cancel_;
    quint64 lastId_ = 0;
    bool busy_ = false;
};

}  // namespace stickslip::gui

Q_DECLARE_METATYPE(stickslip::gui::FitOutcome)
Q_DECLARE_METATYPE(stickslip::gui::IdentifyOutcome)
