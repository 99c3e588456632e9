// `stickslip-cli synthesize`: a rig-like synthetic data set with a known answer
// (core/identify/synthesize.hpp): five run CSVs, manifest.json and answer.json in one directory,
// for checking `identify` on many sets (false alarms on sets without an effect, detections on
// sets with one) instead of the few that were shared.
#include <filesystem>
#include <memory>

#include "cli_common.hpp"
#include "core/identify/pipeline.hpp"
#include "core/identify/synthesize.hpp"
#include "core/io/csv_table.hpp"

namespace stickslip::cli {

namespace {

struct SynthesizeOptions {
    identify::SynthOptions synth;
    std::string out, name;
    std::vector<std::string> effects;  // NAME=v1,v2,...
};

// "NAME=v1,v2" -> name and values; false with a message naming the argument.
bool parseEffect(const std::string& arg, std::pair<std::string, std::vector<double>>& e, std::string& message) {
    const size_t eq = arg.find('=');
    if (eq == std::string::npos || eq == 0) {
        message = "--effect '" + arg + "': expected NAME=VALUE[,VALUE...] (parameters in catalogue order)";
        return false;
    }
    e.first = arg.substr(0, eq);
    e.second.clear();
    for (const std::string& v : identify::splitList(arg.substr(eq + 1))) {
        size_t used = 0;
        double x = 0;
        try {
            x = std::stod(v, &used);
        } catch (...) {
            used = 0;
        }
        if (used != v.size() || v.empty()) {
            message = "--effect '" + arg + "': '" + v + "' is not a number";
            return false;
        }
        e.second.push_back(x);
    }
    return true;
}

void runSynthesize(SynthesizeOptions& o, int& exitCode) {
    std::string message;
    o.synth.effects.clear();
    for (const std::string& a : o.effects) {
        std::pair<std::string, std::vector<double>> e;
        if (!parseEffect(a, e, message)) return reportError("synthesize", message, kBadArguments, exitCode);
        o.synth.effects.push_back(std::move(e));
    }
    if (const ParamIssues is = o.synth.validate(); !is.empty())
        return reportError("synthesize", formatIssues(is), kBadArguments, exitCode);
    const identify::SynthResult r = identify::synthesizeRigSet(o.synth);
    if (!r.ok) return reportError("synthesize", r.message, kRunFailed, exitCode);
    std::error_code ec;
    std::filesystem::create_directories(o.out, ec);
    if (ec) return reportError("synthesize", o.out + ": " + ec.message(), kBadInput, exitCode);
    const std::string dir = o.out + "/";
    nlohmann::json manifest = r.manifest, answer = r.answer;
    const std::string name = o.name.empty() ? std::filesystem::path(o.out).filename().string() : o.name;
    manifest["dataset"] = name;
    answer["dataset"] = name;
    for (const identify::SynthRun& run : r.runs)
        if (!io::writeFileAtomically(dir + run.file, identify::synthRunCsv(run), &message))
            return reportError("synthesize", message, kBadInput, exitCode);
    if (!io::writeFileAtomically(dir + "manifest.json", manifest.dump(1) + "\n", &message) ||
        !io::writeFileAtomically(dir + "answer.json", answer.dump(1) + "\n", &message))
        return reportError("synthesize", message, kBadInput, exitCode);
    exitCode = kOk;
}

}  // namespace

void addSynthesizeCommand(CLI::App& root, int& exitCode) {
    auto o = std::make_shared<SynthesizeOptions>();
    auto* cmd = root.add_subcommand(
        "synthesize", "Write a rig-like synthetic data set with a known answer (runs, manifest.json, answer.json)");
    cmd->add_option("--out", o->out, "Directory to write (created if missing)")->required();
    cmd->add_option("--name", o->name, "Data set name in the manifest (default: the directory's name)");
    cmd->add_option("--seed", o->synth.seed, "Random seed: the drawn law, rig, runs and noise")->capture_default_str();
    cmd->add_option("--runs", o->synth.runs, "Number of runs (1-5)")->capture_default_str();
    cmd->add_option("--seconds", o->synth.seconds, "Recorded length of each run [s]")->capture_default_str();
    cmd->add_option("--steps-per-sample", o->synth.stepsPerSample, "Integration steps per recorded sample")
        ->capture_default_str();
    cmd->add_option("--effect", o->effects,
                    "Effect to switch on: NAME=VALUE[,VALUE...], its parameters in catalogue order (repeatable), e.g. "
                    "backlash=4e-5, stick_healing=0.0115,0.00157,1.66e-5");
    cmd->add_option("--noise-scale", o->synth.noiseScale,
                    "Multiply the measurement noise and the mains pickup by this, 0 ... 100 (0: the noise-free twin of "
                    "the set: same law, runs and draws)")
        ->capture_default_str();
    cmd->callback([o, &exitCode] { runSynthesize(*o, exitCode); });
}

}  // namespace stickslip::cli
