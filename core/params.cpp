#include "params.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>

namespace stickslip {

namespace {

void requirePositive(ParamIssues& out, const char* field, double v) {
    if (!(std::isfinite(v) && v > 0.0)) out.push_back({field, v, "> 0"});
}
void requireNonNegative(ParamIssues& out, const char* field, double v) {
    if (!(std::isfinite(v) && v >= 0.0)) out.push_back({field, v, ">= 0"});
}
void requireFinite(ParamIssues& out, const char* field, double v) {
    if (!std::isfinite(v)) out.push_back({field, v, "finite"});
}
void append(ParamIssues& out, const ParamIssues& more) { out.insert(out.end(), more.begin(), more.end()); }

}  // namespace

std::string ParamIssue::message() const {
    std::ostringstream s;
    s.precision(6);
    s << field << " = " << value << " is out of range: must be " << allowed;
    return s.str();
}

std::string formatIssues(const ParamIssues& issues) {
    std::string out;
    for (const auto& i : issues) {
        if (!out.empty()) out += '\n';
        out += i.message();
    }
    return out;
}

ParamIssues DriveParams::validate() const {
    ParamIssues out;
    requireNonNegative(out, "A", amplitude_m);
    if (std::isfinite(amplitude_m) && amplitude_m > 1.0) out.push_back({"A", amplitude_m, "<= 1 m"});
    requirePositive(out, "f", frequency_Hz);
    requireFinite(out, "phase", phase_rad);
    return out;
}
double DriveParams::omega() const { return 2.0 * std::numbers::pi * frequency_Hz; }
double DriveParams::period() const { return 1.0 / frequency_Hz; }

ParamIssues RigParams::validate() const {
    ParamIssues out;
    requirePositive(out, "tN", normalForce_N);
    requireNonNegative(out, "k", stiffness_N_per_m);
    requirePositive(out, "m", mass_kg);
    requireNonNegative(out, "c", damping_Ns_per_m);
    return out;
}
double RigParams::naturalFrequency_rad_s() const { return std::sqrt(stiffness_N_per_m / mass_kg); }
double RigParams::dampingRatio() const {
    const double crit = 2.0 * std::sqrt(stiffness_N_per_m * mass_kg);
    return crit > 0.0 ? damping_Ns_per_m / crit : 0.0;
}

double dampingFromRatio(double zeta, double k, double m) { return 2.0 * zeta * std::sqrt(k * m); }

ParamIssues RateStateParams::validate() const {
    ParamIssues out;
    requireNonNegative(out, "mu", mu);
    requirePositive(out, "eta", eta_s_per_m);
    requirePositive(out, "Dc", Dc_m);
    requireNonNegative(out, "C1", C1);
    requirePositive(out, "r", r);
    requirePositive(out, "vc", vc_mps);
    requirePositive(out, "epsT", epsT_N_per_m);
    return out;
}

ParamIssues CoulombParams::validate() const {
    ParamIssues out;
    requireNonNegative(out, "mu", mu);
    requirePositive(out, "epsT", epsT_N_per_m);
    return out;
}

ParamIssues IntegrationParams::validate() const {
    ParamIssues out;
    requirePositive(out, "dt", dt_s);
    requirePositive(out, "output_every", outputInterval_s);
    if (maxSteps < 1) out.push_back({"max_steps", static_cast<double>(maxSteps), ">= 1"});
    // The adaptive integrator's own range (AdaptiveOptions::validate).
    if (!(tolerance == 0.0 || (tolerance >= 1e-5 && tolerance <= 0.5)))
        out.push_back({"tolerance", tolerance, "0 (fixed step) or in [1e-5, 0.5]"});
    return out;
}
long IntegrationParams::outputEvery() const {
    if (!(dt_s > 0.0) || !(outputInterval_s > 0.0)) return 1;
    const double n = std::round(outputInterval_s / dt_s);
    // Beyond maxSteps no output sample but the first would be written anyway; the clamp
    // keeps the conversion defined for absurd ratios.
    return n < 1.0 ? 1L : n > static_cast<double>(maxSteps) ? std::max(1L, maxSteps) : static_cast<long>(n);
}

ParamIssues SimParams::validate() const {
    ParamIssues out;
    append(out, drive.validate());
    append(out, rig.validate());
    if (law == LawKind::RateState) append(out, rateState.validate());
    else append(out, coulomb.validate());
    append(out, integration.validate());
    requirePositive(out, "cycles", cycles);
    requireNonNegative(out, "transient", transientCycles);
    // The step must resolve the forcing: at least 8 steps per period.
    if (integration.dt_s > 0.0 && drive.frequency_Hz > 0.0 && integration.dt_s > drive.period() / 8.0)
        out.push_back({"dt", integration.dt_s, "<= T/8 = " + std::to_string(drive.period() / 8.0) + " s"});
    if (setup == SetupKind::Prescribed && integration.tolerance != 0.0)
        out.push_back({"tolerance", integration.tolerance, "0 in the prescribed set-up (adaptive: dynamics only)"});
    return out;
}

std::string stepBudgetProblem(double steps, long maxSteps) {
    if (steps <= static_cast<double>(maxSteps)) return {};
    std::ostringstream s;
    s.precision(6);
    s << "step budget exceeded: the run needs " << steps << " steps, more than max_steps = "
      << static_cast<double>(maxSteps) << "; use a larger dt or a shorter run";
    return s.str();
}

double harmonicRunSteps(const SimParams& p) {
    return (p.transientCycles + p.cycles) * p.drive.period() / p.integration.dt_s;
}

const char* toString(LawKind k) { return k == LawKind::RateState ? "rate-state" : "coulomb"; }
const char* toString(SetupKind k) { return k == SetupKind::Dynamics ? "dynamics" : "prescribed"; }
bool parseLawKind(const std::string& s, LawKind& k) {
    if (s == "rate-state" || s == "ratestate" || s == "rate_state") { k = LawKind::RateState; return true; }
    if (s == "coulomb") { k = LawKind::Coulomb; return true; }
    return false;
}
bool parseSetupKind(const std::string& s, SetupKind& k) {
    if (s == "dynamics") { k = SetupKind::Dynamics; return true; }
    if (s == "prescribed") { k = SetupKind::Prescribed; return true; }
    return false;
}

namespace {
struct KeyRef {
    const char* key;
    double* (*ptr)(SimParams&);
};
// μ and ε_T are shared by both laws; they are handled in setParam.
const KeyRef kKeys[] = {
    {"A", [](SimParams& p) { return &p.drive.amplitude_m; }},
    {"f", [](SimParams& p) { return &p.drive.frequency_Hz; }},
    {"phase", [](SimParams& p) { return &p.drive.phase_rad; }},
    {"tN", [](SimParams& p) { return &p.rig.normalForce_N; }},
    {"k", [](SimParams& p) { return &p.rig.stiffness_N_per_m; }},
    {"m", [](SimParams& p) { return &p.rig.mass_kg; }},
    {"c", [](SimParams& p) { return &p.rig.damping_Ns_per_m; }},
    {"mu", [](SimParams& p) { return &p.rateState.mu; }},
    {"eta", [](SimParams& p) { return &p.rateState.eta_s_per_m; }},
    {"Dc", [](SimParams& p) { return &p.rateState.Dc_m; }},
    {"C1", [](SimParams& p) { return &p.rateState.C1; }},
    {"r", [](SimParams& p) { return &p.rateState.r; }},
    {"vc", [](SimParams& p) { return &p.rateState.vc_mps; }},
    {"epsT", [](SimParams& p) { return &p.rateState.epsT_N_per_m; }},
    {"dt", [](SimParams& p) { return &p.integration.dt_s; }},
    {"output_every", [](SimParams& p) { return &p.integration.outputInterval_s; }},
    {"cycles", [](SimParams& p) { return &p.cycles; }},
    {"transient", [](SimParams& p) { return &p.transientCycles; }},
};
}  // namespace

std::vector<std::string> paramKeys() {
    std::vector<std::string> keys;
    for (const auto& k : kKeys) keys.emplace_back(k.key);
    return keys;
}

bool setParam(SimParams& p, const std::string& key, double value, std::string* error) {
    for (const auto& k : kKeys) {
        if (key == k.key) {
            *k.ptr(p) = value;
            if (key == "mu") p.coulomb.mu = value;
            if (key == "epsT") p.coulomb.epsT_N_per_m = value;
            return true;
        }
    }
    if (error) {
        std::string list;
        for (const auto& k : kKeys) list += std::string(list.empty() ? "" : " ") + k.key;
        *error = "unknown parameter '" + key + "' (known: " + list + ")";
    }
    return false;
}

bool getParam(const SimParams& p, const std::string& key, double& value) {
    for (const auto& k : kKeys) {
        if (key == k.key) {
            value = *k.ptr(const_cast<SimParams&>(p));
            return true;
        }
    }
    return false;
}

}  // namespace stickslip
