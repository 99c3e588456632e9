// How the runs behind a Poincaré section, a sweep value or a map cell are stepped (issue 15,
// item 4): N fixed steps per forcing period (dt = T/N, the paper's algorithm: every sample
// lands on a step), or, when the parameters ask for a tolerance (IntegrationParams::tolerance
// > 0, `--tolerance`), error-controlled steps (adaptive.hpp) with every sample taken at the
// exact forcing phase from the dense output, so no step has to divide the period.
#pragma once

#include "../integrate/adaptive.hpp"
#include "../integrate/dynamics.hpp"
#include "../params.hpp"
#include "poincare.hpp"

namespace stickslip {

struct SectionStepping {
    bool adaptive = false;
    long stepsPerPeriod = 1;   // fixed: N (also the nominal N reported by an adaptive section)
    double period_s = 0;       // forcing period T
    AdaptiveOptions options;   // adaptive: tolerance and step budget from the parameters

    // Adaptive when p.integration.tolerance > 0; N = stepsPerPeriodFor(p, requestedN) either way.
    static SectionStepping of(const SimParams& p, long requestedN);
    // The time of the section phase in the first cycle: round(phase/2π·N)·T/N (fixed, so that
    // samples land on steps) or phase/ω exactly (adaptive).
    double phaseTime(double phase_rad) const;
    // From s (at rest at t = 0) to the section phase.
    StepReport toPhase(const DynamicsModel& m, DynState& s, double phase_rad, const RunControl& ctl) const;
    // Discards `cycles` forcing periods (polls cancel).
    StepReport settle(const DynamicsModel& m, DynState& s, long cycles, const RunControl& ctl) const;
    // Discards `settle` periods, then samples `cycles` points one period apart (poincareSectionFrom
    // or poincareSectionAdaptive); s is left at the last sample.
    PoincareSection section(const DynamicsModel& m, DynState& s, long settle, long cycles,
                            const RunControl& ctl) const;
};

// The adaptive counterpart of poincareSectionFrom: the samples are the dense output at exactly
// s.t + kT (k = 1 … cycles after the settled cycles); stickFraction is the fraction of sampled
// time stuck, slipSteps the accepted steps that slipped, maxRelVel the largest |V| at a step end.
PoincareSection poincareSectionAdaptive(const DynamicsModel& m, DynState& s, double period_s, long settle,
                                        long cycles, const AdaptiveOptions& o, const RunControl& ctl = {});

}  // namespace stickslip
