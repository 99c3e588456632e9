// Sweep benchmarks (issue 3), a plain executable printing figures:
//  1. the Fig. 20 continuation sweep: A from 0.1 to 5 mm, 300 values, 50 settle + 100 sampled
//     cycles each, up then down (state carried over): wall time, and what it found
//     (last stick amplitude, irregular windows per branch);
//  2. a 40 000-point Poincaré section of the Fig. 22 set (A = 0.40 mm): wall time and peak
//     memory (getrusage ru_maxrss).
// Usage: bench_sweep [--steps-per-period N (10000)] [--values N (300)] [--section-points N (40000)]
//                    [--skip-sweep] [--skip-section]
#include <sys/resource.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "core/analysis/poincare.hpp"
#include "core/analysis/stick_threshold.hpp"
#include "core/analysis/sweep.hpp"
#include "core/presets.hpp"

using namespace stickslip;

namespace {

double seconds(std::chrono::steady_clock::time_point a) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - a).count();
}

// CPU time of the process (user + system) [s]: on a shared, loaded machine the wall time
// depends on what else runs; the CPU time does not (much).
double cpuSeconds() {
    rusage u{};
    getrusage(RUSAGE_SELF, &u);
    return static_cast<double>(u.ru_utime.tv_sec + u.ru_stime.tv_sec) +
           1e-6 * static_cast<double>(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

long peakRssKiB() {
    rusage u{};
    getrusage(RUSAGE_SELF, &u);
    return u.ru_maxrss;  // KiB on Linux
}

void printWindows(const SweepResult& r, int direction) {
    double lastStick = 0;
    double start = -1, prev = 0;
    std::string windows;
    int irregular = 0, periodic = 0, stick = 0, maxPeriod = 0;
    for (const auto& pt : r.points) {
        if (pt.direction != direction) continue;
        const MotionClass c = pt.classification.motion;
        if (c == MotionClass::Stick) { ++stick; if (direction > 0 && lastStick < pt.value) lastStick = pt.value; }
        if (c == MotionClass::Periodic) { ++periodic; maxPeriod = std::max(maxPeriod, pt.classification.period); }
        if (c == MotionClass::Irregular) {
            ++irregular;
            if (start < 0) start = pt.value;
            prev = pt.value;
        } else if (start >= 0) {
            char buf[64];
            std::snprintf(buf, sizeof buf, " [%.4f, %.4f]", std::min(start, prev) * 1e3, std::max(start, prev) * 1e3);
            windows += buf;
            start = -1;
        }
    }
    if (start >= 0) {
        char buf[64];
        std::snprintf(buf, sizeof buf, " [%.4f, %.4f]", std::min(start, prev) * 1e3, std::max(start, prev) * 1e3);
        windows += buf;
    }
    std::printf("  %s branch: %d stick, %d periodic (max period %d), %d irregular\n", direction > 0 ? "up" : "down",
                stick, periodic, maxPeriod, irregular);
    if (direction > 0) std::printf("  last stick amplitude (up): %.4f mm\n", lastStick * 1e3);
    std::printf("  irregular windows [mm]:%s\n", windows.empty() ? " none" : windows.c_str());
}

}  // namespace

int main(int argc, char** argv) {
    long n = 10000, sectionPoints = 40000;
    int values = 300;
    bool sweep = true, section = true;
    for (int i = 1; i < argc; ++i) {
        if (!std::strcmp(argv[i], "--steps-per-period") && i + 1 < argc) n = std::atol(argv[++i]);
        else if (!std::strcmp(argv[i], "--values") && i + 1 < argc) values = std::atoi(argv[++i]);
        else if (!std::strcmp(argv[i], "--section-points") && i + 1 < argc) sectionPoints = std::atol(argv[++i]);
        else if (!std::strcmp(argv[i], "--skip-sweep")) sweep = false;
        else if (!std::strcmp(argv[i], "--skip-section")) section = false;
        else { std::fprintf(stderr, "unknown argument %s\n", argv[i]); return 2; }
    }
    if (sweep) {
        Preset pr;
        findPreset("fig20", pr);
        SweepOptions o;
        o.key = "A";
        o.from = 0.1e-3;
        o.to = 5e-3;
        o.steps = values;
        o.direction = SweepDirection::Both;
        o.mode = SweepMode::Continuation;
        o.settleCycles = 50;
        o.sampleCycles = 100;
        o.stepsPerPeriod = n;
        const auto t0 = std::chrono::steady_clock::now();
        const double c0 = cpuSeconds();
        const SweepResult r = bifurcationSweep(pr.params, o);
        const double wall = seconds(t0), cpu = cpuSeconds() - c0;
        const double steps = 2.0 * values * 150.0 * static_cast<double>(n);
        std::printf("Fig. 20 continuation sweep (fig20 preset, eps_T = 1.1e4 N/m): A 0.1-5 mm, %d values, "
                    "50 settle + 100 sampled cycles, up and down, T/%ld\n",
                    values, n);
        std::printf("  status %s%s\n", toString(r.status), r.message.empty() ? "" : (" (" + r.message + ")").c_str());
        std::printf("  wall time %.2f s, CPU time %.2f s, %.3g steps, %.1f ns (CPU) per step\n", wall, cpu, steps,
                    cpu / steps * 1e9);
        std::printf("  closed-form stick threshold A_s = %.4f mm\n", stickThresholdAmplitude(pr.params) * 1e3);
        printWindows(r, +1);
        printWindows(r, -1);
        std::fflush(stdout);
    }
    if (section) {
        Preset pr;
        findPreset("fig22", pr);
        PoincareOptions o;
        o.stepsPerPeriod = n;
        o.settleCycles = 50;
        o.cycles = sectionPoints;
        const long before = peakRssKiB();
        const auto t0 = std::chrono::steady_clock::now();
        const double c0 = cpuSeconds();
        const PoincareSection s = poincareSection(pr.params, o);
        const double wall = seconds(t0), cpu = cpuSeconds() - c0;
        std::printf("Poincare section, Fig. 22 set (A = %.2f mm): %ld points after 50 settle cycles, T/%ld\n",
                    pr.params.drive.amplitude_m * 1e3, sectionPoints, n);
        std::printf("  status %s, %zu points\n", toString(s.status), s.size());
        std::printf("  wall time %.2f s, CPU time %.2f s, peak RSS %.1f MB (before the section: %.1f MB)\n", wall, cpu,
                    peakRssKiB() / 1024.0, before / 1024.0);
    }
    return 0;
}
