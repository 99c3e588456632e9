// Helpers shared by the stickslip-cli subcommands: the common run options (--preset,
// --model, --setup, --set KEY=VALUE, --dt, --cycles, --transient, --output-every) turned
// into validated SimParams, and error reporting with the exit codes of commands.hpp.
#pragma once

#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "commands.hpp"
#include "core/identify/pipeline.hpp"
#include "core/params.hpp"
#include "core/run_options.hpp"

namespace stickslip::cli {

using SimOptions = stickslip::SimOptions;
using stickslip::parseAssignment;
using stickslip::presetNames;

// Registers the options above on `cmd`.
void addSimOptions(CLI::App* cmd, SimOptions& o);

// --tolerance TOL (SimOptions::tolerance): error-controlled steps instead of the fixed dt, for
// the commands that run the spring-mass rig; `samples` says what the dense output gives there.
void addToleranceOption(CLI::App* cmd, SimOptions& o, const std::string& samples);

// How a section's runs are stepped, for output headers: "steps per period = N" or
// "integration = adaptive, tolerance = TOL (samples at the exact phase from the dense output)".
std::string steppingText(const SimParams& p, long requestedStepsPerPeriod);

// The measured-data options `fit` and `identify` share (identify::MeasuredInputs: --data,
// --setup, --columns, --units, --manifest, --run-set, --validate-on) and the cleaning options
// (identify::CleaningOptions: band-stop, low-pass, trims, stage harmonics, steady trim); `data`
// and `validateOn` say what the command does with them.
void addMeasuredInputOptions(CLI::App* cmd, identify::MeasuredInputs& in, const std::string& data,
                             const std::string& validateOn);
void addCleaningOptions(CLI::App* cmd, identify::CleaningOptions& c);

// simParamsFromOptions (core/run_options.hpp) with the CLI exit codes: returns kOk, or kBadArguments with a message naming
// the key, value and allowed range in *error (all violated fields, one per line).
int buildSimParams(const SimOptions& o, SimParams& out, std::string* error);

// The run options as given and every parameter they resolved to (%.17g), one per line: the
// part of a checkpoint's fingerprint that the common options contribute.
std::string simSettingsText(const SimOptions& o, const SimParams& p);

// %.17g: reads back to the same double.
std::string exactNumber(double v);

// Prints "stickslip-cli <command>: <message>" on stderr, stores `code` in exitCode.
void reportError(const std::string& command, const std::string& message, int code, int& exitCode);

}  // namespace stickslip::cli
