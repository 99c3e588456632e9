#include "cli_common.hpp"

#include <cstdio>
#include <iostream>

#include "core/io/units.hpp"
#include "mpi_runner.hpp"
#include "core/presets.hpp"

namespace stickslip::cli {

std::string presetNames() {
    std::string s;
    for (const Preset& p : builtinPresets()) s += (s.empty() ? "" : ", ") + p.name;
    return s;
}

void addSimOptions(CLI::App* cmd, SimOptions& o) {
    cmd->add_option("--preset", o.preset, "Parameter set to start from (" + presetNames() + ")")
        ->capture_default_str();
    cmd->add_option("--model", o.model, "Friction law: rate-state or coulomb (default: the preset's)");
    cmd->add_option("--setup", o.setup, "dynamics (spring-mass rig) or prescribed (slip imposed on the block)");
    std::string keys;
    for (const std::string& k : paramKeys()) keys += " " + k;
    cmd->add_option("--set", o.sets,
                    "KEY=VALUE, repeatable; VALUE in SI or with a unit (0.4mm, 20um, 6.2N, 3Hz, 0.5kg, 0.6s/m, "
                    "0.1m/s, 1e6N/m). KEY:" + keys)
        ->type_name("KEY=VALUE");
    cmd->add_option("--dt", o.dt, "Time step [s] (units allowed, e.g. 10us)")->type_name("S");
    cmd->add_option("--cycles", o.cycles, "Recorded forcing cycles")->type_name("N");
    cmd->add_option("--transient", o.transient, "Forcing cycles simulated and discarded first")->type_name("N");
    cmd->add_option("--output-every", o.outputEvery, "Output sample spacing [s] (rounded to a multiple of dt)")
        ->type_name("S");
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

int buildSimParams(const SimOptions& o, SimParams& out, std::string* error) {
    Preset preset;
    if (!findPreset(o.preset, preset)) {
        if (error) *error = "unknown preset '" + o.preset + "' (known: " + presetNames() + ")";
        return kBadArguments;
    }
    SimParams p = preset.params;
    if (!o.model.empty() && !parseLawKind(o.model, p.law)) {
        if (error) *error = "--model '" + o.model + "' is not one of: rate-state, coulomb";
        return kBadArguments;
    }
    if (!o.setup.empty() && !parseSetupKind(o.setup, p.setup)) {
        if (error) *error = "--setup '" + o.setup + "' is not one of: dynamics, prescribed";
        return kBadArguments;
    }
    std::string why;
    for (const std::string& s : o.sets) {
        std::string key;
        double v = 0;
        if (!parseAssignment(s, key, v, &why) || !setParam(p, key, v, &why)) {
            if (error) *error = why;
            return kBadArguments;
        }
    }
    const std::pair<const char*, const std::string*> flags[] = {
        {"dt", &o.dt}, {"cycles", &o.cycles}, {"transient", &o.transient}, {"output_every", &o.outputEvery}};
    for (const auto& [key, text] : flags) {
        if (text->empty()) continue;
        double v = 0;
        if (!io::parseParamValue(key, *text, v, &why)) {
            if (error) *error = why;
            return kBadArguments;
        }
        setParam(p, key, v);
    }
    const ParamIssues issues = p.validate();
    if (!issues.empty()) {
        if (error) *error = "invalid parameters:\n" + formatIssues(issues);
        return kBadArguments;
    }
    out = p;
    return kOk;
}

std::string exactNumber(double v) {
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.17g", v);
    return buf;
}

std::string simSettingsText(const SimOptions& o, const SimParams& p) {
    std::string t = "preset " + o.preset + "\nmodel " + o.model + "\nsetup " + o.setup + "\ndt " + o.dt + "\n";
    for (const std::string& s : o.sets) t += "set " + s + "\n";
    for (const std::string& k : paramKeys()) {
        double v = 0;
        if (getParam(p, k, v)) t += k + " " + exactNumber(v) + "\n";
    }
    return t + "law " + toString(p.law) + "\nsetup " + toString(p.setup) + "\n";
}

void reportError(const std::string& command, const std::string& message, int code, int& exitCode) {
    // Under mpirun every rank parses the same arguments and meets the same error: rank 0 speaks.
    if (mpiRank() == 0) std::cerr << "stickslip-cli " << command << ": " << message << '\n';
    exitCode = code;
}

}  // namespace stickslip::cli
