// The `fit` and `identify` pipelines from option text to report: load the measured runs
// (column mapping, units, manifest, run settings, set-up), clean them, fit or identify, and
// build the JSON report. One implementation for every front end (stickslip-cli fit/identify,
// the Python module), so the same options give the same report.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "../io/dataset.hpp"
#include "fit.hpp"
#include "identify.hpp"
#include "preprocess.hpp"

namespace stickslip::identify {

// How a pipeline ended; front ends map it to exit codes or exceptions.
enum class PipelineCode { Ok, BadArguments, BadInput, RunFailed, Cancelled };

struct PipelineStatus {
    PipelineCode code = PipelineCode::Ok;
    std::string message;
    bool ok() const { return code == PipelineCode::Ok; }
};

// The measured runs: data (fitted), validateOn (held out), "SIGNAL=COLUMN" mappings, "SIGNAL=UNIT"
// units, "FILE:KEY=VALUE" run settings, manifest path; setup "" = dynamics when the runs have a
// slider displacement, else prescribed.
struct MeasuredInputs {
    std::vector<std::string> data, validateOn, columns, units, runSets;
    std::string manifest, setup;
};

bool loadMeasuredInputs(const MeasuredInputs& in, io::Dataset& fitData, io::Dataset& valData, SetupKind& setup,
                        PipelineStatus& status);

// Preprocessing settings with the three switches applied.
struct CleaningOptions {
    PreprocessSettings pre;
    bool noBandStop = false, noLowPass = false, noSteadyTrim = false;
    PreprocessSettings effective() const;
};

// One cleaned run for a report's preprocessing.runs[]: its file, sample rate, fit window,
// drive period, whether it was resampled, the cleaning notes (what each step did, with the
// levels it estimated) and its settings with their sources.
nlohmann::json cleanRunSummary(const CleanRun& c, const std::string& file);

// "a,b,,c" -> {"a", "b", "c"} (spaces dropped).
std::vector<std::string> splitList(const std::string& s);

struct FitRequest {
    MeasuredInputs in;
    CleaningOptions cleaning;
    std::string model = "rate-state";     // rate-state, coulomb or both
    std::string free = "mu,eta,Dc,vc,epsT";
    std::vector<std::string> sets;        // "KEY=VALUE" start (or fixed) values; zeta as a number
    double splitTime = 0.0;               // hold out the last (1 - F) of every fit window (0 = off)
    bool noFilterPrediction = false;
    PredictSettings predict;
    int multistarts = 3, maxIterations = 40, agreeingStarts = 2;
    std::string initialState = "fitted";  // measured or fitted
    double relativeStep = 1e-4;
    bool jackknife = false;
    std::string coordinates = "curve";    // curve or plain
    std::string robust = "none";          // none, huber or cauchy
    double robustScale = 1.0;
    uint64_t seed = 20260101;
    const std::atomic<bool>* cancel = nullptr;
    std::function<void(const std::string&)> log;  // one progress line per call (may be empty)
};

struct FitOutcome {
    nlohmann::json report;                 // what `stickslip-cli fit --report` writes
    SetupKind setup = SetupKind::Prescribed;
    std::vector<CleanRun> fitRuns, validationRuns;
    DatasetFitSettings settings;
    std::vector<DatasetFit> fits;          // one per law, in the order of `model`
};

bool runFitRequest(const FitRequest& req, FitOutcome& out, PipelineStatus& status);

// The fit of each law in turn to cleaned runs (fitDataset), the loop `fit` and the app's Fit tab
// share. `st` as fitDataset takes it (its law is set per fit; its progress, when set, is mapped
// onto the whole loop); `fitted(i, fit)` is called after each successful fit, `log` gets one line
// before and after each. Stops at the first failure: status RunFailed, or Cancelled when
// st.cancel is set.
bool fitLaws(const std::vector<CleanRun>& fitRuns, const std::vector<CleanRun>& validationRuns, DatasetFitSettings st,
             const std::vector<LawKind>& laws, std::vector<DatasetFit>& out, PipelineStatus& status,
             const std::function<void(const std::string&)>& log = {},
             const std::function<void(size_t, const DatasetFit&)>& fitted = {});

struct IdentifyRequest {
    MeasuredInputs in;
    CleaningOptions cleaning;
    std::string free = "mu,C1,eta,Dc,vc,epsT";
    std::string dynamicsResidual = "equation-error";  // auto, equation-error or segments
    std::vector<std::string> candidates;              // empty = the whole catalogue
    // Recovery self-test (self_test.hpp): on when selfTest; sizes as EFFECT=VALUE (SI units).
    bool selfTest = false;
    int selfTestReplicas = 20;
    std::vector<double> selfTestLevels = {0.5};
    std::vector<std::string> selfTestSizes;
    IdentifyOptions options;                          // freeLaw, candidates, dynamicsResidual, selfTest are set from the above
};

// `report` is what `stickslip-cli identify --report` writes.
bool runIdentifyRequest(const IdentifyRequest& req, IdentifyResult& result, nlohmann::json& report,
                        PipelineStatus& status);

}  // namespace stickslip::identify
