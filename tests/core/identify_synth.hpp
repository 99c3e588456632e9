// Synthetic measured runs for the identify tests, made with the project's own extended model
// (prescribed slip, Fig. 15a) with one effect switched on, plus force noise.
#pragma once

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "core/identify/identify.hpp"

namespace synth {

using namespace stickslip;
using namespace stickslip::identify;

inline ExtendedModel trueModel() {
    ExtendedModel m;
    m.law.mu = 0.30; m.law.C1 = 0.20; m.law.eta_s_per_m = 0.8; m.law.vc_mps = 0.1; m.law.Dc_m = 20e-6;
    m.law.epsT_N_per_m = 1e6;
    // The state advanced exactly per step (extended_model.hpp, StateStep): the runs stand for the
    // law itself, not for backward Euler's error at their 0.25 ms steps.
    m.stateStep = StateStep::ConstantRate;
    return m;
}

struct RunConfig { double A, f, tN; };

// One run per configuration, in recording order (wear accumulates over them), of a slip history
// with dwells at the turning points: g = A clip(1.4 sin ωt, −1, 1), 1 kHz, `seconds` long, force
// noise σ = noise_N; the load reference is the mean t_N (as the loop's).
inline std::vector<IdentifyRun> makeRunsFrom(const ExtendedModel& truth, const std::vector<RunConfig>& cfgs, double seconds,
                                             double noise_N, unsigned seed) {
    std::mt19937 rng(seed);
    std::normal_distribution<double> nd(0.0, 1.0);
    std::vector<IdentifyRun> runs;
    double slip = 0, tNsum = 0;
    for (const RunConfig& c : cfgs) tNsum += c.tN;
    ExtendedModel m = truth;
    m.tNref_N = tNsum / static_cast<double>(cfgs.size());
    int k = 0;
    for (const RunConfig& c : cfgs) {
        IdentifyRun r;
        r.file = "synthetic_run_" + std::to_string(++k);
        r.setup = SetupKind::Prescribed;
        r.normalForce_N = c.tN;
        r.frequency_Hz = c.f;
        const double w = 2 * M_PI * c.f;
        for (double t = 0; t < seconds; t += 1e-3) {
            r.t_s.push_back(t);
            const double s = 1.4 * std::sin(w * t);
            r.slip_m.push_back(c.A * std::clamp(s, -1.0, 1.0));
            r.relVel_mps.push_back(std::abs(s) < 1.0 ? 1.4 * c.A * w * std::cos(w * t) : 0.0);
            r.accel_mps2.push_back(std::abs(s) < 1.0 ? -1.4 * c.A * w * w * std::sin(w * t) : 0.0);
        }
        const ExtendedTrace tr = simulateExtendedPrescribed(m, {c.tN, slip}, r.t_s, r.slip_m, &r.accel_mps2, 4);
        slip = tr.accumulatedSlipEnd_m;
        r.force_N = tr.measuredForce_N;
        for (double& f : r.force_N) f += noise_N * nd(rng);
        runs.push_back(std::move(r));
    }
    return runs;
}

// Four runs whose A, f and t_N differ.
inline std::vector<IdentifyRun> makeRuns(const ExtendedModel& truth, double seconds, double noise_N, unsigned seed) {
    return makeRunsFrom(truth, {{2e-3, 2.0, 5.0}, {3e-3, 1.5, 8.0}, {1.5e-3, 3.0, 11.0}, {2.5e-3, 2.5, 6.5}}, seconds, noise_N,
                        seed);
}

inline IdentifyOptions testOptions() {
    IdentifyOptions o;
    o.decimate = 2;
    o.substeps = 2;
    o.maxEffects = 1;  // the first effect the loop adds is the one under test
    o.multistarts = 1;
    // The contact stiffness ε_T and the state distance D_c held at the truth (the runs are made
    // with the defaults): these tests check the selection of one effect on a known contact. With
    // D_c free a frictional lag at one speed profile trades off against the state relaxation
    // over D_c, and a series compliance is ε_T itself (tst_identify_contact).
    o.freeLaw = {"mu", "C1", "eta", "vc"};
    return o;
}

}  // namespace synth
