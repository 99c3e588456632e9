// PLACEHOLDER: `stickslip-cli identify` is not implemented yet (owner replaces this file).
#include <iostream>

#include "commands.hpp"

namespace stickslip::cli {

void addIdentifyCommand(CLI::App& root, int& exitCode) {
    auto* cmd = root.add_subcommand("identify", "(not implemented yet)");
    cmd->callback([&exitCode] {
        std::cerr << "stickslip-cli identify: not implemented yet\n";
        exitCode = kRunFailedGeneric;
    });
}

}  // namespace stickslip::cli
