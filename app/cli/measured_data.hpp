// Loading measured runs for `fit` and `identify`: --data and --validate-on files with the
// column mapping (--columns), units (--units), manifest and --run-set settings, and the
// set-up (explicit, or dynamics when the files have a slider displacement).
#pragma once

#include <iostream>
#include <string>

#include "commands.hpp"
#include "core/io/dataset.hpp"
#include "core/params.hpp"

namespace stickslip::cli {

// Opt has: data, validateOn, runSets, columns, units (vectors of strings), manifest, setup.
// On failure prints "stickslip-cli <command>: message", sets exitCode (2 bad arguments,
// 3 bad input) and returns false.
template <class Opt>
bool loadMeasuredData(const char* command, const Opt& o, io::Dataset& fitData, io::Dataset& valData,
                      SetupKind& setup, int& exitCode) {
    auto fail = [&](const std::string& msg, int code) {
        std::cerr << "stickslip-cli " << command << ": " << msg << "\n";
        exitCode = code;
        return false;
    };
    io::DatasetOptions dopt;
    dopt.manifestPath = o.manifest;
    dopt.runSets = o.runSets;
    std::string why;
    for (const auto& c : o.columns)
        if (!dopt.mapping.addColumns(c, &why)) return fail(why, kBadArguments);
    for (const auto& u : o.units)
        if (!dopt.mapping.addUnits(u, &why)) return fail(why, kBadArguments);
    io::DatasetError derr;
    if (!io::loadDataset(o.data, dopt, fitData, derr))
        return fail(derr.what(), derr.file == "--run-set" ? kBadArguments : kBadInput);
    if (!o.validateOn.empty()) {
        io::DatasetOptions vopt = dopt;
        vopt.runSets.clear();
        if (!io::loadDataset(o.validateOn, vopt, valData, derr)) return fail(derr.what(), kBadInput);
        for (const std::string& spec : o.runSets) {  // run-sets may name validation files too
            std::string w;
            io::applyRunSet(valData, spec, &w);
        }
    }
    setup = SetupKind::Prescribed;
    if (!o.setup.empty()) {
        if (!parseSetupKind(o.setup, setup))
            return fail("--setup " + o.setup + ": must be prescribed or dynamics", kBadArguments);
    } else if (fitData.runs.front().has(io::Signal::SliderDisp)) {
        setup = SetupKind::Dynamics;
    }
    return true;
}

}  // namespace stickslip::cli
