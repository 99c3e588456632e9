#include "presets.hpp"

namespace stickslip {

namespace {

// The Fig. 20 set: t_N = 6.2 N, k = 8446 N/m, f = 3 Hz, μ = C1 = 0.25, r = 1, η = 0.6 s/m,
// D_c = 20 µm, v_c = 0.1 m/s; m* = 0.53 kg, 0.5 % damping; ε_T = 1e6 N/m ("as large as practical").
SimParams fig20Base() {
    SimParams p;
    p.drive.amplitude_m = 1.0e-3;
    p.drive.frequency_Hz = 3.0;
    p.rig.normalForce_N = 6.2;
    p.rig.stiffness_N_per_m = 8446.0;
    p.rig.mass_kg = 0.53;
    p.rig.damping_Ns_per_m = dampingFromRatio(0.005, p.rig.stiffness_N_per_m, p.rig.mass_kg);
    p.lawParams<RateStateParams>() = RateStateParams{};
    p.lawParams<CoulombParams>() = CoulombParams{};
    p.integration.dt_s = p.drive.period() / 10000.0;
    p.integration.outputInterval_s = 5.0e-4;
    p.cycles = 20;
    p.transientCycles = 0;
    return p;
}

SimParams prescribedSet(double eta, double vc, double tN, double A, double f) {
    SimParams p = fig20Base();
    p.setup = SetupKind::Prescribed;
    p.lawParams<RateStateParams>().eta_s_per_m = eta;
    p.lawParams<RateStateParams>().vc_mps = vc;
    p.rig.normalForce_N = tN;
    p.drive.amplitude_m = A;
    p.drive.frequency_Hz = f;
    p.integration.dt_s = p.drive.period() / 10000.0;
    p.integration.outputInterval_s = p.drive.period() / 400.0;
    p.cycles = 5;
    return p;
}

}  // namespace

std::vector<Preset> builtinPresets() {
    std::vector<Preset> v;
    v.push_back({"default", "Fig. 20 set at A = 1 mm, rate-state law, eps_T = 1e6 N/m", fig20Base()});
    v.push_back({"fig16",
                 "Fig. 16: block with prescribed harmonic slip, 3 Hz, A = 1 mm; eta = 0.8 s/m, v_c = 0.1 m/s",
                 prescribedSet(0.8, 0.1, 6.2, 1.0e-3, 3.0)});
    v.push_back({"fig17", "Fig. 17c: clockwise F/t_N-V loops, prescribed slip; eta = 1.1 s/m, v_c = 0.05 m/s, t_N = 4.2 N",
                 prescribedSet(1.1, 0.05, 4.2, 1.0e-3, 3.0)});
    v.push_back({"fig18", "Fig. 18d: prescribed slip, A = 1.92 mm; eta = 1.0 s/m, v_c = 0.1 m/s",
                 prescribedSet(1.0, 0.1, 6.2, 1.92e-3, 3.0)});
    {
        SimParams p = fig20Base();
        p.rig.stiffness_N_per_m = 3034.0;
        p.rig.normalForce_N = 6.3;
        p.rig.damping_Ns_per_m = dampingFromRatio(0.005, p.rig.stiffness_N_per_m, p.rig.mass_kg);
        p.lawParams<RateStateParams>().epsT_N_per_m = p.lawParams<CoulombParams>().epsT_N_per_m = 1.1e4;
        v.push_back({"fig19", "Fig. 19d: k = 3034 N/m, t_N = 6.3 N (sweep A; also k = 1547, 410); eps_T = 1.1e4 N/m", p});
    }
    {
        SimParams p = fig20Base();
        p.lawParams<RateStateParams>().epsT_N_per_m = p.lawParams<CoulombParams>().epsT_N_per_m = 1.1e4;
        v.push_back({"fig20",
                     "Fig. 20: t_N = 6.2 N, k = 8446 N/m, f = 3 Hz, A = 1 mm (sweep A 0.1-5 mm); eps_T = 1.1e4 N/m "
                     "gives the paper's 0.33 mm stick threshold",
                     p});
    }
    {
        SimParams p = fig20Base();
        p.drive.amplitude_m = 0.40e-3;
        p.lawParams<RateStateParams>().epsT_N_per_m = p.lawParams<CoulombParams>().epsT_N_per_m = 1.1e4;
        p.transientCycles = 60;
        p.cycles = 80;
        v.push_back({"fig22", "Fig. 22: A = 0.40 mm just past the stick threshold (phase portrait, Poincare, spectrum)", p});
    }
    {
        SimParams p = fig20Base();
        p.drive.amplitude_m = 4.0e-3;
        p.lawParams<RateStateParams>().eta_s_per_m = 0.2;
        p.transientCycles = 60;
        p.cycles = 80;
        v.push_back({"fig23", "Fig. 23: eta = 0.2 s/m, A = 4 mm: irregular motion at large amplitude; eps_T = 1e6 N/m", p});
    }
    return v;
}

bool findPreset(const std::string& name, Preset& out) {
    for (auto& p : builtinPresets()) {
        if (p.name == name) {
            out = p;
            return true;
        }
    }
    return false;
}

}  // namespace stickslip
