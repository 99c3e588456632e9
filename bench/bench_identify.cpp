// Wall time of the identify loop (issue 6): all 12 real damper runs (prescribed slip) and one
// synthetic dataset (D05, dynamics set-up). Target ≤ 120 s each. Prints what it found.
#include <sys/resource.h>

#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

#include "core/heap_settings.hpp"
#include "core/identify/identify.hpp"
#include "core/identify/preprocess.hpp"
#include "core/io/dataset.hpp"

using namespace stickslip;
using namespace stickslip::identify;

static double cpuSeconds() {
    rusage u{};
    getrusage(RUSAGE_SELF, &u);
    return u.ru_utime.tv_sec + u.ru_stime.tv_sec + 1e-6 * (u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

static int runCase(const char* title, const std::vector<std::string>& files, const std::string& manifest, SetupKind setup) {
    io::DatasetOptions dopt;
    dopt.manifestPath = manifest;
    io::Dataset ds;
    io::DatasetError err;
    const auto t0 = std::chrono::steady_clock::now();
    const double c0 = cpuSeconds();
    if (!io::loadDataset(files, dopt, ds, err)) { std::fprintf(stderr, "%s\n", err.what().c_str()); return 1; }
    std::vector<IdentifyRun> runs;
    PreprocessSettings pre;
    for (const io::Run& r : ds.runs) {
        CleanRun c;
        std::string e;
        IdentifyRun ir;
        if (!preprocessRun(r, pre, c, &e) || !makeIdentifyRun(c, setup, ir, &e)) { std::fprintf(stderr, "%s\n", e.c_str()); return 1; }
        runs.push_back(std::move(ir));
    }
    const IdentifyResult res = identifyEffects(std::move(runs), IdentifyOptions{});
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::string added;
    for (const auto& e : res.effectsAdded) added += e.name + " ";
    const double cpu = cpuSeconds() - c0;
    std::printf("%-28s wall %7.1f s, CPU %7.1f s (loop %7.1f s wall, %ld fits, residual %s)  added: %s  held-out NRMSE %.4f -> %.4f  "
                "unexplained %s%s\n",
                title, wall, cpu, res.wallTime_s, res.fits, res.residual.c_str(), added.empty() ? "none " : added.c_str(), res.before.validationNrmse,
                res.after.validationNrmse, res.unexplained ? "yes" : "no", res.ok ? "" : (" FAILED: " + res.message).c_str());
    return res.ok ? 0 : 1;
}

int main() {
    stickslip::applyHeapSettings();  // as stickslip-cli and the app do
    const std::string shared = STICKSLIP_SHARED_DIR;
    std::vector<std::string> damper;
    for (const char* f : {"0.5", "1"})
        for (const char* lb : {"30", "36"})
            for (const char* a : {"0.5", "1", "1.5"})
                damper.push_back(shared + "/data/real/friction-damper/" + f + "Hz_" + lb + "lb_" + a + "in.csv");
    std::vector<std::string> d05;
    for (int i = 1; i <= 5; ++i) d05.push_back(shared + "/data/synthetic/D05/run_0" + std::to_string(i) + ".csv");
    int rc = 0;
    rc |= runCase("damper, 12 runs (prescribed)", damper, "", SetupKind::Prescribed);
    rc |= runCase("synthetic D05 (dynamics)", d05, shared + "/data/synthetic/D05/manifest.json", SetupKind::Dynamics);
    return rc;
}
