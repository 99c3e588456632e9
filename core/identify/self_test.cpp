// The recovery self-test (self_test.hpp): replicas of the user's runs with and without an
// injected effect, scored by the selection's tests (1a) and (1b) in the linearised refit.
#include "self_test.hpp"

#include <chrono>
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cmath>
#include <limits>
#include <map>

#include "identify_internal.hpp"

namespace stickslip::identify {

namespace detail {
namespace {

using Vec = Eigen::VectorXd;

// The linearised selection of one candidate: its bases, parameter count and null quantile.
struct LinearCandidate {
    std::string name;
    Eigen::MatrixXd Jc;                  // the effect's columns
    std::vector<Eigen::Index> baseCols;  // the baseline's columns it is fitted with (indices into J0)
    ProjectionBases bases;
    int params = 0;
    double nullQuantile = 0;
};

double squaredNorm(const Eigen::MatrixXd& Q, const Vec& e) { return Q.cols() ? (Q.transpose() * e).squaredNorm() : 0.0; }

struct Selector {
    ProjectionBases base;  // Qc: the baseline's columns
    int baseParams = 0;
    double count = 0, cap = 0, margin = 0;
    bool useNull = true;
    // Index of the candidate the selection picks on the residual e of the baseline, −1 if none.
    // `truth`: the injected candidate's index, fitted at its true size, where its residual is the
    // replica's noise alone (only its linearised refit around it remains); −1 for none.
    int pick(const Vec& e, const std::vector<const LinearCandidate*>& cands, int truth = -1, const Vec* noise = nullptr) const {
        const double ee = e.squaredNorm();
        const double ssCur = std::max(ee - squaredNorm(base.Qc, e), 1e-300);
        const double bicCur = bic(ssCur, count, cap, baseParams);
        int best = -1;
        double bestDb = 0;
        for (size_t i = 0; i < cands.size(); ++i) {
            const LinearCandidate& c = *cands[i];
            if (c.bases.Qc.cols() == 0) continue;
            const Vec& r = static_cast<int>(i) == truth && noise ? *noise : e;
            const double rr = static_cast<int>(i) == truth && noise ? r.squaredNorm() : ee;
            const double ss0 = rr - squaredNorm(c.bases.Q0, r);
            const double ssWith = std::max(ss0 - squaredNorm(c.bases.Qc, r), 1e-300);
            const double db = bic(ssWith, count, cap, c.params) - bicCur;
            if (!(db < -margin)) continue;
            if (useNull && !(ssCur - ssWith > c.nullQuantile)) continue;
            if (best < 0 || db < bestDb) { best = static_cast<int>(i); bestDb = db; }
        }
        return best;
    }
};

// The size parameter's value at position u ∈ [0, 1] from where the effect vanishes (or, for a
// parameter that continues a baseline one, from the baseline's value) to its physical bound.
double sizeAt(const EffectParam& q, double from, double u) {
    if (std::isinf(q.vanishing)) return q.upper * std::pow(q.lower / q.upper, u);  // a stiffness: softer is larger
    if (q.logScale) return std::max(q.lower, from) * std::pow(q.upper / std::max(q.lower, from), u);
    const double to = q.upper > from ? q.upper : q.lower;
    return from + u * (to - from);
}

struct Injection {
    double size = 0, rms = 0;
    std::vector<double> signal;
    bool ok = false;
    std::string note;
};

// One row of the table: an effect at a level (−1: its stated size), and the injection found for it.
struct Job {
    size_t cand;
    double level;
    Injection inj;
};

// The selection with a baseline column held on its bound, and every candidate refitted without it.
struct Held {
    Selector sel;
    std::vector<LinearCandidate> lin;
};

// One self-test: the state its phases share (the baseline's residual, noise blocks and Jacobian,
// the candidates linearised around it, the rows), one method per phase. A phase that stops the
// test returns false with out.message set; `out` then holds what was done so far.
struct SelfTestRun {
    const std::chrono::steady_clock::time_point t0 = std::chrono::steady_clock::now();
    const Context& cx;
    const Spec& spec;
    const FitOutcome& base;
    const std::vector<size_t>& fitIdx;
    const std::vector<std::string>& cands;
    const double neffCap;
    const IdentifyOptions& opt;
    const SelfTestOptions& so;
    const uint64_t nullSeed, replicaSeed;
    SelfTestResult out;
    std::vector<double> r0;                     // the baseline's residual
    std::vector<double> numerics;               // its numerical part (IdentifyOptions::nullNumerics; empty: off)
    std::vector<NoiseBlock> blocks;             // its runs and channels, for the noise replicas
    size_t n = 0;                               // residual length
    std::vector<char> used;                     // compared samples
    double count = 0;                           // how many
    std::vector<std::string> baseNames;         // the baseline's free parameters (J0's columns)
    Eigen::MatrixXd J0;
    std::vector<Eigen::Index> allCols;
    Selector sel;                               // the selection with the whole baseline
    std::vector<LinearCandidate> lin;           // each candidate at its start
    std::vector<Eigen::Index> heldCol;          // per candidate: the baseline column it holds (−1: none)
    std::vector<std::vector<double>> reference; // per candidate: the residual its injection is measured from
    std::vector<Job> jobs;
    std::vector<const LinearCandidate*> all;
    std::vector<Vec> noises;
    std::map<Eigen::Index, Held> heldCache;

    SelfTestRun(const Context& cx_, const Spec& spec_, const FitOutcome& base_, const std::vector<size_t>& fitIdx_,
                const std::vector<std::string>& cands_, double neffCap_)
        : cx(cx_), spec(spec_), base(base_), fitIdx(fitIdx_), cands(cands_), neffCap(neffCap_), opt(*cx_.opt),
          so(opt.selfTest), nullSeed(opt.seed + 6151u), replicaSeed(opt.seed + 104729u) {}

    bool cancelled() const { return opt.cancelRequested(); }
    void progress(const std::string& s, double f) const { if (opt.progress) opt.progress("self-test: " + s, f); }
    bool stop(std::string why) { out.message = std::move(why); return false; }

    // The phases in order; out.ok only when all of them ran to the end.
    void run() {
        out.ran = true;
        if (const ParamIssues why = so.validate(); !why.empty()) { out.message = formatIssues(why); return; }
        if (!baselineResidual()) return;
        baselineJacobian();
        if (!lineariseAll() || !holdAll() || !checkSizes()) return;
        makeJobs();
        if (!findSizes()) return;
        dropDuplicates();
        makeNoises();
        if (!runRows() || !falseAlarms()) return;
        out.ok = true;
        out.wallTime_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    }

    // The baseline's residual, its noise blocks and compared samples: the noise level every size
    // and SNR is measured against.
    bool baselineResidual() {
        if (!residualVector(cx, spec, base.values, fitIdx, r0, &blocks)) return stop("baseline residual failed");
        n = r0.size();
        used.assign(n, 0);
        for (const NoiseBlock& b : blocks)
            for (size_t k = 0; k < b.length; ++k) used[b.offset + k] = b.used[k];
        double ss0 = 0;
        for (size_t k = 0; k < n; ++k)
            if (used[k]) { ss0 += r0[k] * r0[k]; count += 1; }
        if (count < 2) return stop("no compared samples");
        out.noiseRms = std::sqrt(ss0 / count);
        out.nullReplicas = opt.nullReplicas;
        out.neff = effectiveCount(count, neffCap);
        // The replicas carry the numerical part as the user's runs do (the loop's null holds it too).
        if (opt.nullNumerics && opt.nullReplicas > 0 && !numericsOffset(cx, spec, base.values, fitIdx, r0, numerics))
            numerics.clear();
        double ssd = 0;
        for (size_t k = 0; k < numerics.size(); ++k)
            if (used[k]) ssd += numerics[k] * numerics[k];
        out.numericsRms = numerics.empty() ? -1.0 : std::sqrt(ssd / count);
        return true;
    }

    // The baseline's Jacobian over its free parameters, and the selection with all of them.
    void baselineJacobian() {
        progress("baseline Jacobian", 0.0);
        const std::vector<FitParameter> ps0 = parameters(cx, spec, base.values);
        for (const FitParameter& p : ps0)
            if (p.free) baseNames.push_back(p.name);
        J0 = residualJacobian(cx, spec, base.values, fitIdx, ps0, baseNames, n);
        allCols.resize(baseNames.size());
        for (size_t j = 0; j < allCols.size(); ++j) allCols[j] = static_cast<Eigen::Index>(j);
        sel = makeSelector(-1);
    }

    // The baseline's columns without `held` (−1: all of them): a baseline parameter on its bound
    // cannot absorb more.
    Eigen::MatrixXd baseColumns(const std::vector<Eigen::Index>& cols, Eigen::Index held) const {
        std::vector<Eigen::Index> keep;
        for (Eigen::Index c : cols)
            if (c != held) keep.push_back(c);
        Eigen::MatrixXd M(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(keep.size()));
        for (size_t j = 0; j < keep.size(); ++j) M.col(static_cast<Eigen::Index>(j)) = J0.col(keep[j]);
        return M;
    }

    // The selection on the baseline without column `held` (−1: the whole baseline).
    Selector makeSelector(Eigen::Index held) const {
        Selector s;
        const Eigen::MatrixXd B = baseColumns(allCols, held);
        s.base = projectionBases(Eigen::MatrixXd(static_cast<Eigen::Index>(n), 0), B);
        s.baseParams = static_cast<int>(B.cols());
        s.count = count;
        s.cap = neffCap;
        s.margin = opt.bicMargin;
        s.useNull = opt.nullReplicas > 0;
        return s;
    }

    // A candidate's bases, parameter count and null quantile, fitted with its baseline columns but `held`.
    void finish(LinearCandidate& lc, Eigen::Index held) const {
        const Eigen::MatrixXd J0c = baseColumns(lc.baseCols, held);
        lc.bases = projectionBases(J0c, lc.Jc);
        lc.params = static_cast<int>(J0c.cols() + lc.Jc.cols());
        lc.nullQuantile = opt.nullReplicas > 0 ? projectionGainNull(lc.bases, blocks, n, opt.nullReplicas, nullSeed, numerics.empty() ? nullptr : &numerics).quantile(1.0 - opt.nullAlpha) : 0.0;
    }

    // The candidate `c` linearised at `vals` (its effect parameters included).
    void linearise(const std::string& c, const std::map<std::string, double>& vals, LinearCandidate& lc) const {
        Spec s2 = spec;
        s2.effects.push_back(c);
        const std::vector<FitParameter> ps = parameters(cx, s2, vals);
        std::vector<std::string> effNames;
        lc.baseCols.clear();
        for (const FitParameter& p : ps) {
            if (!p.free) continue;
            if (p.name.rfind(c + ".", 0) == 0) { effNames.push_back(p.name); continue; }
            const auto it = std::find(baseNames.begin(), baseNames.end(), p.name);
            if (it != baseNames.end()) lc.baseCols.push_back(static_cast<Eigen::Index>(it - baseNames.begin()));
        }
        lc.Jc = residualJacobian(cx, s2, vals, fitIdx, ps, effNames, n);
        lc.name = c;
        finish(lc, -1);
    }

    // Every candidate linearised at its start: the rivals of the injected effect in each replica.
    bool lineariseAll() {
        lin.resize(cands.size());
        for (size_t i = 0; i < cands.size(); ++i) {
            if (cancelled()) return stop("cancelled");
            progress("linearising " + cands[i], static_cast<double>(i) / cands.size());
            linearise(cands[i], effectStart(cx, cands[i], base.values), lin[i]);
        }
        return true;
    }

    // The baseline parameter an effect continues beyond the baseline's range (viscous_damping's
    // ζ in the dynamics set-up): the baseline meets the effect at that parameter's bound, so the
    // injection is measured from the baseline moved there, and the parameter cannot absorb more.
    bool heldFor(const std::string& c, Eigen::Index& col, std::vector<double>& rRef) const {
        EffectInfo info;
        findEffect(c, info);
        const EffectParam& q = info.params.front();
        col = -1;
        if (!q.continues) return true;
        const auto it = std::find(baseNames.begin(), baseNames.end(), std::string(q.continues));
        const double bound = effectVanishes(cx, c, q);
        if (it == baseNames.end() || bound == q.vanishing) return true;
        col = static_cast<Eigen::Index>(it - baseNames.begin());
        std::map<std::string, double> vals = base.values;
        vals[q.continues] = bound;
        return residualVector(cx, spec, vals, fitIdx, rRef) && rRef.size() == n;
    }

    // Per candidate the held column and the reference residual (the baseline's own when none).
    bool holdAll() {
        heldCol.assign(cands.size(), -1);
        reference.resize(cands.size());
        for (size_t i = 0; i < cands.size(); ++i) {
            if (!heldFor(cands[i], heldCol[i], reference[i])) return stop("baseline at the bound of " + cands[i] + " failed");
            if (heldCol[i] < 0) reference[i] = r0;
        }
        return true;
    }

    // Effect c's stated other parameters (SelfTestOptions::shape), by parameter name.
    std::map<std::string, double> shapeOf(const std::string& c) const {
        std::map<std::string, double> out;
        for (const auto& [key, v] : so.shape)
            if (key.compare(0, c.size() + 1, c + ".") == 0) out[key.substr(c.size() + 1)] = v;
        return out;
    }

    // The baseline's values with effect c at `size`, its other parameters at their starts or as
    // stated.
    std::map<std::string, double> injectedValues(const std::string& c, double size) const {
        EffectInfo info;
        findEffect(c, info);
        std::map<std::string, double> vals = effectStart(cx, c, base.values);
        for (const auto& [name, v] : shapeOf(c)) vals[c + "." + name] = v;
        vals[c + "." + info.params.front().name] = size;
        return vals;
    }

    // The injected signal r(baseline + effect at size) − r(reference) on the compared samples.
    void inject(size_t ci, double size, Injection& inj) const {
        const std::string& c = cands[ci];
        const std::map<std::string, double> vals = injectedValues(c, size);
        Spec s2 = spec;
        s2.effects.push_back(c);
        std::vector<double> r;
        inj.size = size;
        inj.ok = residualVector(cx, s2, vals, fitIdx, r) && r.size() == n;
        if (!inj.ok) return;
        const std::vector<double>& ref = reference[ci];
        inj.signal.assign(n, 0.0);
        double ss = 0;
        for (size_t k = 0; k < n; ++k)
            if (used[k]) { inj.signal[k] = r[k] - ref[k]; ss += inj.signal[k] * inj.signal[k]; }
        inj.rms = std::sqrt(ss / count);
    }

    // A stated size must name a candidate and lie within its parameter's physical range.
    bool checkSizes() {
        for (const auto& [name, v] : so.sizes) {
            EffectInfo info;
            findEffect(name, info);
            const EffectParam q = scaledParam(info.params.front(), cx.muScale);
            if (std::find(cands.begin(), cands.end(), name) == cands.end())
                return stop("self-test size given for " + name + ", which is not among the candidates");
            if (!(v >= q.lower && v <= q.upper))
                return stop("self-test size of " + name + "." + q.name + " = " + std::to_string(v) + " " + q.unit +
                            " is outside its physical range [" + std::to_string(q.lower) + ", " + std::to_string(q.upper) + "]");
        }
        for (const auto& [key, v] : so.shape) {
            const std::string name = key.substr(0, key.find('.'));
            if (std::find(cands.begin(), cands.end(), name) == cands.end())
                return stop("self-test parameter given for " + name + ", which is not among the candidates");
            EffectInfo info;
            findEffect(name, info);
            for (const EffectParam& q0 : info.params) {
                const EffectParam q = scaledParam(q0, cx.muScale);
                if (name + "." + q.name == key && !(v >= q.lower && v <= q.upper))
                    return stop("self-test parameter " + key + " = " + std::to_string(v) + " " + q.unit +
                                " is outside its physical range [" + std::to_string(q.lower) + ", " + std::to_string(q.upper) + "]");
            }
        }
        return true;
    }

    // One row per effect and level (or stated size).
    void makeJobs() {
        for (size_t i = 0; i < cands.size(); ++i) {
            if (so.sizes.count(cands[i])) jobs.push_back({i, -1.0, {}});
            else
                for (double l : so.levels) jobs.push_back({i, l, {}});
        }
    }

    // The row's injection: at the stated size, or the size whose signal reaches the level (by
    // bisection between the vanishing value and the physical bound; the bound when it does not).
    void findSize(Job& job) const {
        const std::string& c = cands[job.cand];
        EffectInfo info;
        findEffect(c, info);
        const EffectParam q = scaledParam(info.params.front(), cx.muScale);
        if (job.level < 0) { inject(job.cand, so.sizes.at(c), job.inj); return; }
        const double from = effectVanishes(cx, c, q);
        const double target = job.level * out.noiseRms;
        Injection hi;
        inject(job.cand, sizeAt(q, from, 1.0), hi);
        if (!hi.ok || cancelled()) { job.inj = hi; return; }
        if (hi.rms < target) {
            job.inj = std::move(hi);
            char buf[96];
            std::snprintf(buf, sizeof buf, "at the physical bound: SNR only %.3g", job.inj.rms / out.noiseRms);
            job.inj.note = buf;
            return;
        }
        double lo = 0.0, up = 1.0;
        job.inj = std::move(hi);
        for (int it = 0; it < 24 && !cancelled(); ++it) {  // the signal grows with the size
            const double mid = 0.5 * (lo + up);
            Injection m;
            inject(job.cand, sizeAt(q, from, mid), m);
            if (!m.ok) break;
            if (m.rms < target) lo = mid;
            else { up = mid; job.inj = std::move(m); }
            if (std::abs(job.inj.rms - target) < 0.01 * target) break;
        }
    }

    // Every row's injection, the rows in parallel (each writes only its own job).
    bool findSizes() {
        progress("sizes", 0.0);
        parallelFor(jobs.size(), [&](size_t j) { findSize(jobs[j]); });
        if (cancelled()) return stop("cancelled");
        return true;
    }

    // Levels beyond what the physical range reaches all end on the bound: one row for them.
    void dropDuplicates() {
        std::vector<Job> kept;
        for (Job& j : jobs) {
            const bool dup = std::any_of(kept.begin(), kept.end(), [&](const Job& k) {
                return k.cand == j.cand && k.inj.ok && j.inj.ok && k.inj.size == j.inj.size;
            });
            if (!dup) kept.push_back(std::move(j));
        }
        jobs = std::move(kept);
    }

    // The noise replicas every row uses (the same seeds for every effect and level).
    void makeNoises() {
        for (const LinearCandidate& lc : lin) all.push_back(&lc);
        for (int b = 0; b < so.replicas; ++b) {
            std::vector<double> e = noiseReplica(blocks, n, replicaSeed + static_cast<uint64_t>(b));
            for (size_t k = 0; k < numerics.size(); ++k) e[k] += numerics[k];
            noises.push_back(Eigen::Map<const Vec>(e.data(), static_cast<Eigen::Index>(n)));
        }
    }

    // Per baseline column held on its bound: the selection without it, and every candidate refitted
    // without it (made once, for all the levels of the effect that holds it).
    const Held& heldSelection(Eigen::Index col) {
        auto it = heldCache.find(col);
        if (it == heldCache.end()) {
            Held h{makeSelector(col), lin};
            for (LinearCandidate& lc : h.lin) finish(lc, col);
            it = heldCache.emplace(col, std::move(h)).first;
        }
        return it->second;
    }

    // The row's description: effect, size parameter, level and the note on how its size was reached.
    SelfTestRow describeRow(const Job& job) const {
        const std::string& c = cands[job.cand];
        EffectInfo info;
        findEffect(c, info);
        SelfTestRow row;
        row.effect = c;
        row.sizeParam = info.params.front().name;
        row.unit = info.params.front().unit;
        row.level = job.level;
        row.shape = shapeOf(c);
        row.note = job.inj.note;
        if (row.note.empty() && job.level > 0 && std::abs(job.inj.rms / out.noiseRms - job.level) > 0.1 * job.level)
            row.note = "nearest size within the physical range";
        return row;
    }

    // One row: the selection's pick on each noise replica with the injected signal, the injected
    // candidate linearised at its size and the rivals at their starts (without the held column).
    void runRow(Job& job) {
        const std::string& c = cands[job.cand];
        SelfTestRow row = describeRow(job);
        if (!job.inj.ok) {
            row.note = "the model with the effect could not be simulated";
            out.rows.push_back(row);
            return;
        }
        row.size = job.inj.size;
        row.signalRms = job.inj.rms;
        row.snr = job.inj.rms / out.noiseRms;
        const Eigen::Index held = heldCol[job.cand];
        const Held* h = held < 0 ? nullptr : &heldSelection(held);
        const Selector& jobSel = h ? h->sel : sel;
        {
            const Eigen::Map<const Vec> sv(job.inj.signal.data(), static_cast<Eigen::Index>(n));
            const double vis = std::max(sv.squaredNorm() - squaredNorm(jobSel.base.Qc, sv), 0.0);
            row.visibleSnr = std::sqrt(vis / count) / out.noiseRms;
        }
        // The injected candidate linearised where the effect is (a fit would start there after its scan).
        LinearCandidate atSize;
        linearise(c, injectedValues(c, job.inj.size), atSize);
        std::vector<const LinearCandidate*> cs = all;
        if (h)
            for (size_t i = 0; i < h->lin.size(); ++i) cs[i] = &h->lin[i];
        cs[job.cand] = &atSize;
        const Eigen::Map<const Vec> sig(job.inj.signal.data(), static_cast<Eigen::Index>(n));
        for (const Vec& nv : noises) {
            const Vec e = sig + nv;
            const int p = jobSel.pick(e, cs, static_cast<int>(job.cand), &nv);
            ++row.replicas;
            if (p == static_cast<int>(job.cand)) ++row.detected;
            else if (p < 0) ++row.missed;
            else { ++row.confused; ++row.confusedWith[cands[static_cast<size_t>(p)]]; }
        }
        out.rows.push_back(std::move(row));
    }

    // Every row in order, cancellable between rows.
    bool runRows() {
        for (size_t j = 0; j < jobs.size(); ++j) {
            if (cancelled()) return stop("cancelled");
            progress("replicas of " + cands[jobs[j].cand], static_cast<double>(j) / jobs.size());
            runRow(jobs[j]);
        }
        return true;
    }

    // False alarms: replicas of the baseline with noise only (as many as all effects' replicas of one level).
    bool falseAlarms() {
        progress("replicas without an effect", 1.0);
        const int nNull = so.replicas * static_cast<int>(std::max<size_t>(cands.size(), 1));
        for (int b = 0; b < nNull && !cancelled(); ++b) {
            std::vector<double> noise = noiseReplica(blocks, n, replicaSeed + 500009u + static_cast<uint64_t>(b));
            for (size_t k = 0; k < numerics.size(); ++k) noise[k] += numerics[k];
            const int p = sel.pick(Eigen::Map<const Vec>(noise.data(), static_cast<Eigen::Index>(n)), all);
            ++out.falseAlarmReplicas;
            if (p >= 0) { ++out.falseAlarms; ++out.falseAlarmsBy[cands[static_cast<size_t>(p)]]; }
        }
        if (cancelled()) return stop("cancelled");
        return true;
    }
};

}  // namespace

SelfTestResult runSelfTest(const Context& cx, const Spec& spec, const FitOutcome& base, const std::vector<size_t>& fitIdx,
                           const std::vector<std::string>& cands, double neffCap) {
    SelfTestRun st(cx, spec, base, fitIdx, cands, neffCap);
    st.run();
    return std::move(st.out);
}

}  // namespace detail

nlohmann::json toJson(const SelfTestResult& r) {
    nlohmann::json j;
    j["ok"] = r.ok;
    if (!r.message.empty()) j["message"] = r.message;
    j["method"] = "replicas = fitted baseline + injected effect (simulated) + AR(1) noise of the baseline residual; "
                  "tests (1a) dBIC and (1b) noise null of the selection in the linearised refit; the held-out and "
                  "size tests are not applied (detection rates are upper bounds for the full loop)";
    j["noise_rms"] = r.noiseRms;
    j["numerics_rms"] = r.numericsRms >= 0 ? nlohmann::json(r.numericsRms) : nlohmann::json(nullptr);
    j["n_eff"] = r.neff;
    j["null_replicas"] = r.nullReplicas;
    j["false_alarm_replicas"] = r.falseAlarmReplicas;
    j["false_alarms"] = r.falseAlarms;
    j["false_alarm_rate"] = r.falseAlarmReplicas > 0 ? static_cast<double>(r.falseAlarms) / r.falseAlarmReplicas : 0.0;
    j["false_alarms_by_effect"] = r.falseAlarmsBy;
    j["wall_time_s"] = r.wallTime_s;
    nlohmann::json rows = nlohmann::json::array();
    for (const SelfTestRow& w : r.rows) {
        nlohmann::json x;
        x["effect"] = w.effect;
        x["size_parameter"] = w.sizeParam;
        x["unit"] = w.unit;
        x["size"] = w.size;
        if (w.level >= 0) x["level"] = w.level;
        else x["level"] = nullptr;
        x["signal_rms"] = w.signalRms;
        x["snr"] = w.snr;
        x["visible_snr"] = w.visibleSnr;
        x["replicas"] = w.replicas;
        x["detected"] = w.detected;
        x["confused"] = w.confused;
        x["missed"] = w.missed;
        x["detection_rate"] = w.replicas > 0 ? static_cast<double>(w.detected) / w.replicas : 0.0;
        x["confused_with"] = w.confusedWith;
        if (!w.shape.empty()) x["shape"] = w.shape;
        if (!w.note.empty()) x["note"] = w.note;
        rows.push_back(x);
    }
    j["rows"] = rows;
    return j;
}

}  // namespace stickslip::identify
