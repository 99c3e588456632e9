// PLACEHOLDER: `stickslip-cli reproduce` is not implemented yet (owner replaces this file).
#include <iostream>

#include "commands.hpp"

namespace stickslip::cli {

void addReproduceCommand(CLI::App& root, int& exitCode) {
    auto* cmd = root.add_subcommand("reproduce", "(not implemented yet)");
    cmd->callback([&exitCode] {
        std::cerr << "stickslip-cli reproduce: not implemented yet\n";
        exitCode = kRunFailedGeneric;
    });
}

}  // namespace stickslip::cli
