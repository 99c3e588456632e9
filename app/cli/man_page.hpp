// The CLI's man page, generated from the same CLI11 definitions that parse the arguments,
// so the installed stickslip-cli(1) cannot drift from `--help`.
#pragma once

#include <string>

#include <CLI/CLI.hpp>

namespace stickslip::cli {

// roff (man(7)) text: NAME, SYNOPSIS, DESCRIPTION, one COMMANDS subsection per subcommand with
// its options, defaults and required flags, EXIT STATUS, FILES, SEE ALSO.
std::string manPage(const CLI::App& root, const std::string& version);

// Registers the hidden `manpage` subcommand (prints manPage(root) to stdout); the build
// runs it to produce stickslip-cli.1.
void addManPageCommand(CLI::App& root, int& exitCode);

}  // namespace stickslip::cli
