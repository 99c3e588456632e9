// PLACEHOLDER: `stickslip-cli simulate` is not implemented yet (owner replaces this file).
#include <iostream>

#include "commands.hpp"

namespace stickslip::cli {

void addSimulateCommand(CLI::App& root, int& exitCode) {
    auto* cmd = root.add_subcommand("simulate", "(not implemented yet)");
    cmd->callback([&exitCode] {
        std::cerr << "stickslip-cli simulate: not implemented yet\n";
        exitCode = kRunFailedGeneric;
    });
}

}  // namespace stickslip::cli
