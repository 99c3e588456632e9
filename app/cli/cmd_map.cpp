// PLACEHOLDER: `stickslip-cli map` is not implemented yet (owner replaces this file).
#include <iostream>

#include "commands.hpp"

namespace stickslip::cli {

void addMapCommand(CLI::App& root, int& exitCode) {
    auto* cmd = root.add_subcommand("map", "(not implemented yet)");
    cmd->callback([&exitCode] {
        std::cerr << "stickslip-cli map: not implemented yet\n";
        exitCode = kRunFailedGeneric;
    });
}

}  // namespace stickslip::cli
