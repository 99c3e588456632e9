#include "run_options.hpp"

#include <cmath>
#include <cstdlib>

#include "io/units.hpp"
#include "presets.hpp"

namespace stickslip {

std::string presetNames() {
    std::string s;
    for (const Preset& p : builtinPresets()) s += (s.empty() ? "" : ", ") + p.name;
    return s;
}

bool parseAssignment(const std::string& text, std::string& key, double& valueSI, std::string* error) {
    const size_t eq = text.find('=');
    if (eq == std::string::npos) {
        if (error) *error = "--set expects KEY=VALUE, got '" + text + "'";
        return false;
    }
    key = text.substr(0, eq);
    while (!key.empty() && key.back() == ' ') key.pop_back();
    while (!key.empty() && key.front() == ' ') key.erase(key.begin());
    const std::string value = text.substr(eq + 1);
    std::string unit;
    if (!io::paramUnit(key, unit)) {
        std::string keys;
        for (const std::string& k : paramKeys()) keys += " " + k;
        if (error) *error = "unknown parameter '" + key + "' in '" + text + "' (known:" + keys + ")";
        return false;
    }
    return io::parseParamValue(key, value, valueSI, error);
}

bool simParamsFromOptions(const SimOptions& o, SimParams& out, std::string* error) {
    Preset preset;
    if (!findPreset(o.preset, preset)) {
        if (error) *error = "unknown preset '" + o.preset + "' (known: " + presetNames() + ")";
        return false;
    }
    SimParams p = preset.params;
    if (!o.model.empty() && !parseLawKind(o.model, p.law)) {
        if (error) *error = "--model '" + o.model + "' is not one of: rate-state, coulomb";
        return false;
    }
    if (!o.setup.empty() && !parseSetupKind(o.setup, p.setup)) {
        if (error) *error = "--setup '" + o.setup + "' is not one of: dynamics, prescribed";
        return false;
    }
    std::string why;
    for (const std::string& s : o.sets) {
        std::string key;
        double v = 0;
        if (!parseAssignment(s, key, v, &why) || !setParam(p, key, v, &why)) {
            if (error) *error = why;
            return false;
        }
    }
    const std::pair<const char*, const std::string*> flags[] = {
        {"dt", &o.dt}, {"cycles", &o.cycles}, {"transient", &o.transient}, {"output_every", &o.outputEvery}};
    for (const auto& [key, text] : flags) {
        if (text->empty()) continue;
        double v = 0;
        if (!io::parseParamValue(key, *text, v, &why)) {
            if (error) *error = why;
            return false;
        }
        setParam(p, key, v);
    }
    if (!o.maxSteps.empty()) {
        // Not a parameter key (run files and sessions do not carry it), so parsed here.
        char* end = nullptr;
        const double n = std::strtod(o.maxSteps.c_str(), &end);
        if (end == o.maxSteps.c_str() || *end != '\0' || !(n >= 1.0 && n <= 1e18) || n != std::floor(n)) {
            if (error) *error = "--max-steps '" + o.maxSteps + "': expected a whole number in [1, 1e+18] (time steps of one run)";
            return false;
        }
        p.integration.maxSteps = static_cast<long>(n);
    }
    if (!o.tolerance.empty()) {
        // Not a parameter key either: selects the adaptive integrator (IntegrationParams::tolerance).
        char* end = nullptr;
        const double tol = std::strtod(o.tolerance.c_str(), &end);
        if (end == o.tolerance.c_str() || *end != '\0' || !std::isfinite(tol)) {
            if (error) *error = "--tolerance '" + o.tolerance + "': expected a number (relative displacement error, 1e-5 to 0.5; 0 = fixed step)";
            return false;
        }
        p.integration.tolerance = tol;
    }
    const ParamIssues issues = p.validate();
    if (!issues.empty()) {
        if (error) *error = "invalid parameters:\n" + formatIssues(issues);
        return false;
    }
    out = p;
    return true;
}

}  // namespace stickslip
