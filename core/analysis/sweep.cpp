#include "sweep.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <mutex>
#include <numbers>

#include "lyapunov.hpp"
#include "parallel.hpp"

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
void runValue(const SimParams& p, const SweepOptions& opt, long n, DynState& s, const DynamicsModel& m,
              SweepPoint& pt, const RunControl& quiet) {
    constexpr double nan = std::numeric_limits<double>::quiet_NaN();
    pt.lyapunovPerCycle = pt.lyapunovPerSecond = nan;
    if (!opt.lyapunov) {
        pt.section = poincareSectionFrom(m, s, n, opt.settleCycles, opt.sampleCycles, quiet);
    } else {
        StepReport rep = detail::settleCycles(m, s, n, opt.settleCycles, quiet);
        if (rep.status != RunStatus::Ok) {
            pt.section.period_s = p.drive.period();
            pt.section.status = rep.status;
            pt.section.message = rep.message;
        } else {
            LyapunovResult ly = largestLyapunovFrom(m, s, n, opt.sampleCycles, opt.lyapunovD0, separationScales(p),
                                                    quiet, &pt.section);
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
    RunControl quiet{ctl.cancel, {}};

    auto paramsFor = [&](double v) {
        SimParams p = base;
        setParam(p, opt.key, v);
        return p;
    };

    if (opt.mode == SweepMode::Continuation) {
        std::vector<std::pair<double, int>> plan;
        if (opt.direction != SweepDirection::Down)
            for (double v : up) plan.push_back({v, +1});
        if (opt.direction != SweepDirection::Up)
            for (double v : down) plan.push_back({v, -1});
        res.points.reserve(plan.size());
        DynState s;
        bool first = true;
        for (std::size_t i = 0; i < plan.size(); ++i) {
            const SimParams p = paramsFor(plan[i].first);
            const DynamicsModel m = poincareModel(p, n);
            const long offset = detail::phaseOffsetSteps(opt.phase_rad, n);
            if (first) {
                s = m.initialState(0.0);
                first = false;
                StepReport rep = advanceQuiet(m, s, offset, quiet);
                if (rep.status != RunStatus::Ok) {
                    res.status = rep.status;
                    res.message = valueMessage(opt.key, plan[i].first, rep.message);
                    return res;
                }
            } else {
                // Carry (x, v, a, F, α) over; restart the clock at the section phase of the new
                // drive, so the stage period and phase follow the new value (f may be the key).
                s.t = static_cast<double>(offset) * m.dt_s;
                s.u = m.stage.displacement(s.t);
            }
            SweepPoint pt;
            pt.value = plan[i].first;
            pt.direction = plan[i].second;
            runValue(p, opt, n, s, m, pt, quiet);
            const RunStatus st = pt.section.status;
            const std::string msg = pt.section.message;
            if (st == RunStatus::Ok) res.points.push_back(std::move(pt));
            if (st != RunStatus::Ok) {
                res.status = st;
                res.message = st == RunStatus::Cancelled ? "cancelled" : valueMessage(opt.key, plan[i].first, msg);
                return res;
            }
            if (ctl.progress) ctl.progress(static_cast<double>(i + 1) / static_cast<double>(plan.size()));
        }
        return res;
    }

    // Independent: every value from rest; each writes only its own slot.
    std::vector<SweepPoint> pts(up.size());
    std::vector<unsigned char> done(up.size(), 0);
    std::mutex progressLock;
    std::size_t finished = 0;
    parallelFor(
        up.size(), opt.threads,
        [&](std::size_t i) {
            const SimParams p = paramsFor(up[i]);
            const DynamicsModel m = poincareModel(p, n);
            DynState s = m.initialState(0.0);
            SweepPoint& pt = pts[i];
            pt.value = up[i];
            pt.direction = +1;
            StepReport rep = advanceQuiet(m, s, detail::phaseOffsetSteps(opt.phase_rad, n), quiet);
            if (rep.status != RunStatus::Ok) {
                pt.section.status = rep.status;
                pt.section.message = rep.message;
            } else {
                runValue(p, opt, n, s, m, pt, quiet);
            }
            done[i] = 1;
            if (ctl.progress) {
                std::lock_guard<std::mutex> lk(progressLock);
                ++finished;
                ctl.progress(static_cast<double>(finished) / static_cast<double>(up.size()));
            }
        },
        [&] { return ctl.cancelled(); });
    // Report the first failure by index (deterministic), keep every finished value.
    for (std::size_t i = 0; i < pts.size(); ++i) {
        if (!done[i]) {
            if (res.status == RunStatus::Ok) { res.status = RunStatus::Cancelled; res.message = "cancelled"; }
            continue;
        }
        if (pts[i].section.status != RunStatus::Ok) {
            if (pts[i].section.status == RunStatus::Cancelled) {
                if (res.status == RunStatus::Ok) { res.status = RunStatus::Cancelled; res.message = "cancelled"; }
            } else if (res.status != RunStatus::Failed) {
                res.status = RunStatus::Failed;
                res.message = valueMessage(opt.key, pts[i].value, pts[i].section.message);
            }
            continue;
        }
        res.points.push_back(pts[i]);
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
