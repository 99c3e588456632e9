// Fuzz target: the stickslip-cli argument parser. The input's lines are the arguments after
// the program name; the CLI11 tree is the one stickslip-cli builds (buildCliApp), with every
// subcommand's callback taken out so nothing runs: only parsing, validators and help/error
// formatting are exercised. Anything thrown other than CLI11's ParseError is a finding (a
// validator or converter that escapes with std::invalid_argument, std::out_of_range, ...).
#include <cstdint>
#include <exception>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "cli_app.hpp"
#include "fuzz_check.hpp"

namespace {

// CLI11 has no getter for a callback, but a derived class may name the protected members,
// and a pointer to member obtained so applies to any CLI::App.
struct CallbackSlots : CLI::App {
    static constexpr auto kFinal = &CallbackSlots::final_callback_;
    static constexpr auto kParseComplete = &CallbackSlots::parse_complete_callback_;
};

// Moves every subcommand's callbacks into `kept` instead of destroying them: the commands'
// options are bound to storage (a shared_ptr) that only the callback's captures keep alive.
void takeCallbacks(CLI::App& app, std::vector<std::function<void()>>& kept) {
    for (CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; })) {
        kept.push_back(std::exchange(sub->*CallbackSlots::kFinal, {}));
        kept.push_back(std::exchange(sub->*CallbackSlots::kParseComplete, {}));
        takeCallbacks(*sub, kept);
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    if (size > 4096) return 0;  // long argv lines add nothing but time
    const std::string in(reinterpret_cast<const char*>(data), size);
    std::vector<std::string> args{"stickslip-cli"};
    size_t b = 0;
    while (b <= in.size()) {
        const size_t e = std::min(in.find('\n', b), in.size());
        args.push_back(in.substr(b, e - b));
        b = e + 1;
    }
    if (args.size() > 64) return 0;
    std::vector<char*> argv;
    for (std::string& a : args) argv.push_back(a.data());

    std::vector<std::function<void()>> kept;  // outlives `app`, whose options point into it
    CLI::App app;
    int exitCode = 0;
    stickslip::cli::buildCliApp(app, exitCode);
    takeCallbacks(app, kept);
    try {
        app.parse(static_cast<int>(argv.size()), argv.data());
    } catch (const CLI::ParseError& e) {
        std::ostringstream out, err;
        app.exit(e, out, err);  // formats --help / the error message as main() would
    } catch (const std::exception& e) {
        FUZZ_CHECK(false, "argument parsing threw %s", e.what());
    }
    FUZZ_CHECK(exitCode == 0, "a command ran (exit code %d)", exitCode);
    return 0;
}
