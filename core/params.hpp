// Parameters of the rig, the drive, the friction laws and the integration, as named
// value types with SI units beside every field. Defaults are the paper's Fig. 20 set
// (../shared/MODEL.md). Every struct has validate() returning *all* violated fields.
#pragma once

#include <string>
#include <vector>

#include "friction/law_list.hpp"
#include "param_table.hpp"

namespace stickslip {


// Stage motion u(t) = A sin(2π f t + phase).
struct DriveParams {
    double amplitude_m = 1.0e-3;   // A, zero-to-peak stage amplitude [m]
    double frequency_Hz = 3.0;     // f, forcing frequency [Hz]
    double phase_rad = 0.0;        // initial stage phase [rad]
    ParamIssues validate() const;
    double omega() const;          // 2π f [rad/s]
    double period() const;         // 1/f [s]
};

// The 1-DOF slider (paper Fig. 15b, Eq. 8): m* ẍ + c ẋ + k x = F.
struct RigParams {
    double normalForce_N = 6.2;          // t_N, normal load [N]
    double stiffness_N_per_m = 8446.0;   // k, beam stiffness [N/m]
    double mass_kg = 0.53;               // m*, effective mass [kg]
    double damping_Ns_per_m = 0.669;     // c, viscous damping [N s/m] (≈ 0.5 % of critical)
    ParamIssues validate() const;
    double naturalFrequency_rad_s() const;   // sqrt(k/m)
    double dampingRatio() const;             // c / (2 sqrt(k m))
};

// c for a given damping ratio ζ: c = 2 ζ sqrt(k m).
double dampingFromRatio(double zeta, double stiffness_N_per_m, double mass_kg);

struct IntegrationParams {
    double dt_s = 1.0 / 30000.0;            // time step [s] (T/10 000 at 3 Hz)
    double outputInterval_s = 5.0e-4;       // output sample spacing [s]; rounded to a multiple of dt
    // Step budget of one run (transient + recorded steps): a run that would need more fails
    // before its first step with "step budget exceeded: …", so no parameter set (a tiny dt,
    // a huge cycle count) can stall a worker. The default is 10 000× a default 20-cycle run.
    long maxSteps = 2'000'000'000;
    // Relative displacement error target of the adaptive integrator (core/integrate/adaptive.hpp,
    // issue 15), 1e-5 … 0.5; 0 (the default) = the paper's fixed-step scheme with dt_s. Only the
    // dynamics set-up integrates adaptively. Not a parameter key (not in sessions or run files).
    double tolerance = 0.0;
    ParamIssues validate() const;
    // Number of steps between output samples (≥ 1).
    long outputEvery() const;
};

enum class SetupKind { Dynamics, Prescribed };

const char* toString(LawKind);
const char* toString(SetupKind);
bool parseLawKind(const std::string&, LawKind&);
bool parseSetupKind(const std::string&, SetupKind&);

// Everything a simulation needs. Immutable during a run.
struct SimParams {
    DriveParams drive;
    RigParams rig;
    LawKind law = LawKind::RateState;
    SetupKind setup = SetupKind::Dynamics;
    RegisteredLaws::ParamTuple lawSet;   // the parameters of every registered law; `law` picks one
    IntegrationParams integration;
    double cycles = 20.0;            // recorded forcing cycles [-]
    double transientCycles = 0.0;    // cycles simulated and discarded first [-]
    ParamIssues validate() const;    // all of the above, fields prefixed by nothing (keys as in the CLI)
    template <class P>
    P& lawParams() { return std::get<P>(lawSet); }
    template <class P>
    const P& lawParams() const { return std::get<P>(lawSet); }
};

// Empty when a run of `steps` time steps fits `maxSteps`, else the failure message
// "step budget exceeded: the run needs 3e+11 steps, more than max_steps = 2e+09; ...".
// `steps` is a double so that absurd counts (or NaN) are caught before any conversion.
std::string stepBudgetProblem(double steps, long maxSteps);
// Steps a harmonic run of `p` takes: (transient + cycles) T / dt.
double harmonicRunSteps(const SimParams& p);

// Keys as used on the command line and in sessions: the rows of paramTable() (param_table.hpp).
// A law key (μ, ε_T, D_c, …) sets it in every law that has it; getParam reads the selected
// law's value (or the first law having the key). Returns false (and an explanation) for an unknown key.
bool setParam(SimParams&, const std::string& key, double value, std::string* error = nullptr);
bool getParam(const SimParams&, const std::string& key, double& value);
std::vector<std::string> paramKeys();
// The keys a run of `p` uses: drive, rig, the selected law's and the integration keys.
std::vector<std::string> paramKeysFor(LawKind law);

}  // namespace stickslip
