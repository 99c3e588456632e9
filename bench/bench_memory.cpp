// Peak memory and cancel latency of stickslip-cli's long jobs (issue: hardening, item 6), a
// plain executable printing figures. Every job runs as a child process; its peak resident set
// comes from wait4()'s rusage of that child (ru_maxrss), so the figures are the CLI's own.
//   memory (default): (a) `simulate --preset fig20` over 1 000 and 10 000 recorded cycles
//     written to a CSV; (b) periodicity maps of 100 x 100 and 300 x 300 cells with few cycles
//     and a coarse step per cell (--settle 2 --samples 4 --steps-per-period 200) so the large
//     one finishes in minutes. Two sizes each, to show how the peak scales.
//   --cancel: SIGINT to simulate, sweep (continuation and independent), map, fit and identify
//     (prescribed and dynamics) S seconds after each started (first output on stderr); prints
//     signal -> exit latency, the exit code (5 = cancelled) and whether an output file was left.
// Usage: bench_memory [--cancel [--after S (1)]] [--cycles N (10000)] [--map N (300)] [--keep DIR]
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

extern char** environ;

namespace {

using Clock = std::chrono::steady_clock;

struct Child {
    int exitCode = -1;     // -1: killed by a signal
    double wall_s = 0;
    long maxRss_kB = 0;
    double cancelLatency_s = -1;  // signal -> exit, when a signal was sent
};

// Runs `args` (argv[0] = the CLI); with signalAfter_s >= 0 sends SIGINT that long after the
// child's first stderr output (or its start, when waitForOutput is false).
Child run(const std::vector<std::string>& args, double signalAfter_s = -1, bool waitForOutput = true) {
    int errPipe[2];
    if (::pipe(errPipe) != 0) return {};
    posix_spawn_file_actions_t fa;
    posix_spawn_file_actions_init(&fa);
    posix_spawn_file_actions_adddup2(&fa, errPipe[1], STDERR_FILENO);
    posix_spawn_file_actions_addclose(&fa, errPipe[0]);
    posix_spawn_file_actions_addopen(&fa, STDOUT_FILENO, "/dev/null", O_WRONLY, 0);
    std::vector<char*> argv;
    for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    const auto t0 = Clock::now();
    pid_t pid = 0;
    const int rc = posix_spawn(&pid, argv[0], &fa, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&fa);
    ::close(errPipe[1]);
    if (rc != 0) {
        std::fprintf(stderr, "cannot start %s: %s\n", argv[0], std::strerror(rc));
        ::close(errPipe[0]);
        return {};
    }
    auto secondsSince = [](Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); };
    Clock::time_point signalled{};
    bool sent = false, sawOutput = !waitForOutput;
    Clock::time_point outputAt = t0;
    std::string err;
    for (;;) {
        pollfd p{errPipe[0], POLLIN, 0};
        if (::poll(&p, 1, 20) > 0) {
            char buf[4096];
            const ssize_t n = ::read(errPipe[0], buf, sizeof buf);
            if (n > 0) {
                err.append(buf, static_cast<size_t>(n));
                if (!sawOutput) outputAt = Clock::now();
                sawOutput = true;
            } else {
                p.fd = -1;
            }
        }
        if (signalAfter_s >= 0 && !sent && sawOutput && secondsSince(outputAt) >= signalAfter_s) {
            ::kill(pid, SIGINT);
            signalled = Clock::now();
            sent = true;
        }
        int status = 0;
        rusage ru{};
        const pid_t w = ::wait4(pid, &status, WNOHANG, &ru);
        if (w == pid) {
            Child c;
            c.wall_s = secondsSince(t0);
            c.maxRss_kB = ru.ru_maxrss;
            c.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
            if (sent) c.cancelLatency_s = secondsSince(signalled);
            ::close(errPipe[0]);
            return c;
        }
    }
}

long fileSize(const std::string& path) {
    struct stat st {};
    return ::stat(path.c_str(), &st) == 0 ? static_cast<long>(st.st_size) : -1;
}

void memory(const std::string& dir, long cycles, int mapN) {
    std::printf("== peak memory (ru_maxrss of the child) ==\n");
    for (long n : {cycles / 10, cycles}) {
        const std::string out = dir + "/run.csv";
        const Child c = run({STICKSLIP_CLI, "simulate", "--preset", "fig20", "--cycles", std::to_string(n), "--out", out});
        std::printf("simulate fig20 --cycles %6ld: exit %d, %7.1f s, peak RSS %8.1f MB, CSV %8.1f MB\n", n,
                    c.exitCode, c.wall_s, c.maxRss_kB / 1024.0, fileSize(out) / 1048576.0);
        std::fflush(stdout);
        ::unlink(out.c_str());
    }
    for (int n : {mapN / 3, mapN}) {
        const std::string out = dir + "/map.csv", N = std::to_string(n);
        const Child c = run({STICKSLIP_CLI, "map", "--preset", "fig20", "--from", "0.2mm", "--to", "5mm", "--steps", N,
                             "--param2", "f", "--from2", "2", "--to2", "10", "--steps2", N, "--settle", "2",
                             "--samples", "4", "--steps-per-period", "200", "--out", out});
        std::printf("map %3d x %-3d (settle 2, samples 4, 200 steps/period): exit %d, %7.1f s, peak RSS %8.1f MB, "
                    "CSV %6.2f MB\n", n, n, c.exitCode, c.wall_s, c.maxRss_kB / 1024.0, fileSize(out) / 1048576.0);
        std::fflush(stdout);
        ::unlink(out.c_str());
    }
}

void cancelLatencies(const std::string& dir, double after_s) {
    const std::string shared = STICKSLIP_SHARED_DIR "/data/real/friction-damper/";
    const std::string d05 = STICKSLIP_SHARED_DIR "/data/synthetic/D05/";
    struct Job {
        const char* name;
        std::vector<std::string> args;
        bool hasOutput;  // prints on stderr once running
    };
    const std::vector<Job> jobs = {
        {"simulate (100 000 cycles)", {"simulate", "--preset", "fig20", "--cycles", "100000", "--out", dir + "/c.csv"}, false},
        {"sweep continuation", {"sweep", "--preset", "fig20", "--from", "0.2mm", "--to", "5mm", "--steps", "400",
                                "--progress", "--out", dir + "/c.csv"}, true},
        {"sweep independent", {"sweep", "--preset", "fig20", "--independent", "--from", "0.2mm", "--to", "5mm",
                               "--steps", "400", "--progress", "--out", dir + "/c.csv"}, true},
        {"map 40 x 40", {"map", "--preset", "fig20", "--from", "0.2mm", "--to", "5mm", "--steps", "40", "--param2", "f",
                         "--from2", "3", "--to2", "10", "--steps2", "40", "--progress", "--out", dir + "/c.csv"}, true},
        {"fit (3 damper runs)", {"fit", "--data", shared + "1Hz_30lb_1in.csv", shared + "1Hz_30lb_1.5in.csv",
                                 shared + "1Hz_30lb_0.5in.csv", "--setup", "prescribed", "--multistarts", "20",
                                 "--agreeing-starts", "0", "--max-iterations", "200", "--report", dir + "/c.json"}, true},
        {"fit dynamics (D05, 3 runs)", {"fit", "--data", d05 + "run_01.csv", d05 + "run_03.csv", d05 + "run_05.csv",
                                        "--manifest", d05 + "manifest.json", "--multistarts", "5", "--agreeing-starts",
                                        "0", "--report", dir + "/c.json"}, true},
        {"identify dynamics (D05)", {"identify", "--data", d05 + "run_01.csv", d05 + "run_03.csv", d05 + "run_05.csv",
                                     "--manifest", d05 + "manifest.json", "--report", dir + "/c.json"}, true},
        {"identify (3 damper runs)", {"identify", "--data", shared + "1Hz_30lb_1in.csv", shared + "1Hz_30lb_1.5in.csv",
                                      shared + "1Hz_30lb_0.5in.csv", "--setup", "prescribed", "--report",
                                      dir + "/c.json"}, true},
    };
    std::printf("== cancel latency: SIGINT %.1f s after the job started -> process exit ==\n", after_s);
    for (const Job& j : jobs) {
        std::vector<std::string> args{STICKSLIP_CLI};
        args.insert(args.end(), j.args.begin(), j.args.end());
        const Child c = run(args, after_s, j.hasOutput);
        const bool leftOutput = fileSize(dir + "/c.csv") >= 0 || fileSize(dir + "/c.json") >= 0;
        std::printf("%-28s exit %d, latency %7.3f s %s%s\n", j.name, c.exitCode, c.cancelLatency_s,
                    c.cancelLatency_s >= 0 && c.cancelLatency_s < 1.0 ? "(< 1 s)" : "(NOT under 1 s)",
                    leftOutput ? ", OUTPUT FILE LEFT" : ", no output file");
        std::fflush(stdout);
        ::unlink((dir + "/c.csv").c_str());
        ::unlink((dir + "/c.json").c_str());
    }
}

}  // namespace

int main(int argc, char** argv) {
    bool cancel = false;
    long cycles = 10000;
    int mapN = 300;
    double after_s = 1.0;
    std::string keep;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "--cancel") cancel = true;
        else if (a == "--cycles" && i + 1 < argc) cycles = std::atol(argv[++i]);
        else if (a == "--map" && i + 1 < argc) mapN = std::atoi(argv[++i]);
        else if (a == "--keep" && i + 1 < argc) keep = argv[++i];
        else if (a == "--after" && i + 1 < argc) after_s = std::atof(argv[++i]);
        else {
            std::fprintf(stderr, "usage: bench_memory [--cancel [--after S]] [--cycles N] [--map N] [--keep DIR]\n");
            return 2;
        }
    }
    char tmpl[] = "/tmp/bench_memory.XXXXXX";
    const std::string dir = keep.empty() ? std::string(::mkdtemp(tmpl)) : keep;
    if (cancel) cancelLatencies(dir, after_s);
    else memory(dir, cycles, mapN);
    if (keep.empty()) ::rmdir(dir.c_str());
    return 0;
}
