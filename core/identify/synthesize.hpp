// Rig-like synthetic data sets with a known answer, for checking the missing-effect loop on
// many sets instead of the few that were shared (a selection rule is judged by its
// false-alarm rate on sets without an effect and its detection rate on sets with one).
//
// A set imitates ../shared/data/synthetic/README.md: five runs of the spring–mass rig (Fig. 15b,
// Eq. 8) on one specimen, recorded in order (wear accumulates over them, pre-roll included),
// each at its own k, A, f and t_N; the model is this project's extended law (extended_model.hpp)
// integrated with a fine fixed step (Newmark + return map, `stepsPerSample` steps per recorded
// sample) and "measured" as point samples at `sampleRate_Hz` after a start-up transient of random
// length (so at an arbitrary stage phase), with white noise on every channel and 60 Hz / 180 Hz
// mains pickup of random phase on the two force channels. The baseline law and rig are drawn
// from ranges that cover the answer keys of the shared sets (SynthOptions::ranges); the runs'
// (k, A, f, t_N) from five classes of the same kind. Nothing here is read by the loop.
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "../params.hpp"
#include "extended_model.hpp"

namespace stickslip::identify {

// One closed interval [lo, hi] a value is drawn from (log-uniform when `log`).
struct DrawRange {
    double lo = 0, hi = 0;
    bool log = false;
};

// The baseline's ranges (the shared answer keys span about these; see synthesize.cpp).
struct SynthRanges {
    DrawRange mass_kg{0.50, 0.53}, zeta{0.005, 0.010};
    DrawRange mu{0.22, 0.30}, C1{0.20, 0.29}, Dc_m{1e-5, 4e-5}, eta_s_per_m{0.3, 0.95}, vc_mps{0.05, 0.20};
    DrawRange epsT_N_per_m{1e4, 1e6, true};
    DrawRange mains60_N{0.02, 0.08}, mains180_N{0.002, 0.023};
    DrawRange transient_s{2.5, 4.5};
};

struct SynthOptions {
    uint64_t seed = 1;
    int runs = 5;                    // 1..5: the first `runs` of the five classes, in shuffled order
    double seconds = 20.0;           // recorded length of a run [s]
    double sampleRate_Hz = 1000.0;   // recording rate [Hz]
    int stepsPerSample = 120;        // integration steps per recorded sample (h = 8.3 µs at 1 kHz)
    double dispNoise_m = 1e-5, forceNoise_N = 0.05, accelNoise_mps2 = 0.05;  // white noise, RMS
    // Multiplies every channel's noise and the mains pickup, in [0, 100]. The draws stay the same
    // (law, runs, noise sequence), only their size changes: 0 makes the noise-free twin of a set,
    // to tell what the loop does because of noise from what it does because of its model.
    double noiseScale = 1.0;
    double nominalMass_kg = 0.53;    // what the manifest states (the true mass is drawn)
    // Effects switched on: catalogue name and its parameters in catalogue order (effects/registry.hpp).
    std::vector<std::pair<std::string, std::vector<double>>> effects;
    SynthRanges ranges;
    // Field, value and allowed range of every violation; also an unknown effect, a wrong number of
    // parameters, or a value outside the effect's physical range.
    ParamIssues validate() const;
};

// One recorded run: the shared sets' columns.
struct SynthRun {
    std::string file;
    double k_N_per_m = 0, A_m = 0, f_Hz = 0, tN_N = 0;
    std::vector<double> t_s, stage_m, slider_m, force_N, normal_N, accel_mps2;
    double slipStart_m = 0, slipEnd_m = 0;  // accumulated on the specimen (wear_drift)
};

struct SynthResult {
    bool ok = false;
    std::string message;
    std::vector<SynthRun> runs;
    ExtendedModel truth;                    // baseline + effects (rig.mass_kg, ζ in `zeta`)
    double zeta = 0;
    nlohmann::json manifest;                // what an experimenter knows (k, A, f, t_N, nominal mass)
    nlohmann::json answer;                  // everything else: the drawn law, rig and effects
};

// Draws and simulates one set (deterministic in the options, seed included). Never throws.
SynthResult synthesizeRigSet(const SynthOptions& o);

// The CSV text of a run, in the shared sets' format (header, then one row per sample).
std::string synthRunCsv(const SynthRun& r);

}  // namespace stickslip::identify
