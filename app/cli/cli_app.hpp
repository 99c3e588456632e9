// The root CLI11 app of stickslip-cli: every subcommand and flag registered, nothing parsed.
// main() and the argument-parser fuzz target (fuzz/fuzz_cli_args.cpp) build the same tree.
#pragma once

#include <CLI/CLI.hpp>

namespace stickslip::cli {

// Registers the description, --version and every subcommand on `app`; the subcommands'
// callbacks store the process exit code in `exitCode`.
void buildCliApp(CLI::App& app, int& exitCode);

}  // namespace stickslip::cli
