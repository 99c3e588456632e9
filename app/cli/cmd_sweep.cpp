// PLACEHOLDER: `stickslip-cli sweep` is not implemented yet (owner replaces this file).
#include <iostream>

#include "commands.hpp"

namespace stickslip::cli {

void addSweepCommand(CLI::App& root, int& exitCode) {
    auto* cmd = root.add_subcommand("sweep", "(not implemented yet)");
    cmd->callback([&exitCode] {
        std::cerr << "stickslip-cli sweep: not implemented yet\n";
        exitCode = kRunFailedGeneric;
    });
}

}  // namespace stickslip::cli
