// stickslip-cli: the headless front end of StickSlip Lab.
#include <iostream>

#include "cancel.hpp"
#include "core/heap_settings.hpp"
#include "cli_app.hpp"
#include "commands.hpp"
#include "mpi_runner.hpp"

int main(int argc, char** argv) {
    using namespace stickslip::cli;
    stickslip::applyHeapSettings();  // before any thread starts (heap_settings.hpp)
    mpiStart(argc, argv);  // a no-op unless launched by mpirun/srun
    installCancelHandlers();
    CLI::App app;
    int exitCode = kOk;
    buildCliApp(app, exitCode);
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
