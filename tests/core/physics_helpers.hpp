// Small helpers shared by the verification tests in tests/core/ (header-only, Qt-free).
#pragma once

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "core/integrate/run_result.hpp"
#include "core/params.hpp"

namespace stickslip::testing {

// The paper's Fig. 20 set (MODEL.md) at A = 1 mm, ε_T = 1e6 N/m, 0.5 % damping, dt = T/10 000.
inline SimParams fig20Params() {
    SimParams p;
    p.drive.amplitude_m = 1.0e-3;
    p.drive.frequency_Hz = 3.0;
    p.rig.normalForce_N = 6.2;
    p.rig.stiffness_N_per_m = 8446.0;
    p.rig.mass_kg = 0.53;
    p.rig.damping_Ns_per_m = dampingFromRatio(0.005, p.rig.stiffness_N_per_m, p.rig.mass_kg);
    p.lawParams<RateStateParams>() = RateStateParams{};
    p.lawParams<RateStateParams>().epsT_N_per_m = 1.0e6;
    p.lawParams<CoulombParams>() = CoulombParams{};
    p.lawParams<CoulombParams>().epsT_N_per_m = 1.0e6;
    p.integration.dt_s = p.drive.period() / 10000.0;
    p.integration.outputInterval_s = p.drive.period() / 100.0;
    p.cycles = 20;
    p.transientCycles = 0;
    return p;
}

// fig20Params with the given law (Coulomb or rate-state) over `cycles` forcing cycles.
inline SimParams lawParams(bool coulomb, double cycles) {
    SimParams p = fig20Params();
    p.law = coulomb ? LawKind::Coulomb : LawKind::RateState;
    p.cycles = cycles;
    return p;
}

inline bool sampleFinite(const Sample& s) {
    return std::isfinite(s.t_s) && std::isfinite(s.stage_m) && std::isfinite(s.slider_m) &&
           std::isfinite(s.sliderVel_mps) && std::isfinite(s.relVel_mps) && std::isfinite(s.force_N) &&
           std::isfinite(s.ratio) && std::isfinite(s.alpha) && std::isfinite(s.slipRate_mps);
}

inline bool allFinite(const std::vector<Sample>& v) {
    return std::all_of(v.begin(), v.end(), sampleFinite);
}

inline double relDiff(double a, double b) {
    const double s = std::max(std::abs(a), std::abs(b));
    return s > 0.0 ? std::abs(a - b) / s : 0.0;
}

// Independent closed form of Eq. 5 (written out here, not taken from the law):
// |F|/t_N = μ + C1 (exp(−|V|/(v_c r)) − 1) + η |V|.
inline double eq5Ratio(const RateStateParams& p, double V) {
    const double a = std::abs(V);
    return p.mu + p.C1 * (std::exp(-a / (p.vc_mps * p.r)) - 1.0) + p.eta_s_per_m * a;
}

inline bool contains(const std::string& hay, const std::string& needle) { return hay.find(needle) != std::string::npos; }

}  // namespace stickslip::testing
