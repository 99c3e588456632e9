// Subcommands of stickslip-cli. Each lives in its own cmd_<name>.cpp and registers itself
// on the root app; its callback stores the process exit code in `exitCode`.
#pragma once

#include <CLI/CLI.hpp>

namespace stickslip::cli {

// Exit codes shared by all commands.
enum Exit : int {
    kOk = 0,
    kRunFailedGeneric = 1,
    kBadArguments = 2,   // bad arguments or parameters (message names key, value, allowed range)
    kBadInput = 3,       // unreadable or malformed input (file, line, column)
    kRunFailed = 4,      // a run that failed numerically
    kCancelled = 5,
};

void addSimulateCommand(CLI::App& root, int& exitCode);
void addPresetsCommand(CLI::App& root, int& exitCode);
void addSweepCommand(CLI::App& root, int& exitCode);
void addMapCommand(CLI::App& root, int& exitCode);
void addAnalyzeCommand(CLI::App& root, int& exitCode);
void addReproduceCommand(CLI::App& root, int& exitCode);
void addFitCommand(CLI::App& root, int& exitCode);
void addIdentifyCommand(CLI::App& root, int& exitCode);
void addSynthesizeCommand(CLI::App& root, int& exitCode);

}  // namespace stickslip::cli
