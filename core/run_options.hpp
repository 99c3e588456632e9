// The common run options of every front end (CLI --preset/--model/--setup/--set/--dt/
// --cycles/--transient/--output-every/--max-steps, the Python module's keyword arguments) as raw text,
// turned into validated SimParams. One implementation, so every front end builds the same
// parameters from the same options.
#pragma once

#include <string>
#include <vector>

#include "params.hpp"

namespace stickslip {

// Raw option text as given (values may carry units, e.g. "20us").
struct SimOptions {
    std::string preset = "default";
    std::string model;                 // "", "rate-state" or "coulomb"
    std::string setup;                 // "", "dynamics" or "prescribed"
    std::vector<std::string> sets;     // "KEY=VALUE", applied in order
    std::string dt;                    // time step [s]
    std::string cycles;                // recorded cycles
    std::string transient;             // discarded cycles
    std::string outputEvery;           // output sample spacing [s]
    std::string maxSteps;              // step budget of one run ("" = IntegrationParams' default)
    std::string tolerance;             // adaptive error target ("" or "0" = fixed step dt)
};

// Preset names joined by ", " (for help texts and messages).
std::string presetNames();

// Splits "KEY=VALUE" and parses VALUE for KEY (SI or with a unit of the key's dimension).
bool parseAssignment(const std::string& text, std::string& key, double& valueSI, std::string* error);

// Preset, then model/setup, then every set in order, then dt/cycles/transient/output_every
// and the step budget (a whole number in [1, 1e18]); then validate(). Returns false with a message naming the key, value and allowed range in
// *error (all violated fields, one per line).
bool simParamsFromOptions(const SimOptions& o, SimParams& out, std::string* error);

}  // namespace stickslip
