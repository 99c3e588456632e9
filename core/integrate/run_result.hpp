// What a run returns: a status, a message and the samples it produced — never NaNs.
#pragma once

#include <atomic>
#include <functional>
#include <string>
#include <vector>

namespace stickslip {

// One output sample (per the issue: t, u, x, ẋ, V, F, F/t_N, α, stuck, plus slip rate).
struct Sample {
    double t_s = 0;             // time
    double stage_m = 0;         // u, stage displacement
    double slider_m = 0;        // x, slider displacement
    double sliderVel_mps = 0;   // ẋ
    double relVel_mps = 0;      // V = u̇ − ẋ
    double force_N = 0;         // F
    double ratio = 0;           // F / t_N
    double alpha = 0;           // α
    double slipRate_mps = 0;    // λ̇ = Δλ/Δt (0 while stuck)
    bool stuck = true;          // the last step was elastic
};

enum class RunStatus { Ok, Cancelled, Failed };
const char* toString(RunStatus);

struct RunStats {
    long steps = 0;             // time steps taken
    long lawIterations = 0;     // local return-map iterations, summed
    long newtonIterations = 0;  // global (slider) Newton iterations, summed
    long stuckSteps = 0;
};

// Once per forcing period over the recorded steps of a dynamics run whose step divides the
// period: the state at every whole period t = kT (the Poincaré section at phase 0, read by
// core/analysis/poincare.hpp sectionOfRun) and max |V| over every recorded step.
struct PeriodRecord {
    long stepsPerPeriod = 0;      // N = T/dt; 0: not recorded (prescribed set-up, or dt does not divide T)
    std::vector<Sample> samples;  // states at t = kT, k·N > transient steps, in time order
    double maxRelVel_mps = 0;     // max |V| over the recorded steps
};

struct RunResult {
    RunStatus status = RunStatus::Ok;
    std::string message;           // empty when Ok
    std::vector<Sample> samples;   // what was computed up to the end (or the failure/cancel)
    RunStats stats;
    PeriodRecord period;           // dynamics runs: once-per-period states (above)
    bool ok() const { return status == RunStatus::Ok; }
};

// The one cancel test of every long job (runs, fits, identify, the app's workers): a null flag
// means "cannot be cancelled". Relaxed: the flag orders nothing else, it is only polled.
inline bool cancelRequested(const std::atomic<bool>* flag) { return flag && flag->load(std::memory_order_relaxed); }

// Cooperative cancellation and progress. The run polls `cancel` every block of steps
// and returns what it has with RunStatus::Cancelled.
struct RunControl {
    const std::atomic<bool>* cancel = nullptr;
    std::function<void(double fraction)> progress;  // called from the running thread
    bool cancelled() const { return cancelRequested(cancel); }
    // When set, every output sample is handed here (on the running thread, in time order)
    // instead of being kept in RunResult::samples: a long run streamed to a file then holds
    // no samples in memory. The run's status, message and stats are still returned.
    std::function<void(const Sample&)> onSample;
    void output(std::vector<Sample>& samples, const Sample& s) const {
        if (onSample) onSample(s);
        else samples.push_back(s);
    }
};

}  // namespace stickslip
