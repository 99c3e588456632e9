// The Jacobian of one prescribed-slip run (issue 14, item 9): the central differences the fits
// use (2p extra runs of simulateExtendedPrescribed) against one run that carries the forward
// sensitivities (simulatePrescribedSensitivity), on one core, for the bare law (p = 7) and with
// the three effects whose parameters are μ shifts (p = 10). The run: a 2 Hz reversing stroke of
// ±2 mm with a 13 Hz ripple, 20 s at 1 kHz, two law steps per sample (sticks at every reversal).
// Prints the median of 5 repetitions of each, in milliseconds, and the ratio.
// Usage: bench_jacobian [seconds]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "core/identify/prescribed_sensitivity.hpp"

using namespace stickslip;
using namespace stickslip::identify;

namespace {

template <class F>
double medianMs(F&& f) {
    std::vector<double> ms;
    for (int k = 0; k < 5; ++k) {
        const auto t0 = std::chrono::steady_clock::now();
        f();
        ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
    }
    std::sort(ms.begin(), ms.end());
    return ms[2];
}

}  // namespace

int main(int argc, char** argv) {
    const double seconds = argc > 1 ? std::atof(argv[1]) : 20.0;
    std::vector<double> t, g;
    for (long i = 0; i <= std::lround(seconds * 1000); ++i) {
        const double tt = 1e-3 * static_cast<double>(i);
        t.push_back(tt);
        g.push_back(2e-3 * std::sin(2.0 * M_PI * 2.0 * tt) + 1e-4 * std::sin(2.0 * M_PI * 13.0 * tt));
    }
    ExtendedModel bare;
    bare.law.mu = 0.25; bare.law.C1 = 0.25; bare.law.eta_s_per_m = 0.6; bare.law.Dc_m = 20e-6; bare.law.vc_mps = 0.1;
    bare.law.epsT_N_per_m = 1e6;
    bare.tNref_N = 6.2;
    RunContext ctx;
    ctx.normalForce_N = 8.0;
    ExtendedModel shifted = bare;
    setEffect(shifted.effects, "normal_load_mu", {0.01});
    setEffect(shifted.effects, "direction_asymmetry", {0.05});
    setEffect(shifted.effects, "wear_drift", {2.0});
    const std::vector<std::string> law = {"mu", "eta", "Dc", "C1", "r", "vc", "epsT"};
    std::vector<std::string> more = law;
    for (const char* k : {"normal_load_mu.dmu_dtN_per_N", "direction_asymmetry.mu_pos_minus_mu_neg", "wear_drift.dmu_ds_per_m"})
        more.push_back(k);
    std::printf("one run: %zu samples, 2 law steps per sample\n", t.size());
    std::printf("%-28s %4s %12s %16s %16s %8s\n", "model", "p", "run [ms]", "central FD [ms]", "sensitivity [ms]", "ratio");
    for (const auto& [name, m, names] : {std::tuple{"rate-state", bare, law}, std::tuple{"+ load, direction, wear", shifted, more}}) {
        volatile double sink = 0;
        const double run = medianMs([&] { sink = simulateExtendedPrescribed(m, ctx, t, g, nullptr, 2).measuredForce_N.back(); });
        const double sens = medianMs([&] {
            const PrescribedSensitivity s = simulatePrescribedSensitivity(m, ctx, t, g, nullptr, 2, names);
            if (!s.ok()) { std::fprintf(stderr, "%s\n", s.message.c_str()); std::exit(1); }
            sink = s.dMeasured(0, 0);
        });
        const double fd = static_cast<double>(2 * names.size()) * run;
        std::printf("%-28s %4zu %12.2f %16.1f %16.2f %8.1f\n", name, names.size(), run, fd, sens, fd / sens);
        (void)sink;
    }
    return 0;
}
