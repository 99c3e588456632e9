// Helpers shared by the stickslip-cli subcommands: the common run options (--preset,
// --model, --setup, --set KEY=VALUE, --dt, --cycles, --transient, --output-every) turned
// into validated SimParams, and error reporting with the exit codes of commands.hpp.
#pragma once

#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "commands.hpp"
#include "core/params.hpp"

namespace stickslip::cli {

// Raw option text as given on the command line (values may carry units, e.g. "20us").
struct SimOptions {
    std::string preset = "default";
    std::string model;                 // "", "rate-state" or "coulomb"
    std::string setup;                 // "", "dynamics" or "prescribed"
    std::vector<std::string> sets;     // "KEY=VALUE", applied in order
    std::string dt;                    // --dt S
    std::string cycles;                // --cycles N
    std::string transient;             // --transient N
    std::string outputEvery;           // --output-every S
};

// Registers the options above on `cmd`.
void addSimOptions(CLI::App* cmd, SimOptions& o);

// Splits "KEY=VALUE" and parses VALUE for KEY (SI or with a unit of the key's dimension).
bool parseAssignment(const std::string& text, std::string& key, double& valueSI, std::string* error);

// Preset, then --model/--setup, then every --set in order, then --dt/--cycles/--transient/
// --output-every; then validate(). Returns kOk, or kBadArguments with a message naming
// the key, value and allowed range in *error (all violated fields, one per line).
int buildSimParams(const SimOptions& o, SimParams& out, std::string* error);

// The run options as given and every parameter they resolved to (%.17g), one per line: the
// part of a checkpoint's fingerprint that the common options contribute.
std::string simSettingsText(const SimOptions& o, const SimParams& p);

// %.17g: reads back to the same double.
std::string exactNumber(double v);

// Prints "stickslip-cli <command>: <message>" on stderr, stores `code` in exitCode.
void reportError(const std::string& command, const std::string& message, int code, int& exitCode);

// Preset names joined by ", " (for help texts and messages).
std::string presetNames();

}  // namespace stickslip::cli
