// Poincaré section (paper Figs 12, 13, 22, 23): one sample per forcing period at a chosen
// phase, (slider displacement x, relative velocity V, F/t_N), plus per-run motion measures
// gathered over the sampled cycles (stick fraction, max |V|).
//
// The step is dt = T/N with N steps per period, so every sample lands exactly on a step
// (no interpolation): the section is the N-fold iterate of the discrete map.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "../integrate/dynamics.hpp"
#include "../params.hpp"

namespace stickslip {

struct PoincareOptions {
    long stepsPerPeriod = 0;   // N: dt = T/N; 0 = round(T / params.integration.dt_s)
    double phase_rad = 0.0;    // section phase within the forcing cycle [rad], in [0, 2π)
    long settleCycles = 50;    // forcing cycles simulated and discarded first [-]
    long cycles = 100;         // sampled cycles = number of section points [-]
    ParamIssues validate() const;
};

struct PoincareSection {
    double period_s = 0;                // forcing period T [s]
    std::vector<double> t_s;            // sample times [s]
    std::vector<double> slider_m;       // x at the section [m]
    std::vector<double> relVel_mps;     // V = u̇ − ẋ at the section [m/s]
    std::vector<double> ratio;          // F / t_N at the section [-]
    std::vector<double> alpha;          // α at the section [-]
    double stickFraction = 0;           // fraction of sampled steps that were stuck (elastic) [-]
    double maxRelVel_mps = 0;           // max |V| over every sampled step [m/s]
    long slipSteps = 0;                 // sampled steps that slipped
    RunStatus status = RunStatus::Ok;
    std::string message;                // why the run stopped early (status != Ok)
    std::size_t size() const { return slider_m.size(); }
    bool ok() const { return status == RunStatus::Ok; }
};

// N steps per forcing period: `requested` if > 0, else round(T / p.integration.dt_s) (≥ 1).
long stepsPerPeriodFor(const SimParams& p, long requested);

// The dynamics model of p with dt = T / stepsPerPeriod (harmonic stage only).
DynamicsModel poincareModel(const SimParams& p, long stepsPerPeriod);

// From rest at t = 0: advance to the section phase, discard settleCycles, then sample
// `cycles` points. Validates p and the options first (Failed with every issue listed).
// Progress is the fraction of cycles done.
PoincareSection poincareSection(const SimParams& p, const PoincareOptions& opt, const RunControl& ctl = {});

// The phase-0 section a dynamics run recorded (RunResult::period, when its step divides the
// period): the same points and motion measures as poincareSection with phase 0,
// settleCycles = transientCycles and cycles = cycles (both whole numbers), without simulating
// again. Empty with status Failed and a message when the run recorded no period states;
// a cancelled or failed run gives what it recorded, with its status and message.
PoincareSection sectionOfRun(const RunResult& run, double period_s);

// Continue from a prepared model and state (continuation sweeps): discard settleCycles,
// then sample `cycles` points; `s` is left at the last sample. Assumes the model's dt
// divides the period into stepsPerPeriod steps and that `s` sits on the section phase.
PoincareSection poincareSectionFrom(const DynamicsModel& m, DynState& s, long stepsPerPeriod, long settleCycles,
                                    long cycles, const RunControl& ctl = {});

}  // namespace stickslip

namespace stickslip::detail {
// Advance one forcing period (n steps), accumulating the section's motion measures
// (stuck steps, slip steps, max |V|) and appending the end state as a section point.
StepReport advanceSampledCycle(const DynamicsModel& m, DynState& s, long n, PoincareSection& out, long& stuckSteps,
                               const RunControl& ctl);
// Append the state as a section point.
void appendSectionPoint(const DynamicsModel& m, const DynState& s, PoincareSection& out);
// Advance `cycles` periods of n steps without recording; polls cancel; returns the first non-Ok report.
StepReport settleCycles(const DynamicsModel& m, DynState& s, long n, long cycles, const RunControl& ctl);
// Steps from t = 0 to the section phase: round(phase / 2π · n) mod n.
long phaseOffsetSteps(double phase_rad, long n);
}  // namespace stickslip::detail
