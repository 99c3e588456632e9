#include "cli_common.hpp"

#include <cstdio>
#include <iostream>

#include "core/io/units.hpp"
#include "mpi_runner.hpp"
#include "core/presets.hpp"
#include "core/analysis/poincare.hpp"

#include "core/friction/friction_law.hpp"

namespace stickslip::cli {

void addSimOptions(CLI::App* cmd, SimOptions& o) {
    cmd->add_option("--preset", o.preset, "Parameter set to start from (" + presetNames() + ")")
        ->capture_default_str();
    std::string laws;
    for (const LawInfo& i : lawRegistry()) laws += std::string(laws.empty() ? "" : ", ") + i.key;
    cmd->add_option("--model", o.model, "Friction law: " + laws + " (default: the preset's)");
    cmd->add_option("--setup", o.setup, "dynamics (spring-mass rig) or prescribed (slip imposed on the block)");
    std::string keys;  // from the parameter table: key [SI unit]
    for (const ParamDef& d : paramTable()) keys += std::string(" ") + d.key + (*d.unit ? std::string("[") + d.unit + "]" : "");
    cmd->add_option("--set", o.sets,
                    "KEY=VALUE, repeatable; VALUE in SI or with a unit (0.4mm, 20um, 6.2N, 3Hz, 0.5kg, 0.6s/m, "
                    "0.1m/s, 1e6N/m). KEY:" + keys)
        ->type_name("KEY=VALUE");
    cmd->add_option("--dt", o.dt, "Time step [s] (units allowed, e.g. 10us)")->type_name("S");
    cmd->add_option("--cycles", o.cycles, "Recorded forcing cycles")->type_name("N");
    cmd->add_option("--transient", o.transient, "Forcing cycles simulated and discarded first")->type_name("N");
    cmd->add_option("--output-every", o.outputEvery, "Output sample spacing [s] (rounded to a multiple of dt)")
        ->type_name("S");
    cmd->add_option("--max-steps", o.maxSteps,
                    "Step budget of one run (transient + recorded steps); a run that needs more fails at once "
                    "(default 2e9)")
        ->type_name("N");
}

void addToleranceOption(CLI::App* cmd, SimOptions& o, const std::string& samples) {
    cmd->add_option("--tolerance", o.tolerance,
                    "Integrate adaptively to this relative displacement error (1e-5 to 0.5; dynamics set-up): "
                    "error-controlled steps, stick-slip switches located, " + samples + ". Default: the fixed step --dt")
        ->type_name("TOL");
}

std::string steppingText(const SimParams& p, long requestedStepsPerPeriod) {
    if (p.integration.tolerance > 0.0)
        return "integration = adaptive, tolerance = " + exactNumber(p.integration.tolerance) +
               " (samples at the exact phase from the dense output)";
    return "steps per period = " + std::to_string(stepsPerPeriodFor(p, requestedStepsPerPeriod));
}

int buildSimParams(const SimOptions& o, SimParams& out, std::string* error) {
    return simParamsFromOptions(o, out, error) ? kOk : kBadArguments;
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
    return t + "law " + toString(p.law) + "\nsetup " + toString(p.setup) + "\ntolerance " +
           exactNumber(p.integration.tolerance) + "\n";
}

void reportError(const std::string& command, const std::string& message, int code, int& exitCode) {
    // Under mpirun every rank parses the same arguments and meets the same error: rank 0 speaks.
    if (mpiRank() == 0) std::cerr << "stickslip-cli " << command << ": " << message << '\n';
    exitCode = code;
}

}  // namespace stickslip::cli
