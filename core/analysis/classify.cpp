#include "classify.hpp"

#include "../friction/friction_law.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace stickslip {

const char* toString(MotionClass c) {
    switch (c) {
        case MotionClass::Stick: return "stick";
        case MotionClass::Periodic: return "periodic";
        case MotionClass::Irregular: return "irregular";
    }
    return "?";
}

ParamIssues ClassifyOptions::validate() const {
    ParamIssues out;
    if (maxPeriod < 1 || maxPeriod > 1000) out.push_back({"maxPeriod", double(maxPeriod), "in [1, 1000]"});
    if (!(relTol > 0 && relTol < 1)) out.push_back({"relTol", relTol, "in (0, 1)"});
    return out;
}

ClassifyScales classifyScales(const SimParams& p) {
    const double mu = lawMu(p);
    ClassifyScales sc;
    sc.x_m = std::max(std::abs(p.drive.amplitude_m), mu * p.rig.normalForce_N / p.rig.stiffness_N_per_m);
    sc.v_mps = sc.x_m * p.drive.omega();
    return sc;
}

Classification classifyMotion(const PoincareSection& s, const ClassifyScales& sc, const ClassifyOptions& opt) {
    Classification c;
    c.stickFraction = s.stickFraction;
    c.maxRelVel_mps = s.maxRelVel_mps;
    if (s.size() > 0 && s.slipSteps == 0) {
        c.motion = MotionClass::Stick;
        c.period = 1;
        return c;
    }
    const std::size_t n = s.size();
    const double tx = opt.relTol * sc.x_m, tv = opt.relTol * sc.v_mps;
    c.bestMismatch = std::numeric_limits<double>::infinity();
    for (int p = 1; p <= opt.maxPeriod; ++p) {
        // Need at least two full repetitions to call anything periodic.
        if (n < static_cast<std::size_t>(2 * p + 1)) break;
        double worst = 0;
        for (std::size_t i = 0; i + p < n; ++i) {
            worst = std::max(worst, std::abs(s.slider_m[i + p] - s.slider_m[i]) / tx);
            worst = std::max(worst, std::abs(s.relVel_mps[i + p] - s.relVel_mps[i]) / tv);
        }
        c.bestMismatch = std::min(c.bestMismatch, worst);
        if (worst <= 1.0) {
            c.motion = MotionClass::Periodic;
            c.period = p;
            return c;
        }
    }
    c.motion = MotionClass::Irregular;
    c.period = 0;
    return c;
}

}  // namespace stickslip
