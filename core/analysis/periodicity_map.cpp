#include "periodicity_map.hpp"

#include <cmath>
#include <cstdio>
#include <mutex>

#include "parallel.hpp"
#include "poincare.hpp"
#include "section_stepping.hpp"
#include "sweep.hpp"

namespace stickslip {

ParamIssues MapOptions::validate(const SimParams& base) const {
    ParamIssues out;
    double dummy = 0;
    if (!getParam(base, key1, dummy)) out.push_back({"param '" + key1 + "'", 0.0, "a parameter key"});
    if (!getParam(base, key2, dummy)) out.push_back({"param2 '" + key2 + "'", 0.0, "a parameter key"});
    if (out.empty() && key1 == key2) out.push_back({"param2 '" + key2 + "'", 0.0, "a key different from param"});
    for (double v : {from1, to1, from2, to2})
        if (!std::isfinite(v)) out.push_back({"from/to", v, "finite"});
    if (steps1 < 1) out.push_back({"steps", double(steps1), ">= 1"});
    if (steps2 < 1) out.push_back({"steps2", double(steps2), ">= 1"});
    if (settleCycles < 0) out.push_back({"settle", double(settleCycles), ">= 0"});
    if (sampleCycles < 1) out.push_back({"samples", double(sampleCycles), ">= 1"});
    if (stepsPerPeriod < 0) out.push_back({"stepsPerPeriod", double(stepsPerPeriod), ">= 0 (0 = from dt)"});
    if (threads < 0) out.push_back({"threads", double(threads), ">= 0 (0 = all cores)"});
    for (auto& i : classify.validate()) out.push_back(i);
    if (out.empty() && base.setup != SetupKind::Dynamics)
        out.push_back({"setup", 0.0, "dynamics (a map needs the harmonic oscillator set-up)"});
    if (out.empty()) {
        for (double a : {from1, to1})
            for (double b : {from2, to2}) {
                SimParams p = base;
                std::string err;
                if (!setParam(p, key1, a, &err)) out.push_back({key1, a, err});
                if (!setParam(p, key2, b, &err)) out.push_back({key2, b, err});
                for (auto& i : p.validate()) out.push_back(i);
            }
    }
    return out;
}

std::size_t mapCellCount(const MapOptions& opt) {
    if (opt.steps1 < 1 || opt.steps2 < 1) return 0;
    return static_cast<std::size_t>(opt.steps1) * static_cast<std::size_t>(opt.steps2);
}

namespace {

// One cell from rest: a pure function of (base, opt, index) (no shared state is touched).
MapCell computeCell(const SimParams& base, const MapOptions& opt, const std::vector<double>& values1,
                    const std::vector<double>& values2, long n, std::size_t idx, const RunControl& quiet) {
    MapCell cell;
    cell.index = idx;
    const std::size_t i1 = idx % values1.size(), i2 = idx / values1.size();
    SimParams p = base;
    setParam(p, opt.key1, values1[i1]);
    setParam(p, opt.key2, values2[i2]);
    // Steps per period stay N for every cell (dt = T/N follows f).
    const DynamicsModel m = poincareModel(p, n);
    DynState s = m.initialState(0.0);
    const PoincareSection sec = SectionStepping::of(p, n).section(m, s, opt.settleCycles, opt.sampleCycles, quiet);
    cell.status = sec.status;
    if (sec.status == RunStatus::Ok) {
        const Classification c = classifyMotion(sec, classifyScales(p), opt.classify);
        cell.motion = c.motion;
        cell.period = c.period;
        cell.stickFraction = c.stickFraction;
        cell.maxRelVel_mps = c.maxRelVel_mps;
    } else if (sec.status == RunStatus::Failed) {
        char buf[160];
        std::snprintf(buf, sizeof buf, "%s = %.6g, %s = %.6g: ", opt.key1.c_str(), values1[i1], opt.key2.c_str(),
                      values2[i2]);
        cell.message = buf + sec.message;
    }
    return cell;
}

}  // namespace

std::vector<MapCell> periodicityMapCells(const SimParams& base, const MapOptions& opt,
                                         const std::vector<std::size_t>& indices, const RunControl& ctl,
                                         const std::function<void(const MapCell&)>& cellDone) {
    std::vector<MapCell> out(indices.size());
    for (std::size_t k = 0; k < indices.size(); ++k) out[k].index = indices[k];
    if (ParamIssues issues = opt.validate(base); !issues.empty()) {
        for (MapCell& c : out) { c.status = RunStatus::Failed; c.message = formatIssues(issues); }
        return out;
    }
    const std::vector<double> values1 = sweepValues(opt.from1, opt.to1, opt.steps1);
    const std::vector<double> values2 = sweepValues(opt.from2, opt.to2, opt.steps2);
    const std::size_t cells = values1.size() * values2.size();
    for (std::size_t idx : indices)
        if (idx >= cells) {
            for (MapCell& c : out) { c.status = RunStatus::Failed; c.message = "cell index out of range"; }
            return out;
        }
    const long n = stepsPerPeriodFor(base, opt.stepsPerPeriod);
    RunControl quiet{ctl.cancel, {}, {}};
    parallelForReporting(
        indices.size(), opt.threads,
        [&](std::size_t k) { out[k] = computeCell(base, opt, values1, values2, n, indices[k], quiet); },
        cellDone ? std::function<void(std::size_t)>([&](std::size_t k) { cellDone(out[k]); }) : nullptr,
        ctl.progress, [&] { return ctl.cancelled(); });
    return out;
}

PeriodicityMap assemblePeriodicityMap(const SimParams& base, const MapOptions& opt, const std::vector<MapCell>& cells) {
    PeriodicityMap map;
    map.key1 = opt.key1;
    map.key2 = opt.key2;
    if (ParamIssues issues = opt.validate(base); !issues.empty()) {
        map.status = RunStatus::Failed;
        map.message = formatIssues(issues);
        return map;
    }
    map.values1 = sweepValues(opt.from1, opt.to1, opt.steps1);
    map.values2 = sweepValues(opt.from2, opt.to2, opt.steps2);
    const std::size_t n = map.values1.size() * map.values2.size();
    map.motion.assign(n, MotionClass::Irregular);
    map.period.assign(n, 0);
    map.stickFraction.assign(n, 0.0);
    map.maxRelVel_mps.assign(n, 0.0);
    map.done.assign(n, 0);
    std::vector<std::string> failure(n);
    for (const MapCell& c : cells) {
        if (c.index >= n) continue;
        const std::size_t i = c.index;
        map.done[i] = 0;
        failure[i].clear();
        if (c.status == RunStatus::Ok) {
            map.motion[i] = c.motion;
            map.period[i] = c.period;
            map.stickFraction[i] = c.stickFraction;
            map.maxRelVel_mps[i] = c.maxRelVel_mps;
            map.done[i] = 1;
        } else if (c.status == RunStatus::Failed) {
            failure[i] = c.message;
        }
    }
    for (std::size_t i = 0; i < n; ++i) {
        if (!failure[i].empty()) {
            map.status = RunStatus::Failed;
            map.message = failure[i];
            return map;
        }
    }
    for (std::size_t i = 0; i < n; ++i)
        if (!map.done[i]) {
            map.status = RunStatus::Cancelled;
            map.message = "cancelled";
            break;
        }
    return map;
}

PeriodicityMap periodicityMap(const SimParams& base, const MapOptions& opt, const RunControl& ctl) {
    if (ParamIssues issues = opt.validate(base); !issues.empty()) return assemblePeriodicityMap(base, opt, {});
    std::vector<std::size_t> all(mapCellCount(opt));
    for (std::size_t i = 0; i < all.size(); ++i) all[i] = i;
    return assemblePeriodicityMap(base, opt, periodicityMapCells(base, opt, all, ctl));
}

}  // namespace stickslip
