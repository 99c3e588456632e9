// Wall time of fitting all 12 real friction-damper runs jointly (prescribed set-up), for the
// rate-state law (μ, η, D_c, v_c, ε_T free, C1 = μ) and the Coulomb law (μ, ε_T free).
// How the data are reduced (defaults of PreprocessSettings / PredictSettings):
//  - zero-phase 60 Hz band-stop + 100 Hz low-pass, then only the steady-amplitude cycles are
//    kept (the ramps up and down are trimmed: moving amplitude ≥ 90 % of its maximum);
//  - every 4th sample (1024 Hz → 256 Hz) is a law step boundary, with 8 law steps in between;
//  - the law is started 0.25 s before the window from the measured force.
// Predictions run in parallel (DatasetFitSettings::threads, default: all cores; every
// (parameter point, run) pair is one task, so the 2p displaced points of a numeric Jacobian are
// spread too); the results do not depend on the thread count. Up to `multistarts` starts: the
// rest are skipped once two ended at the same best cost (DatasetFitSettings::agreeingStarts).
// Wall and process CPU time are printed.
// Usage: bench_fit [data-folder] [multistarts] [threads] [agreeing-starts, 0 = run all]
#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "core/heap_settings.hpp"
#include "core/identify/fit.hpp"

using namespace stickslip;
using namespace stickslip::identify;

namespace {
double cpuSeconds() {
    rusage u{};
    getrusage(RUSAGE_SELF, &u);
    return static_cast<double>(u.ru_utime.tv_sec + u.ru_stime.tv_sec) + 1e-6 * static_cast<double>(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}
}  // namespace

int main(int argc, char** argv) {
    stickslip::applyHeapSettings();  // as stickslip-cli and the app do
    const std::string dir = argc > 1 ? argv[1] : std::string(STICKSLIP_SHARED_DIR) + "/data/real/friction-damper";
    const int starts = argc > 2 ? std::atoi(argv[2]) : 3;
    const int threads = argc > 3 ? std::atoi(argv[3]) : 0;
    // 4th argument: starts that must agree before the rest are skipped (default: the
    // DatasetFitSettings default, 2; 0 = run all starts).
    const int agreeing = argc > 4 ? std::atoi(argv[4]) : DatasetFitSettings{}.agreeingStarts;
    std::vector<std::string> files;
    for (const auto& e : std::filesystem::directory_iterator(dir))
        if (e.path().extension() == ".csv") files.push_back(e.path().string());
    std::sort(files.begin(), files.end());
    const auto t0 = std::chrono::steady_clock::now();
    io::Dataset ds;
    io::DatasetError err;
    if (!io::loadDataset(files, {}, ds, err)) {
        std::fprintf(stderr, "%s\n", err.what().c_str());
        return 3;
    }
    std::vector<CleanRun> runs;
    for (const io::Run& r : ds.runs) {
        CleanRun c;
        std::string why;
        if (!preprocessRun(r, PreprocessSettings{}, c, &why)) {
            std::fprintf(stderr, "%s\n", why.c_str());
            return 3;
        }
        runs.push_back(std::move(c));
    }
    const double tLoad = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::printf("loaded and preprocessed %zu runs in %.2f s wall, %.2f s CPU\n", runs.size(), tLoad, cpuSeconds());
    for (LawKind law : {LawKind::RateState, LawKind::Coulomb}) {
        DatasetFitSettings st;
        st.setup = SetupKind::Prescribed;
        st.law = law;
        st.multistarts = starts;
        st.threads = threads;
        st.agreeingStarts = agreeing;
        const double c1 = cpuSeconds();
        const auto t1 = std::chrono::steady_clock::now();
        const DatasetFit f = fitDataset(runs, {}, st);
        const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count();
        const double cpu = cpuSeconds() - c1;
        if (!f.ok) {
            std::fprintf(stderr, "%s: %s\n", toString(law), f.message.c_str());
            return 4;
        }
        std::printf("%-10s joint fit of %zu runs: wall %.2f s, CPU %.2f s, %d of %d starts%s (best %d), %ld residual evaluations, "
                    "%zu residuals, fit NRMSE %.4f, tau_int %.2f\n",
                    toString(law), runs.size(), wall, cpu, f.fit.startsTried, starts,
                    f.fit.stoppedEarly ? " (two agreed)" : "", f.fit.bestStart, f.fit.residualEvaluations,
                    f.fit.residualCount, f.fitNrmse, f.tauInt);
        for (size_t i = 0; i < f.fit.names.size(); ++i)
            std::printf("    %-5s = %.6g +- %.3g (iid %.3g)%s\n", f.fit.names[i].c_str(), f.fit.values[i], f.fit.stderrs[i],
                        f.stderrsIid[i], f.fit.free[i] ? "" : " (fixed)");
        std::printf("    %s\n    start costs:", f.fit.identifiabilityMessage.c_str());
        for (double c : f.fit.startCosts) std::printf(" %.6g", c);
        std::printf("\n");
    }
    std::printf("total: wall %.2f s, CPU %.2f s\n", std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(),
                cpuSeconds());
    return 0;
}
