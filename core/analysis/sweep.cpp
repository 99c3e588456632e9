#include "sweep.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <iterator>
#include <limits>
#include <mutex>
#include <numbers>
#include <thread>

#include "lyapunov.hpp"
#include "parallel.hpp"
#include "section_stepping.hpp"

namespace stickslip {

const char* toString(SweepMode m) { return m == SweepMode::Continuation ? "continuation" : "independent"; }
const char* toString(SweepDirection d) {
    switch (d) {
        case SweepDirection::Up: return "up";
        case SweepDirection::Down: return "down";
        case SweepDirection::Both: return "both";
    }
    return "?";
}
bool parseSweepMode(const std::string& s, SweepMode& m) {
    if (s == "continuation") { m = SweepMode::Continuation; return true; }
    if (s == "independent") { m = SweepMode::Independent; return true; }
    return false;
}
bool parseSweepDirection(const std::string& s, SweepDirection& d) {
    if (s == "up") { d = SweepDirection::Up; return true; }
    if (s == "down") { d = SweepDirection::Down; return true; }
    if (s == "both") { d = SweepDirection::Both; return true; }
    return false;
}

std::vector<double> sweepValues(double from, double to, int steps) {
    std::vector<double> v;
    if (steps < 1) return v;
    v.reserve(static_cast<std::size_t>(steps));
    if (steps == 1) { v.push_back(from); return v; }
    for (int i = 0; i < steps; ++i) {
        const double s = static_cast<double>(i) / static_cast<double>(steps - 1);
        v.push_back(i == steps - 1 ? to : from + (to - from) * s);
    }
    return v;
}

ParamIssues SweepOptions::validate(const SimParams& base) const {
    ParamIssues out;
    double dummy = 0;
    if (!getParam(base, key, dummy)) out.push_back({"param '" + key + "'", 0.0, "a parameter key (see presets/--set)"});
    if (!std::isfinite(from)) out.push_back({"from", from, "finite"});
    if (!std::isfinite(to)) out.push_back({"to", to, "finite"});
    if (steps < 1) out.push_back({"steps", double(steps), ">= 1"});
    if (settleCycles < 0) out.push_back({"settle", double(settleCycles), ">= 0"});
    if (sampleCycles < 1) out.push_back({"samples", double(sampleCycles), ">= 1"});
    if (stepsPerPeriod < 0) out.push_back({"stepsPerPeriod", double(stepsPerPeriod), ">= 0 (0 = from dt)"});
    if (!(phase_rad >= 0 && phase_rad < 2 * std::numbers::pi)) out.push_back({"phase", phase_rad, "in [0, 2π)"});
    if (threads < 0) out.push_back({"threads", double(threads), ">= 0 (0 = all cores)"});
    if (lyapunov && !(lyapunovD0 > 0 && lyapunovD0 < 1e-2)) out.push_back({"lyapunovD0", lyapunovD0, "in (0, 1e-2)"});
    for (auto& i : classify.validate()) out.push_back(i);
    if (lyapunov && base.integration.tolerance > 0.0)
        out.push_back({"tolerance", base.integration.tolerance,
                       "0 with the Lyapunov exponent (its companion trajectory steps the fixed-step map; "
                       "--no-lyapunov with --tolerance)"});
    if (out.empty() && base.setup != SetupKind::Dynamics)
        out.push_back({"setup", 0.0, "dynamics (a sweep needs the harmonic oscillator set-up)"});
    // Every value must give valid parameters.
    if (out.empty()) {
        for (double v : {from, to}) {
            SimParams p = base;
            std::string err;
            if (!setParam(p, key, v, &err)) { out.push_back({key, v, err}); continue; }
            for (auto& i : p.validate()) out.push_back(i);
        }
    }
    return out;
}

namespace {

// One value: settle, then sample (with the Lyapunov companion when asked) from state s.
void runValue(const SimParams& p, const SweepOptions& opt, const SectionStepping& st, DynState& s,
              const DynamicsModel& m, SweepPoint& pt, const RunControl& quiet, bool companionThread = false) {
    constexpr double nan = std::numeric_limits<double>::quiet_NaN();
    pt.lyapunovPerCycle = pt.lyapunovPerSecond = nan;
    const long n = st.stepsPerPeriod;  // the Lyapunov companion steps the fixed-step map (validate())
    if (!opt.lyapunov) {
        pt.section = st.section(m, s, opt.settleCycles, opt.sampleCycles, quiet);
    } else {
        StepReport rep = detail::settleCycles(m, s, n, opt.settleCycles, quiet);
        if (rep.status != RunStatus::Ok) {
            pt.section.period_s = p.drive.period();
            pt.section.status = rep.status;
            pt.section.message = rep.message;
        } else {
            LyapunovResult ly = largestLyapunovFrom(m, s, n, opt.sampleCycles, opt.lyapunovD0, separationScales(p),
                                                    quiet, &pt.section, companionThread);
            if (ly.ok()) {
                pt.lyapunovPerCycle = ly.perCycle;
                pt.lyapunovPerSecond = ly.perSecond;
            }
        }
    }
    pt.classification = classifyMotion(pt.section, classifyScales(p), opt.classify);
}

std::string valueMessage(const std::string& key, double v, const std::string& msg) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.9g", v);
    return key + " = " + buf + ": " + msg;
}

// One continuation branch: the values in order, the state carried from each to the next.
struct Branch {
    std::vector<SweepPoint> points;  // the values finished (all of them when status is Ok)
    RunStatus status = RunStatus::Ok;
    std::string message;
    double failedValue = 0;
};

// Runs `values` in order, tagged `direction`, the state carried from each value to the next.
// The first value continues from *carry when continueCarry (clock reset to the section phase);
// otherwise it starts from rest at the section phase, followed by `leadInCycles` discarded
// cycles at that value. When carry is given it holds the state after the last value on return.
void runBranch(const SimParams& base, const SweepOptions& opt, long n, const std::vector<double>& values,
               int direction, DynState* carry, bool continueCarry, long leadInCycles, bool companionThread,
               const RunControl& quiet, const std::function<void()>& valueDone, Branch& out) {
    out.points.reserve(values.size());
    DynState local;
    DynState& s = carry ? *carry : local;
    const bool fromRest = !(carry && continueCarry);
    for (std::size_t i = 0; i < values.size(); ++i) {
        SimParams p = base;
        setParam(p, opt.key, values[i]);
        const DynamicsModel m = poincareModel(p, n);
        const SectionStepping st = SectionStepping::of(p, n);
        if (i == 0 && fromRest) {
            s = m.initialState(0.0);
            StepReport rep = st.toPhase(m, s, opt.phase_rad, quiet);
            if (rep.status == RunStatus::Ok && leadInCycles > 0) rep = st.settle(m, s, leadInCycles, quiet);
            if (rep.status != RunStatus::Ok) {
                out.status = rep.status;
                out.message = rep.message;
                out.failedValue = values[i];
                return;
            }
        }
        if (i > 0 || !fromRest || leadInCycles > 0) {
            // Carry (x, v, a, F, α) over; restart the clock at the section phase of the new drive,
            // so the stage period and phase follow the new value (f may be the key). After a
            // lead-in this puts the clock where a continued branch has it.
            s.t = st.phaseTime(opt.phase_rad);
            s.u = m.stage.displacement(s.t);
        }
        SweepPoint pt;
        pt.value = values[i];
        pt.direction = direction;
        runValue(p, opt, st, s, m, pt, quiet, companionThread);
        if (pt.section.status != RunStatus::Ok) {
            out.status = pt.section.status;
            out.message = pt.section.message;
            out.failedValue = values[i];
            return;
        }
        out.points.push_back(std::move(pt));
        valueDone();
    }
}

}  // namespace

SweepResult bifurcationSweep(const SimParams& base, const SweepOptions& opt, const RunControl& ctl) {
    SweepResult res;
    res.key = opt.key;
    if (ParamIssues issues = opt.validate(base); !issues.empty()) {
        res.status = RunStatus::Failed;
        res.message = formatIssues(issues);
        return res;
    }
    const long n = stepsPerPeriodFor(base, opt.stepsPerPeriod);
    const std::vector<double> up = sweepValues(opt.from < opt.to ? opt.from : opt.to,
                                               opt.from < opt.to ? opt.to : opt.from, opt.steps);
    std::vector<double> down(up.rbegin(), up.rend());
    RunControl quiet{ctl.cancel, {}, {}};

    if (opt.mode == SweepMode::Continuation) {
        // Progress over every value of every branch, possibly from two threads.
        const std::size_t total = (opt.direction == SweepDirection::Both ? 2 : 1) * up.size();
        std::mutex progressLock;
        std::size_t finished = 0;
        auto valueDone = [&] {
            if (!ctl.progress) return;
            std::lock_guard<std::mutex> lk(progressLock);
            ++finished;
            ctl.progress(static_cast<double>(finished) / static_cast<double>(total));
        };
        Branch upBranch, downBranch;
        // A single branch at a time: the Lyapunov companion trajectory gets the second thread.
        const bool twoBranchesAtOnce = opt.direction == SweepDirection::Both && opt.concurrentBranches;
        const bool companion = opt.lyapunov && !twoBranchesAtOnce && workerCount(opt.threads, 2) >= 2;
        if (opt.direction == SweepDirection::Up) {
            runBranch(base, opt, n, up, +1, nullptr, false, 0, companion, quiet, valueDone, upBranch);
        } else if (opt.direction == SweepDirection::Down) {
            runBranch(base, opt, n, down, -1, nullptr, false, 0, companion, quiet, valueDone, downBranch);
        } else if (!opt.concurrentBranches) {
            // The paper's way: the down branch continues from the up branch's end state.
            DynState s;
            runBranch(base, opt, n, up, +1, &s, false, 0, companion, quiet, valueDone, upBranch);
            if (upBranch.status == RunStatus::Ok)
                runBranch(base, opt, n, down, -1, &s, true, 0, companion, quiet, valueDone, downBranch);
        } else {
            // Independent branches: the down branch starts from rest at the top value with a
            // lead-in as long as the up branch's stay there (settle + sample cycles), so the two
            // can run at once. Each is a pure function of (params, options): the same result on
            // one thread or two.
            const long leadIn = opt.settleCycles + opt.sampleCycles;
            auto runDown = [&] {
                runBranch(base, opt, n, down, -1, nullptr, false, leadIn, false, quiet, valueDone, downBranch);
            };
            if (workerCount(opt.threads, 2) >= 2) {
                std::thread downThread(runDown);
                runBranch(base, opt, n, up, +1, nullptr, false, 0, companion, quiet, valueDone, upBranch);
                downThread.join();
            } else {
                runBranch(base, opt, n, up, +1, nullptr, false, 0, companion, quiet, valueDone, upBranch);
                runDown();
            }
        }
        res.points = std::move(upBranch.points);
        res.points.insert(res.points.end(), std::make_move_iterator(downBranch.points.begin()),
                          std::make_move_iterator(downBranch.points.end()));
        // The first problem in branch order (up, then down) is the one reported. (A failure in
        // one concurrent branch does not stop the other, so the points kept stay deterministic.)
        for (const Branch* b : {&upBranch, &downBranch}) {
            if (b->status == RunStatus::Ok) continue;
            res.status = b->status;
            res.message = b->status == RunStatus::Cancelled ? "cancelled"
                                                             : valueMessage(opt.key, b->failedValue, b->message);
            break;
        }
        return res;
    }

    // Independent: every value from rest, a pure function of its index.
    std::vector<std::size_t> all(up.size());
    for (std::size_t i = 0; i < all.size(); ++i) all[i] = i;
    return assembleIndependentSweep(base, opt, independentSweepValues(base, opt, all, ctl));
}

std::vector<SweepValueRecord> independentSweepValues(const SimParams& base, const SweepOptions& opt,
                                                     const std::vector<std::size_t>& indices, const RunControl& ctl,
                                                     const std::function<void(const SweepValueRecord&)>& valueDone) {
    std::vector<SweepValueRecord> out(indices.size());
    for (std::size_t k = 0; k < indices.size(); ++k) out[k].index = indices[k];
    const std::vector<double> up = sweepValues(std::min(opt.from, opt.to), std::max(opt.from, opt.to), opt.steps);
    std::string problem;
    if (ParamIssues issues = opt.validate(base); !issues.empty()) problem = formatIssues(issues);
    for (std::size_t idx : indices)
        if (problem.empty() && idx >= up.size()) problem = "value index out of range";
    if (!problem.empty()) {
        for (SweepValueRecord& r : out) {
            r.done = true;
            r.point.section.status = RunStatus::Failed;
            r.point.section.message = problem;
        }
        return out;
    }
    const long n = stepsPerPeriodFor(base, opt.stepsPerPeriod);
    RunControl quiet{ctl.cancel, {}, {}};
    parallelForReporting(
        indices.size(), opt.threads,
        [&](std::size_t k) {
            const double v = up[indices[k]];
            SimParams p = base;
            setParam(p, opt.key, v);
            const DynamicsModel m = poincareModel(p, n);
            const SectionStepping st = SectionStepping::of(p, n);
            DynState s = m.initialState(0.0);
            SweepPoint& pt = out[k].point;
            pt.value = v;
            pt.direction = +1;
            StepReport rep = st.toPhase(m, s, opt.phase_rad, quiet);
            if (rep.status != RunStatus::Ok) {
                pt.section.status = rep.status;
                pt.section.message = rep.message;
            } else {
                runValue(p, opt, st, s, m, pt, quiet);
            }
            out[k].done = true;
        },
        valueDone ? std::function<void(std::size_t)>([&](std::size_t k) { valueDone(out[k]); }) : nullptr,
        ctl.progress, [&] { return ctl.cancelled(); });
    return out;
}

SweepResult assembleIndependentSweep(const SimParams& base, const SweepOptions& opt,
                                     const std::vector<SweepValueRecord>& records) {
    SweepResult res;
    res.key = opt.key;
    if (ParamIssues issues = opt.validate(base); !issues.empty()) {
        res.status = RunStatus::Failed;
        res.message = formatIssues(issues);
        return res;
    }
    const std::size_t count = static_cast<std::size_t>(opt.steps);
    std::vector<const SweepValueRecord*> slot(count, nullptr);
    for (const SweepValueRecord& r : records)
        if (r.index < count) slot[r.index] = r.done ? &r : nullptr;
    // Report the first failure by index (deterministic), keep every finished value.
    for (std::size_t i = 0; i < count; ++i) {
        if (!slot[i]) {
            if (res.status == RunStatus::Ok) { res.status = RunStatus::Cancelled; res.message = "cancelled"; }
            continue;
        }
        const SweepPoint& pt = slot[i]->point;
        if (pt.section.status != RunStatus::Ok) {
            if (pt.section.status == RunStatus::Cancelled) {
                if (res.status == RunStatus::Ok) { res.status = RunStatus::Cancelled; res.message = "cancelled"; }
            } else if (res.status != RunStatus::Failed) {
                res.status = RunStatus::Failed;
                res.message = valueMessage(opt.key, pt.value, pt.section.message);
            }
            continue;
        }
        res.points.push_back(pt);
    }
    if (res.status == RunStatus::Ok && opt.direction != SweepDirection::Up) {
        // From rest, the down branch is the same computation: listed in descending order.
        std::vector<SweepPoint> downPts(res.points.rbegin(), res.points.rend());
        for (auto& p : downPts) p.direction = -1;
        if (opt.direction == SweepDirection::Down) res.points = std::move(downPts);
        else res.points.insert(res.points.end(), downPts.begin(), downPts.end());
    }
    return res;
}

}  // namespace stickslip
