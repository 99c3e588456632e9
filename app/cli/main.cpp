// stickslip-cli: the headless front end of StickSlip Lab.
#include <iostream>

#include "cancel.hpp"
#include "commands.hpp"
#include "man_page.hpp"
#include "mpi_runner.hpp"
#include "core/version.hpp"

int main(int argc, char** argv) {
    using namespace stickslip::cli;
    mpiStart(argc, argv);  // a no-op unless launched by mpirun/srun
    installCancelHandlers();
    CLI::App app{"StickSlip Lab command line: simulate, sweep, analyse and fit friction-induced stick-slip"};
    app.set_version_flag("--version", std::string("stickslip-cli ") + stickslip::kVersion);
    app.require_subcommand(1);
    int exitCode = kOk;
    addSimulateCommand(app, exitCode);
    addPresetsCommand(app, exitCode);
    addSweepCommand(app, exitCode);
    addMapCommand(app, exitCode);
    addAnalyzeCommand(app, exitCode);
    addReproduceCommand(app, exitCode);
    addFitCommand(app, exitCode);
    addIdentifyCommand(app, exitCode);
    addManPageCommand(app, exitCode);
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        const int rc = mpiRank() == 0 ? app.exit(e) : (e.get_exit_code() == 0 ? 0 : 1);
        mpiStop();
        return rc == 0 ? 0 : kBadArguments;
    }
    mpiStop();
    return exitCode;
}
