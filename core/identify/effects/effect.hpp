// What every missing-effect candidate declares: its name (as the report uses it), a
// one-paragraph physical description, its residual signature, its parameters with units and
// physical bounds, and the diagnostic signals that point to it. The physics of each effect
// is a small value type in its own file; effects/registry.hpp registers them in one place.
#pragma once

#include <functional>
#include <limits>
#include <map>
#include <string>
#include <vector>

namespace stickslip::identify {

// One parameter of an effect, in physical units.
struct EffectParam {
    std::string name;      // e.g. "tau_s"
    std::string unit;      // e.g. "s"
    double initial = 0;    // starting value of a fit (the effect then changes little)
    double lower = 0;      // physical lower bound
    double upper = 1;      // physical upper bound
    bool logScale = false; // positive scale parameter: fitted on a log scale
    // Value at which the effect vanishes (the size parameter, params[0], only): identify
    // credits an effect only if its size differs from this by more than its honest
    // uncertainty. +infinity (a stiffness): the test is made on the compliance 1/value.
    double vanishing = 0;
    // A coefficient in units of μ (a shift of the friction coefficient, per unit of something):
    // its start and bounds are multiplied by max(1, |μ̂|) of the baseline, since a device whose
    // reference load is not the normal force (a band tension) has μ, and every shift of it,
    // "per unit reference load" (μ̂ = 77 on the friction damper).
    bool muUnits = false;
    // The baseline parameter this one continues beyond its baseline range (viscous_damping's ζ
    // continues the rig's ζ): the candidate fit starts from the baseline's value, where the
    // two models agree, instead of `initial`.
    const char* continues = nullptr;
};

// Which set-ups an effect can act in.
struct EffectSetups {
    bool prescribed = true;  // friction force predicted from the measured slip history
    bool dynamics = true;    // spring–mass rig (Eq. 8) driven by the stage
};

// What the fitted runs contain, for an effect whose size is judged where the runs put it.
struct OperatingPoint {
    // Median duration, weighted by duration, of the fit runs' stick episodes that begin after a
    // slip and end in one [s]; NaN without such an episode.
    double stickDuration_s = std::numeric_limits<double>::quiet_NaN();
};

// The quantity identify's size test judges (IdentifyOptions, test 3). Unset, it is the first
// parameter. An effect whose first parameter trades off with another in what the runs show
// (the healing's rate b against its age scale t_c: a larger b with a larger t_c gives the same
// breakaway after the sticks the runs contain) sets it to what the runs do identify: a function
// of its parameters (names without the effect's prefix) at the runs' operating point, vanishing
// at 0. A non-finite value (no operating point) falls back to the first parameter.
struct EffectSize {
    std::string name;  // as the report shows it
    std::function<double(const std::map<std::string, double>&, const OperatingPoint&)> value;
};

// p[name], NaN when p does not have it (a refit that gave no values): an EffectSize never throws.
inline double paramOr(const std::map<std::string, double>& p, const std::string& name) {
    const auto it = p.find(name);
    return it != p.end() ? it->second : std::numeric_limits<double>::quiet_NaN();
}

struct EffectInfo {
    std::string name;                    // catalogue name, e.g. "frictional_lag"
    std::string description;             // one paragraph of physics
    std::string signature;               // what it leaves in the residual of a model without it
    std::vector<EffectParam> params;     // the first one sets the size of the effect (identify checks it is not on a bound)
    std::vector<std::string> pointers;   // diagnostic signals (names in diagnostics.hpp) that point to it
    EffectSetups setups;
    EffectSize size = {};                // unset: params.front() is the size
};

}  // namespace stickslip::identify
