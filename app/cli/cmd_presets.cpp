// `stickslip-cli presets [NAME]`: the built-in parameter sets (../shared/MODEL.md).
#include <cstdio>
#include <iostream>

#include "cli_common.hpp"
#include "core/io/units.hpp"
#include "core/presets.hpp"

namespace stickslip::cli {

namespace {

std::string valueWithUnit(const SimParams& p, const std::string& key) {
    double v = 0;
    getParam(p, key, v);
    std::string unit;
    io::paramUnit(key, unit);
    char buf[96];
    std::snprintf(buf, sizeof buf, "%.6g%s%s", v, unit.empty() ? "" : " ", unit.c_str());
    return buf;
}

// The keys shown in the overview: drive, rig and law.
const char* const kSummaryKeys[] = {"A", "f", "tN", "k", "m", "c", "mu", "eta", "Dc", "C1", "r", "vc", "epsT"};

}  // namespace

void addPresetsCommand(CLI::App& root, int& exitCode) {
    auto* cmd = root.add_subcommand("presets", "List the built-in parameter sets (paper figures) and their values");
    auto name = std::make_shared<std::string>();
    cmd->add_option("name", *name, "Show every parameter of this preset (one of: " + presetNames() + ")");
    cmd->callback([&exitCode, name] {
        if (!name->empty()) {
            Preset p;
            if (!findPreset(*name, p)) {
                reportError("presets", "unknown preset '" + *name + "' (known: " + presetNames() + ")", kBadArguments,
                            exitCode);
                return;
            }
            std::cout << p.name << ": " << p.description << '\n';
            std::cout << "  model = " << toString(p.params.law) << "\n  setup = " << toString(p.params.setup) << '\n';
            for (const std::string& key : paramKeys()) std::cout << "  " << key << " = " << valueWithUnit(p.params, key) << '\n';
            exitCode = kOk;
            return;
        }
        for (const Preset& p : builtinPresets()) {
            std::cout << p.name << "  [" << toString(p.params.law) << ", " << toString(p.params.setup) << "]\n  "
                      << p.description << "\n  ";
            bool first = true;
            for (const char* key : kSummaryKeys) {
                std::cout << (first ? "" : ", ") << key << " = " << valueWithUnit(p.params, key);
                first = false;
            }
            std::cout << "\n\n";
        }
        exitCode = kOk;
    });
}

}  // namespace stickslip::cli
