#include "lyapunov.hpp"

#include "../friction/friction_law.hpp"

#include <algorithm>
#include <cmath>
#include <condition_variable>
#include <limits>
#include <memory>
#include <mutex>
#include <thread>

namespace stickslip {

SeparationScales separationScales(const SimParams& p) {
    SeparationScales sc;
    const double mu = lawMu(p);
    sc.x_m = mu * p.rig.normalForce_N / p.rig.stiffness_N_per_m;
    sc.v_mps = sc.x_m * p.rig.naturalFrequency_rad_s();
    sc.force_N = mu * p.rig.normalForce_N;
    sc.alpha = 1.0;
    return sc;
}

double stateSeparation(const DynState& a, const DynState& b, const SeparationScales& sc) {
    const double dx = (a.x - b.x) / sc.x_m;
    const double dv = (a.v - b.v) / sc.v_mps;
    const double dF = (a.law.force_N - b.law.force_N) / sc.force_N;
    const double da = (a.law.alpha - b.law.alpha) / sc.alpha;
    return std::sqrt(dx * dx + dv * dv + dF * dF + da * da);
}

DynState perturbedState(const DynState& s, const RigParams& rig, const SeparationScales& sc, double d0) {
    DynState p = s;
    const double dx = d0 / std::sqrt(2.0) * sc.x_m;
    const double dv = d0 / std::sqrt(2.0) * sc.v_mps;
    p.x += dx;
    p.v += dv;
    // Keep m a + c v + k x = F for the perturbed state (F unchanged).
    p.a -= (rig.stiffness_N_per_m * dx + rig.damping_Ns_per_m * dv) / rig.mass_kg;
    return p;
}

double renormalise(const DynState& ref, DynState& pert, const SeparationScales& sc, double d0) {
    const double d = stateSeparation(ref, pert, sc);
    if (!(d > 0) || !std::isfinite(d)) {
        pert = ref;  // collapsed (or lost): restart the companion at distance d0 along (x, v)
        return d;
    }
    const double f = d0 / d;
    pert.x = ref.x + f * (pert.x - ref.x);
    pert.v = ref.v + f * (pert.v - ref.v);
    pert.a = ref.a + f * (pert.a - ref.a);
    pert.law.force_N = ref.law.force_N + f * (pert.law.force_N - ref.law.force_N);
    pert.law.alpha = ref.law.alpha + f * (pert.law.alpha - ref.law.alpha);
    for (std::size_t i = 0; i < pert.law.aux.size(); ++i)
        pert.law.aux[i] = ref.law.aux[i] + f * (pert.law.aux[i] - ref.law.aux[i]);
    pert.t = ref.t;
    pert.u = ref.u;
    return d;
}

ParamIssues LyapunovOptions::validate() const {
    ParamIssues out;
    if (stepsPerPeriod < 0) out.push_back({"stepsPerPeriod", double(stepsPerPeriod), ">= 0 (0 = from dt)"});
    if (settleCycles < 0) out.push_back({"settle", double(settleCycles), ">= 0"});
    if (cycles < 1) out.push_back({"cycles", double(cycles), ">= 1"});
    if (!(d0 > 0 && d0 < 1e-2)) out.push_back({"d0", d0, "in (0, 1e-2)"});
    return out;
}

namespace {

// Advances the companion trajectory by one cycle at a time on its own thread, on request:
// start() hands it a cycle, finish() waits for it and returns its report.
class CompanionWorker {
public:
    CompanionWorker(const DynamicsModel& m, DynState& pert, long n, const RunControl& ctl)
        : thread_([this, &m, &pert, n, &ctl] {
              long seen = 0;
              for (;;) {
                  std::unique_lock<std::mutex> lk(mu_);
                  cv_.wait(lk, [&] { return requested_ > seen || quit_; });
                  if (requested_ == seen) return;  // quit with nothing pending
                  seen = requested_;
                  lk.unlock();
                  StepReport r = advanceQuiet(m, pert, n, ctl);
                  lk.lock();
                  report_ = std::move(r);
                  finished_ = seen;
                  cv_.notify_all();
              }
          }) {}
    CompanionWorker(const CompanionWorker&) = delete;
    CompanionWorker& operator=(const CompanionWorker&) = delete;
    ~CompanionWorker() {
        {
            std::lock_guard<std::mutex> lk(mu_);
            quit_ = true;
        }
        cv_.notify_all();
        thread_.join();
    }
    void start() {
        std::lock_guard<std::mutex> lk(mu_);
        ++requested_;
        cv_.notify_all();
    }
    StepReport finish() {
        std::unique_lock<std::mutex> lk(mu_);
        cv_.wait(lk, [&] { return finished_ == requested_; });
        return report_;
    }

private:
    std::mutex mu_;
    std::condition_variable cv_;
    long requested_ = 0, finished_ = 0;
    bool quit_ = false;
    StepReport report_;
    std::thread thread_;  // last: starts after the members it uses exist
};

}  // namespace

LyapunovResult largestLyapunovFrom(const DynamicsModel& m, DynState& ref, long stepsPerPeriod, long cycles,
                                   double d0, const SeparationScales& sc, const RunControl& ctl,
                                   PoincareSection* section, bool companionThread) {
    LyapunovResult res;
    const double period = m.dt_s * static_cast<double>(stepsPerPeriod);
    RunControl quiet{ctl.cancel, {}, {}};
    PoincareSection local;
    PoincareSection& sec = section ? *section : local;
    sec.period_s = period;
    long stuck = 0;
    DynState pert = perturbedState(ref, m.rig, sc, d0);
    res.logGrowth.reserve(static_cast<std::size_t>(cycles));
    // A collapsed separation (both trajectories land on the same stuck state) counts as a
    // contraction by 1e-16 per cycle: far below any chaotic growth, and finite.
    const double floorLog = std::log(1e-16);
    std::unique_ptr<CompanionWorker> worker;
    if (companionThread && cycles > 1) worker = std::make_unique<CompanionWorker>(m, pert, stepsPerPeriod, quiet);
    for (long c = 0; c < cycles; ++c) {
        StepReport rep;
        if (worker) {
            // Both trajectories advance one cycle at once; the reference's failure comes first.
            worker->start();
            rep = detail::advanceSampledCycle(m, ref, stepsPerPeriod, sec, stuck, quiet);
            StepReport repPert = worker->finish();
            if (rep.status == RunStatus::Ok) rep = std::move(repPert);
        } else {
            rep = detail::advanceSampledCycle(m, ref, stepsPerPeriod, sec, stuck, quiet);
            if (rep.status == RunStatus::Ok) rep = advanceQuiet(m, pert, stepsPerPeriod, quiet);
        }
        if (rep.status != RunStatus::Ok || ctl.cancelled()) {
            res.status = rep.status != RunStatus::Ok ? rep.status : RunStatus::Cancelled;
            res.message = rep.status != RunStatus::Ok ? rep.message : "cancelled";
            sec.status = res.status;
            sec.message = res.message;
            break;
        }
        const double d = renormalise(ref, pert, sc, d0);
        double lg = (d > 0 && std::isfinite(d)) ? std::log(d / d0) : floorLog;
        lg = std::max(lg, floorLog);
        if (!(d > 0) || !std::isfinite(d)) pert = perturbedState(ref, m.rig, sc, d0);
        res.logGrowth.push_back(lg);
        if (ctl.progress) ctl.progress(static_cast<double>(c + 1) / static_cast<double>(cycles));
    }
    const long total = stuck + sec.slipSteps;
    sec.stickFraction = total > 0 ? static_cast<double>(stuck) / static_cast<double>(total) : 0.0;
    double sum = 0;
    for (double g : res.logGrowth) sum += g;
    res.perCycle = res.logGrowth.empty() ? std::numeric_limits<double>::quiet_NaN()
                                         : sum / static_cast<double>(res.logGrowth.size());
    res.perSecond = res.perCycle / period;
    return res;
}

LyapunovResult largestLyapunov(const SimParams& p, const LyapunovOptions& opt, const RunControl& ctl) {
    ParamIssues issues = p.validate();
    ParamIssues more = opt.validate();
    issues.insert(issues.end(), more.begin(), more.end());
    LyapunovResult res;
    if (!issues.empty()) {
        res.status = RunStatus::Failed;
        res.message = formatIssues(issues);
        res.perCycle = res.perSecond = std::numeric_limits<double>::quiet_NaN();
        return res;
    }
    const long n = stepsPerPeriodFor(p, opt.stepsPerPeriod);
    const DynamicsModel m = poincareModel(p, n);
    DynState s = m.initialState(0.0);
    RunControl quiet{ctl.cancel, {}, {}};
    StepReport rep = detail::settleCycles(m, s, n, opt.settleCycles, quiet);
    if (rep.status != RunStatus::Ok) {
        res.status = rep.status;
        res.message = rep.message;
        res.perCycle = res.perSecond = std::numeric_limits<double>::quiet_NaN();
        return res;
    }
    return largestLyapunovFrom(m, s, n, opt.cycles, opt.d0, separationScales(p), ctl);
}

}  // namespace stickslip
