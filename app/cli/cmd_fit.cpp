// PLACEHOLDER: `stickslip-cli fit` is not implemented yet (owner replaces this file).
#include <iostream>

#include "commands.hpp"

namespace stickslip::cli {

void addFitCommand(CLI::App& root, int& exitCode) {
    auto* cmd = root.add_subcommand("fit", "(not implemented yet)");
    cmd->callback([&exitCode] {
        std::cerr << "stickslip-cli fit: not implemented yet\n";
        exitCode = kRunFailedGeneric;
    });
}

}  // namespace stickslip::cli
