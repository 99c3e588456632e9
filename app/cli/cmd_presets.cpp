// PLACEHOLDER: `stickslip-cli presets` is not implemented yet (owner replaces this file).
#include <iostream>

#include "commands.hpp"

namespace stickslip::cli {

void addPresetsCommand(CLI::App& root, int& exitCode) {
    auto* cmd = root.add_subcommand("presets", "(not implemented yet)");
    cmd->callback([&exitCode] {
        std::cerr << "stickslip-cli presets: not implemented yet\n";
        exitCode = kRunFailedGeneric;
    });
}

}  // namespace stickslip::cli
