// One entry point for a run as SimParams describe it, in either set-up.
#pragma once

#include "../params.hpp"
#include "dynamics.hpp"
#include "prescribed.hpp"
#include "run_result.hpp"

namespace stickslip {

// Dynamics: the spring–mass rig driven by u = A sin(ωt).
// Prescribed: the block with slip g(t) = A sin(ωt) (stage moving, slider held), sampled at
// the output interval and integrated with steps no larger than integration.dt_s; or, when
// `history` is given, that measured slip history.
RunResult simulate(const SimParams& p, const RunControl& ctl = {}, const SlipHistory* history = nullptr);

}  // namespace stickslip
