// `stickslip-cli analyze`: the paper's signal analyses of one run file (simulated by
// `simulate`, or measured), found by column name: power spectrum peaks, autocorrelation
// decay time, stage–slider phase lag, friction-loop orientation counts and the 0–1 test.
// The analyses themselves are core/analysis/analyze_run.hpp (shared with the Python module).
#include <memory>
#include <nlohmann/json.hpp>

#include "cli_common.hpp"
#include "core/analysis/analyze_run.hpp"
#include "core/io/csv_table.hpp"
#include "core/version.hpp"

namespace stickslip::cli {

namespace {

struct AnalyzeOptions {
    std::string input, out = "-";
    double frequency = 0;        // forcing frequency [Hz]; 0 = from the file / the stage spectrum
    double naturalFrequency = 0; // ω_n [rad/s]; 0 = √(k/m) from '#' lines, else not reported
    double maxLag = 2.0;         // autocorrelation lags up to [s]
};

void runAnalyze(const AnalyzeOptions& o, int& exitCode) {
    io::CsvTable t;
    io::CsvError err;
    if (!io::readCsvTable(o.input, t, err)) {
        reportError("analyze", err.what(), kBadInput, exitCode);
        return;
    }
    AnalyzeSettings settings;
    settings.frequency_Hz = o.frequency;
    settings.naturalFrequency_rad_s = o.naturalFrequency;
    settings.maxLag_s = o.maxLag;
    nlohmann::json j;
    std::string error;
    if (!analyzeRunTable(t, o.input, settings, std::string("stickslip-cli ") + kVersion, j, &error)) {
        reportError("analyze", error, kBadInput, exitCode);
        return;
    }
    if (!io::writeFileAtomically(o.out, j.dump(2) + "\n", &error)) {
        reportError("analyze", error, kBadInput, exitCode);
        return;
    }
    exitCode = kOk;
}

}  // namespace

void addAnalyzeCommand(CLI::App& root, int& exitCode) {
    auto opts = std::make_shared<AnalyzeOptions>();
    auto* cmd = root.add_subcommand("analyze", "Spectrum peaks, autocorrelation decay, phase lag, loop orientation "
                                               "and 0-1 test of a run CSV (simulated or measured), as JSON");
    cmd->add_option("--input", opts->input, "Run CSV with a time_s column (and stage/slider/force columns)")
        ->required();
    cmd->add_option("--out", opts->out, "JSON output ('-' = stdout)")->capture_default_str();
    cmd->add_option("--frequency", opts->frequency, "Forcing frequency [Hz] (default: from the file or the stage spectrum)");
    cmd->add_option("--natural-frequency", opts->naturalFrequency,
                    "Natural frequency sqrt(k/m) [rad/s] for the non-dimensional phase lag (default: from '# k', '# m' lines)");
    cmd->add_option("--max-lag", opts->maxLag, "Longest autocorrelation lag [s]")->capture_default_str();
    cmd->callback([opts, &exitCode] { runAnalyze(*opts, exitCode); });
}

}  // namespace stickslip::cli
