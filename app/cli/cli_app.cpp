#include "cli_app.hpp"

#include <string>

#include "commands.hpp"
#include "core/version.hpp"
#include "man_page.hpp"

namespace stickslip::cli {

void buildCliApp(CLI::App& app, int& exitCode) {
    app.description("StickSlip Lab command line: simulate, sweep, analyse and fit friction-induced stick-slip");
    app.set_version_flag("--version", std::string("stickslip-cli ") + stickslip::kVersion);
    app.require_subcommand(1);
    addSimulateCommand(app, exitCode);
    addPresetsCommand(app, exitCode);
    addSweepCommand(app, exitCode);
    addMapCommand(app, exitCode);
    addAnalyzeCommand(app, exitCode);
    addReproduceCommand(app, exitCode);
    addFitCommand(app, exitCode);
    addIdentifyCommand(app, exitCode);
    addSynthesizeCommand(app, exitCode);
    addManPageCommand(app, exitCode);
}

}  // namespace stickslip::cli
