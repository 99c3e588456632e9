#include "periodicity_map.hpp"

#include <cmath>
#include <mutex>

#include "parallel.hpp"
#include "poincare.hpp"
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

PeriodicityMap periodicityMap(const SimParams& base, const MapOptions& opt, const RunControl& ctl) {
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
    const std::size_t cells = map.values1.size() * map.values2.size();
    map.motion.assign(cells, MotionClass::Irregular);
    map.period.assign(cells, 0);
    map.stickFraction.assign(cells, 0.0);
    map.maxRelVel_mps.assign(cells, 0.0);
    map.done.assign(cells, 0);
    std::vector<std::string> failure(cells);
    const long n = stepsPerPeriodFor(base, opt.stepsPerPeriod);
    RunControl quiet{ctl.cancel, {}};
    std::mutex progressLock;
    std::size_t finished = 0;
    parallelFor(
        cells, opt.threads,
        [&](std::size_t idx) {
            const std::size_t i1 = idx % map.values1.size(), i2 = idx / map.values1.size();
            SimParams p = base;
            setParam(p, opt.key1, map.values1[i1]);
            setParam(p, opt.key2, map.values2[i2]);
            // Steps per period stay N for every cell (dt = T/N follows f).
            const DynamicsModel m = poincareModel(p, n);
            DynState s = m.initialState(0.0);
            const PoincareSection sec = poincareSectionFrom(m, s, n, opt.settleCycles, opt.sampleCycles, quiet);
            if (sec.status == RunStatus::Ok) {
                const Classification c = classifyMotion(sec, classifyScales(p), opt.classify);
                map.motion[idx] = c.motion;
                map.period[idx] = c.period;
                map.stickFraction[idx] = c.stickFraction;
                map.maxRelVel_mps[idx] = c.maxRelVel_mps;
                map.done[idx] = 1;
            } else if (sec.status == RunStatus::Failed) {
                char buf[160];
                std::snprintf(buf, sizeof buf, "%s = %.6g, %s = %.6g: ", opt.key1.c_str(), map.values1[i1],
                              opt.key2.c_str(), map.values2[i2]);
                failure[idx] = buf + sec.message;
            }
            if (ctl.progress) {
                std::lock_guard<std::mutex> lk(progressLock);
                ++finished;
                ctl.progress(static_cast<double>(finished) / static_cast<double>(cells));
            }
        },
        [&] { return ctl.cancelled(); });
    for (std::size_t i = 0; i < cells; ++i) {
        if (!failure[i].empty()) {
            map.status = RunStatus::Failed;
            map.message = failure[i];
            return map;
        }
    }
    for (std::size_t i = 0; i < cells; ++i)
        if (!map.done[i]) {
            map.status = RunStatus::Cancelled;
            map.message = "cancelled";
            break;
        }
    return map;
}

}  // namespace stickslip
