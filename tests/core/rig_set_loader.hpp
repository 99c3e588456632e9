// Loads a rig data set in the shared synthetic sets' layout (run_01.csv ... with manifest.json)
// the way the CLI does (manifest, cleaning, dynamics set-up), for the identify tests.
#pragma once

#include <memory>

#include <QtTest/QtTest>

#include <algorithm>
#include <string>
#include <vector>

#include "core/identify/identify.hpp"
#include "core/identify/preprocess.hpp"
#include "core/io/dataset.hpp"

namespace rigset {

// Cleans a recording as loadRuns does (IdentifyOptions::reprepare for the simulated null).
inline const auto reprepare =
    stickslip::identify::recordingPreparer(stickslip::identify::PreprocessSettings{}, stickslip::SetupKind::Dynamics);

// The first `nRuns` runs of the set in `dir`, each cut to its first `maxSeconds`; with
// `withRecordings` each run keeps its (cut) recording, for the simulated null.
inline std::vector<stickslip::identify::IdentifyRun> loadRuns(const std::string& dir, int nRuns, double maxSeconds,
                                                              bool withRecordings = false) {
    using namespace stickslip;
    using namespace stickslip::identify;
    std::vector<std::string> files;
    for (int i = 1; i <= nRuns; ++i) files.push_back(dir + "/run_0" + std::to_string(i) + ".csv");
    io::DatasetOptions dopt;
    dopt.manifestPath = dir + "/manifest.json";
    io::Dataset ds;
    io::DatasetError err;
    if (!io::loadDataset(files, dopt, ds, err)) qFatal("%s", err.what().c_str());
    std::vector<IdentifyRun> runs;
    for (io::Run& r : ds.runs) {
        const std::vector<double>& t = r[io::Signal::Time];
        const size_t keep = std::lower_bound(t.begin(), t.end(), t.front() + maxSeconds) - t.begin();
        for (std::vector<double>& ch : r.channels)
            if (ch.size() > keep) ch.resize(keep);
        IdentifyRun ir;
        std::string why;
        if (!reprepare(r, ir, why)) qFatal("%s", why.c_str());
        if (withRecordings) ir.recording = std::make_shared<const io::Run>(r);
        runs.push_back(std::move(ir));
    }
    return runs;
}

}  // namespace rigset
