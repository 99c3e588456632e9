// PLACEHOLDER: `stickslip-cli analyze` is not implemented yet (owner replaces this file).
#include <iostream>

#include "commands.hpp"

namespace stickslip::cli {

void addAnalyzeCommand(CLI::App& root, int& exitCode) {
    auto* cmd = root.add_subcommand("analyze", "(not implemented yet)");
    cmd->callback([&exitCode] {
        std::cerr << "stickslip-cli analyze: not implemented yet\n";
        exitCode = kRunFailedGeneric;
    });
}

}  // namespace stickslip::cli
