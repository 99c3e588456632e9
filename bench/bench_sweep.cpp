// Sweep benchmarks (issue 3), a plain executable printing figures:
//  1. the Fig. 20 continuation sweep: A from 0.1 to 5 mm, 300 values, 50 settle + 100 sampled
//     cycles each, both directions: wall and CPU time, threads used, and what it found (last
//     stick amplitude, irregular windows per branch, where the branches differ: hysteresis).
//     By default the two branches run concurrently (SweepOptions::concurrentBranches: the down
//     branch starts from rest at the top value after a lead-in there, instead of from the end of
//     the up branch); --sequential runs the paper's way (down continues from the up branch's end,
//     one thread); --compare runs both and counts the down-branch values whose class differs;
//     --lyapunov also computes the largest Lyapunov exponent per value (as the CLI does by
//     default): sequentially its companion trajectory runs on the second thread.
//     --reference N instead compares classifications: the same A range, values independent
//     (each from rest), at the stepping asked for and at the fine fixed step T/N, and counts the
//     values whose class/period agree (the fine step is first order: T/128000 is ~13x closer to
//     the exact motion than the presets' T/10000; issue 15, item 3).
//  2. a 40 000-point Poincaré section of the Fig. 22 set (A = 0.40 mm): wall time and peak
//     memory (getrusage ru_maxrss).
// Usage: bench_sweep [--steps-per-period N (8000)] [--values N (300)] [--threads N (0 = all)]
//                    [--sequential | --compare] [--lyapunov] [--section-points N (40000)]
//                    [--skip-sweep] [--skip-section] [--tolerance TOL (0: fixed step)]
//                    [--reference N (0: none)]
// With --tolerance the runs are error-controlled (section_stepping.hpp): the step count is the
// integrator's, not cycles x N, so only wall/CPU time and cycles per second are printed.
// (8000 steps per period: the step bench_core finds for 1e-3 error/amplitude.)
#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "core/analysis/parallel.hpp"

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
        if (c == MotionClass::Stick) { ++stick; lastStick = std::max(lastStick, pt.value); }
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
    std::printf("  %s branch: %d stick, %d periodic (max period %d), %d irregular; highest stick amplitude %.4f mm\n",
                direction > 0 ? "up" : "down", stick, periodic, maxPeriod, irregular, lastStick * 1e3);
    std::printf("    irregular windows [mm]:%s\n", windows.empty() ? " none" : windows.c_str());
}

// Hysteresis: values where the up and down branches of one sweep end in different classes.
void printHysteresis(const SweepResult& r) {
    std::vector<const SweepPoint*> up, down;
    for (const auto& pt : r.points) (pt.direction > 0 ? up : down).push_back(&pt);
    std::reverse(down.begin(), down.end());
    int differ = 0;
    std::string where;
    for (std::size_t i = 0; i < std::min(up.size(), down.size()); ++i) {
        const Classification &a = up[i]->classification, &b = down[i]->classification;
        if (a.motion == b.motion && a.period == b.period) continue;
        if (++differ <= 8) {
            char buf[96];
            std::snprintf(buf, sizeof buf, " %.4f (%s%d/%s%d)", up[i]->value * 1e3, toString(a.motion), a.period,
                          toString(b.motion), b.period);
            where += buf;
        }
    }
    std::printf("  up vs down (hysteresis): %d of %zu values differ in class/period%s%s\n", differ, up.size(),
                differ ? ", first [mm] (up/down):" : "", where.c_str());
}

// Down-branch values whose class differs between two sweeps (sequential vs concurrent).
void compareDownBranches(const SweepResult& a, const SweepResult& b) {
    int n = 0, differ = 0;
    std::string where;
    for (const auto& p : a.points) {
        if (p.direction > 0) continue;
        for (const auto& q : b.points) {
            if (q.direction > 0 || q.value != p.value) continue;
            ++n;
            const Classification &x = p.classification, &y = q.classification;
            if (x.motion != y.motion || x.period != y.period) {
                if (++differ <= 8) {
                    char buf[96];
                    std::snprintf(buf, sizeof buf, " %.4f (%s%d/%s%d)", p.value * 1e3, toString(x.motion), x.period,
                                  toString(y.motion), y.period);
                    where += buf;
                }
            }
        }
    }
    std::printf("Down branch, sequential vs concurrent: %d of %d values differ in class/period%s%s\n", differ, n,
                differ ? ", first [mm] (seq/conc):" : "", where.c_str());
}

double load1() {
    double l[1] = {0};
    return getloadavg(l, 1) == 1 ? l[0] : -1.0;
}

// "T/8000" or "adaptive, tolerance 0.0001", as the printed lines name a stepping.
std::string steppingName(long n, double tolerance) {
    char b[64];
    if (tolerance > 0) std::snprintf(b, sizeof b, "adaptive, tolerance %g", tolerance);
    else std::snprintf(b, sizeof b, "T/%ld", n);
    return b;
}

// The benchmark's sweep of the Fig. 20 range: A 0.1-5 mm, 50 settle + 100 sampled cycles.
SweepOptions fig20Range(int values, long n, int threads) {
    SweepOptions o;
    o.key = "A";
    o.from = 0.1e-3;
    o.to = 5e-3;
    o.steps = values;
    o.settleCycles = 50;
    o.sampleCycles = 100;
    o.stepsPerPeriod = n;
    o.threads = threads;
    return o;
}

SimParams fig20Params(double tolerance) {
    Preset pr;
    findPreset("fig20", pr);
    pr.params.integration.tolerance = tolerance;
    return pr.params;
}

SweepResult runFig20Sweep(int values, long n, int threads, bool concurrent, bool lyapunov, double tolerance) {
    const SimParams p = fig20Params(tolerance);
    SweepOptions o = fig20Range(values, n, threads);
    o.direction = SweepDirection::Both;
    o.mode = SweepMode::Continuation;
    o.concurrentBranches = concurrent;
    o.lyapunov = lyapunov;
    const int used = concurrent || lyapunov ? workerCount(threads, 2) : 1;
    const double loadBefore = load1();
    const auto t0 = std::chrono::steady_clock::now();
    const double c0 = cpuSeconds();
    SweepResult r = bifurcationSweep(p, o);
    const double wall = seconds(t0), cpu = cpuSeconds() - c0;
    // Steps: 150 cycles per value and branch, plus the concurrent down branch's lead-in.
    // With the Lyapunov exponent the companion trajectory adds the 100 sampled cycles again.
    const double cycles = 2.0 * values * (lyapunov ? 250.0 : 150.0) + (concurrent ? 150.0 : 0.0);
    const double steps = cycles * static_cast<double>(n);
    const std::string stepping = steppingName(n, tolerance);
    std::printf("Fig. 20 continuation sweep (fig20 preset, eps_T = 1.1e4 N/m): A 0.1-5 mm, %d values, "
                "50 settle + 100 sampled cycles, up and down, %s\n",
                values, stepping.c_str());
    std::printf("  Lyapunov exponent: %s\n", lyapunov ? (concurrent ? "yes, companion on the branch's thread"
                                                                   : "yes, companion on a second thread")
                                                        : "no");
    std::printf("  branches: %s\n", concurrent ? "concurrent (down branch from rest at 5 mm after a 150-cycle lead-in)"
                                               : "sequential (down branch continues from the end of the up branch)");
    std::printf("  status %s%s\n", toString(r.status), r.message.empty() ? "" : (" (" + r.message + ")").c_str());
    if (tolerance > 0)
        std::printf("  wall time %.2f s, CPU time %.2f s, threads used %d, %.0f cycles per wall second\n", wall, cpu,
                    used, cycles / wall);
    else
        std::printf("  wall time %.2f s, CPU time %.2f s, threads used %d, %.3g steps, %.1f ns (CPU) per step, "
                    "%.0f cycles per wall second\n",
                    wall, cpu, used, steps, cpu / steps * 1e9, cycles / wall);
    std::printf("  load average (1 min) before %.2f, after %.2f\n", loadBefore, load1());
    printWindows(r, +1);
    printWindows(r, -1);
    printHysteresis(r);
    std::fflush(stdout);
    return r;
}

// Independent sweep of the Fig. 20 range at one stepping (each value from rest).
SweepResult independentFig20(int values, long n, int threads, double tolerance) {
    SweepOptions o = fig20Range(values, n, threads);
    o.direction = SweepDirection::Up;
    o.mode = SweepMode::Independent;
    o.lyapunov = false;
    return bifurcationSweep(fig20Params(tolerance), o);
}

// The classification of the stepping asked for against a fine fixed step, value by value.
int compareWithReference(int values, long n, int threads, double tolerance, long refN) {
    const std::string stepping = steppingName(n, tolerance);
    auto t0 = std::chrono::steady_clock::now();
    const SweepResult ref = independentFig20(values, refN, threads, 0.0);
    const double refWall = seconds(t0);
    t0 = std::chrono::steady_clock::now();
    const SweepResult r = independentFig20(values, n, threads, tolerance);
    const double wall = seconds(t0);
    if (ref.status != RunStatus::Ok || r.status != RunStatus::Ok || ref.points.size() != r.points.size()) {
        std::fprintf(stderr, "sweep failed: %s%s\n", ref.message.c_str(), r.message.c_str());
        return 1;
    }
    int agree = 0;
    std::string where;
    for (std::size_t i = 0; i < r.points.size(); ++i) {
        const Classification &a = r.points[i].classification, &b = ref.points[i].classification;
        if (a.motion == b.motion && a.period == b.period) {
            ++agree;
            continue;
        }
        char buf[96];
        std::snprintf(buf, sizeof buf, " %.3f (%s%d/%s%d)", r.points[i].value * 1e3, toString(a.motion), a.period,
                      toString(b.motion), b.period);
        where += buf;
    }
    std::printf("Fig. 20 range, A 0.1-5 mm, %d values independent (from rest), 50 settle + 100 sampled cycles, "
                "period test 1e-4\n",
                values);
    std::printf("  %s against the fixed step T/%ld: %d of %zu values agree in class/period (%.1f s; reference %.1f s)\n",
                stepping.c_str(), refN, agree, r.points.size(), wall, refWall);
    std::printf("  differ [mm] (%s / T/%ld):%s\n", stepping.c_str(), refN, where.empty() ? " none" : where.c_str());
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    long n = 8000, sectionPoints = 40000;
    double tolerance = 0.0;
    int values = 300, threads = 0;
    long reference = 0;
    bool sweep = true, section = true, sequential = false, compare = false, lyapunov = false;
    for (int i = 1; i < argc; ++i) {
        if (!std::strcmp(argv[i], "--steps-per-period") && i + 1 < argc) n = std::atol(argv[++i]);
        else if (!std::strcmp(argv[i], "--values") && i + 1 < argc) values = std::atoi(argv[++i]);
        else if (!std::strcmp(argv[i], "--threads") && i + 1 < argc) threads = std::atoi(argv[++i]);
        else if (!std::strcmp(argv[i], "--section-points") && i + 1 < argc) sectionPoints = std::atol(argv[++i]);
        else if (!std::strcmp(argv[i], "--sequential")) sequential = true;
        else if (!std::strcmp(argv[i], "--compare")) compare = true;
        else if (!std::strcmp(argv[i], "--lyapunov")) lyapunov = true;
        else if (!std::strcmp(argv[i], "--tolerance") && i + 1 < argc) tolerance = std::atof(argv[++i]);
        else if (!std::strcmp(argv[i], "--reference") && i + 1 < argc) reference = std::atol(argv[++i]);
        else if (!std::strcmp(argv[i], "--skip-sweep")) sweep = false;
        else if (!std::strcmp(argv[i], "--skip-section")) section = false;
        else { std::fprintf(stderr, "unknown argument %s\n", argv[i]); return 2; }
    }
    if (n < 1 || values < 1 || threads < 0 || sectionPoints < 1 || reference < 0) {
        std::fprintf(stderr,
                     "--steps-per-period, --values and --section-points must be >= 1, --threads and --reference >= 0\n");
        return 2;
    }
    if (reference > 0) return compareWithReference(values, n, threads, tolerance, reference);
    if (sweep) {
        Preset pr;
        findPreset("fig20", pr);
        std::printf("closed-form stick threshold A_s = %.4f mm\n", stickThresholdAmplitude(pr.params) * 1e3);
        if (compare) {
            const SweepResult seq = runFig20Sweep(values, n, threads, false, lyapunov, tolerance);
            const SweepResult conc = runFig20Sweep(values, n, threads, true, lyapunov, tolerance);
            compareDownBranches(seq, conc);
        } else {
            runFig20Sweep(values, n, threads, !sequential, lyapunov, tolerance);
        }
    }
    if (section) {
        Preset pr;
        findPreset("fig22", pr);
        pr.params.integration.tolerance = tolerance;
        PoincareOptions o;
        o.stepsPerPeriod = n;
        o.settleCycles = 50;
        o.cycles = sectionPoints;
        const long before = peakRssKiB();
        const auto t0 = std::chrono::steady_clock::now();
        const double c0 = cpuSeconds();
        const PoincareSection s = poincareSection(pr.params, o);
        const double wall = seconds(t0), cpu = cpuSeconds() - c0;
        if (tolerance > 0)
            std::printf("Poincare section, Fig. 22 set (A = %.2f mm): %ld points after 50 settle cycles, adaptive, "
                        "tolerance %g (samples from the dense output)\n",
                        pr.params.drive.amplitude_m * 1e3, sectionPoints, tolerance);
        else
            std::printf("Poincare section, Fig. 22 set (A = %.2f mm): %ld points after 50 settle cycles, T/%ld\n",
                        pr.params.drive.amplitude_m * 1e3, sectionPoints, n);
        std::printf("  status %s, %zu points\n", toString(s.status), s.size());
        std::printf("  wall time %.2f s, CPU time %.2f s, peak RSS %.1f MB (before the section: %.1f MB)\n", wall, cpu,
                    peakRssKiB() / 1024.0, before / 1024.0);
    }
    return 0;
}
