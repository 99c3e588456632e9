// A short real run for the widget tests: the Fig. 20 set at A = 1 mm, 3 cycles, T/2000 steps,
// output every T/200.
#pragma once

#include "core/integrate/simulate.hpp"
#include "core/presets.hpp"

namespace stickslip::testing {

inline SimParams shortParams(LawKind law) {
    Preset p;
    findPreset("fig20", p);
    SimParams s = p.params;
    s.law = law;
    s.integration.dt_s = s.drive.period() / 2000.0;
    s.integration.outputInterval_s = s.drive.period() / 200.0;
    s.cycles = 3;
    return s;
}

inline RunResult shortRun(LawKind law) { return simulate(shortParams(law)); }

}  // namespace stickslip::testing
