#include "params.hpp"

#include <cctype>
#include <variant>

#include "friction/friction_law.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>

namespace stickslip {

namespace {
void append(ParamIssues& out, const ParamIssues& more) { out.insert(out.end(), more.begin(), more.end()); }
}  // namespace

ParamIssues DriveParams::validate() const {
    ParamIssues out;
    checkParam("A", amplitude_m, out);
    checkParam("f", frequency_Hz, out);
    checkParam("phase", phase_rad, out);
    return out;
}
double DriveParams::omega() const { return 2.0 * std::numbers::pi * frequency_Hz; }
double DriveParams::period() const { return 1.0 / frequency_Hz; }

ParamIssues RigParams::validate() const {
    ParamIssues out;
    checkParam("tN", normalForce_N, out);
    checkParam("k", stiffness_N_per_m, out);
    checkParam("m", mass_kg, out);
    checkParam("c", damping_Ns_per_m, out);
    return out;
}
double RigParams::naturalFrequency_rad_s() const { return std::sqrt(stiffness_N_per_m / mass_kg); }
double RigParams::dampingRatio() const {
    const double crit = 2.0 * std::sqrt(stiffness_N_per_m * mass_kg);
    return crit > 0.0 ? damping_Ns_per_m / crit : 0.0;
}

double dampingFromRatio(double zeta, double k, double m) { return 2.0 * zeta * std::sqrt(k * m); }

ParamIssues IntegrationParams::validate() const {
    ParamIssues out;
    checkParam("dt", dt_s, out);
    checkParam("output_every", outputInterval_s, out);
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
    append(out, std::visit([](const auto& l) { return l.params.validate(); }, makeLaw(*this)));
    append(out, integration.validate());
    checkParam("cycles", cycles, out);
    checkParam("transient", transientCycles, out);
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

const char* toString(LawKind k) { return lawInfo(k).key; }
const char* toString(SetupKind k) { return k == SetupKind::Dynamics ? "dynamics" : "prescribed"; }

namespace {
// "Rate_State", "ratestate" and "rate-state" name the same law.
std::string normalisedLawName(const std::string& s) {
    std::string out;
    for (char c : s)
        if (c != '-' && c != '_' && c != ' ') out += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return out;
}
}  // namespace

bool parseLawKind(const std::string& s, LawKind& k) {
    for (const LawInfo& i : lawRegistry())
        if (normalisedLawName(s) == normalisedLawName(i.key)) {
            k = i.kind;
            return true;
        }
    return false;
}
bool parseSetupKind(const std::string& s, SetupKind& k) {
    if (s == "dynamics") { k = SetupKind::Dynamics; return true; }
    if (s == "prescribed") { k = SetupKind::Prescribed; return true; }
    return false;
}

std::vector<std::string> paramKeys() {
    std::vector<std::string> keys;
    for (const ParamDef& d : paramTable()) keys.emplace_back(d.key);
    return keys;
}

std::vector<std::string> paramKeysFor(LawKind law) {
    std::vector<std::string> keys;
    for (const ParamDef& d : paramTable())
        if (d.group != ParamGroup::FrictionLaw || lawHasParam(law, d.key)) keys.emplace_back(d.key);
    return keys;
}

bool setParam(SimParams& p, const std::string& key, double value, std::string* error) {
    const ParamDef* d = findParam(key);
    if (!d) {
        if (error) {
            std::string list;
            for (const ParamDef& r : paramTable()) list += std::string(list.empty() ? "" : " ") + r.key;
            *error = "unknown parameter '" + key + "' (known: " + list + ")";
        }
        return false;
    }
    if (d->field) {
        *d->field(p) = value;
        return true;
    }
    for (const LawInfo& law : lawRegistry())
        if (double* f = law.field(p, key)) *f = value;
    return true;
}

bool getParam(const SimParams& p, const std::string& key, double& value) {
    const ParamDef* d = findParam(key);
    if (!d) return false;
    SimParams& q = const_cast<SimParams&>(p);  // the accessors only read here
    if (d->field) {
        value = *d->field(q);
        return true;
    }
    if (double* f = lawInfo(p.law).field(q, key)) {
        value = *f;
        return true;
    }
    for (const LawInfo& law : lawRegistry())
        if (double* f = law.field(q, key)) {
            value = *f;
            return true;
        }
    return false;
}

}  // namespace stickslip
