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

void addMeasuredInputOptions(CLI::App* cmd, identify::MeasuredInputs& in, const std::string& data,
                             const std::string& validateOn) {
    cmd->add_option("--data", in.data, data)->required()->expected(1, -1);
    cmd->add_option("--setup", in.setup,
                    "prescribed (slip in, force out) or dynamics (stage in, slider and force out); default from the columns");
    cmd->add_option("--columns", in.columns,
                    "SIGNAL=COLUMN mappings, e.g. friction=Fx (signals: time stage_disp slider_disp slip rel_vel stage_vel "
                    "slider_vel friction normal tension slider_accel)");
    cmd->add_option("--units", in.units, "SIGNAL=UNIT, e.g. stage_disp=mm");
    cmd->add_option("--manifest", in.manifest, "dataset manifest JSON (per run k, A, f, tN; nominal mass)");
    cmd->add_option("--run-set", in.runSets, "FILE:KEY=VALUE known setting of one run, e.g. run_01.csv:tN=6.2N");
    cmd->add_option("--validate-on", in.validateOn, validateOn)->expected(1, -1);
}

void addCleaningOptions(CLI::App* cmd, identify::CleaningOptions& c) {
    auto& f = c.pre.filters;
    cmd->add_flag("--no-bandstop", c.noBandStop, "switch the mains band-stop off");
    cmd->add_option("--bandstop-hz", f.bandStopCenter_Hz, "band-stop centre [Hz]")->capture_default_str();
    cmd->add_option("--bandstop-width", f.bandStopWidth_Hz, "band-stop width [Hz]")->capture_default_str();
    cmd->add_option("--bandstop-order", f.bandStopOrder, "band-stop prototype order")->capture_default_str();
    cmd->add_flag("--no-lowpass", c.noLowPass, "switch the low-pass off");
    cmd->add_option("--lowpass-hz", f.lowPass_Hz, "low-pass cut-off [Hz]")->capture_default_str();
    cmd->add_option("--lowpass-order", f.lowPassOrder, "low-pass order")->capture_default_str();
    cmd->add_option("--trim-start", c.pre.trim.start_s, "drop this many seconds at the start [s]");
    cmd->add_option("--trim-end", c.pre.trim.end_s, "drop this many seconds at the end [s]");
    cmd->add_option("--stage-harmonics", c.pre.stageFourierOrder,
                    "dynamics: stage input = Fourier fit with this many harmonics (0 = measured)")->capture_default_str();
    cmd->add_flag("--fuse-slider-acceleration", c.pre.fuseSliderAcceleration,
                  "dynamics: slider displacement and velocity from slider_disp and slider_accel together (Rauch-Tung-Striebel smoother, noise levels estimated per run)");
    cmd->add_flag("--no-steady-trim", c.noSteadyTrim, "keep ramps (do not trim to the steady drive amplitude)");
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
