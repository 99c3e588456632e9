// residualStructure (diagnostics.hpp): is the residual predictable from the runs' own state, run
// to run? Every fit below is a table of bin means, so each run is reduced once to per-bin sums
// (count, Σr, Σr²) per signal, and a fit on any set of runs and its squared error on any other
// run are sums over those tables: no sample is visited twice.
#include <algorithm>
#include <cmath>
#include <limits>
#include <iterator>
#include <numeric>

#include "diagnostics.hpp"

namespace stickslip::identify {

namespace {

// One run's residual summed per bin of one signal.
struct BinSums {
    std::vector<double> n, s, ss;  // count, Σ r, Σ r² per bin
};

// Quantile bin edges of the sorted pooled values (interior edges, strictly increasing: ties merge
// bins; non-finite values ignored).
std::vector<double> quantileEdges(const std::vector<double>& sorted, int bins) {
    std::vector<double> edges, v;
    for (double x : sorted)
        if (std::isfinite(x)) v.push_back(x);
    if (v.empty()) return edges;
    for (int b = 1; b < bins; ++b) {
        const double e = v[static_cast<size_t>(static_cast<double>(b) / bins * (v.size() - 1))];
        if (edges.empty() || e > edges.back()) edges.push_back(e);
    }
    // A value equal to the last edge belongs above it (upper_bound below); drop an edge at the
    // maximum, which would leave its upper bin empty.
    if (!edges.empty() && edges.back() >= v.back()) edges.pop_back();
    return edges;
}

size_t binOf(const std::vector<double>& edges, double x) {
    if (!std::isfinite(x)) return 0;
    return static_cast<size_t>(std::upper_bound(edges.begin(), edges.end(), x) - edges.begin());
}

// The bin means of the runs in `use` (true), 0 in a bin none of them reaches.
std::vector<double> binMeans(const std::vector<BinSums>& perRun, const std::vector<char>& use) {
    const size_t nb = perRun.empty() ? 0 : perRun.front().n.size();
    std::vector<double> n(nb, 0.0), s(nb, 0.0);
    for (size_t r = 0; r < perRun.size(); ++r) {
        if (!use[r]) continue;
        for (size_t b = 0; b < nb; ++b) n[b] += perRun[r].n[b], s[b] += perRun[r].s[b];
    }
    std::vector<double> m(nb, 0.0);
    for (size_t b = 0; b < nb; ++b)
        if (n[b] > 0) m[b] = s[b] / n[b];
    return m;
}

// Σ (r − m_bin)² over one run: Σ_b (Σr² − 2 m_b Σr + m_b² n_b).
double sqErrorAfter(const BinSums& run, const std::vector<double>& m) {
    double e = 0.0;
    for (size_t b = 0; b < m.size(); ++b) e += run.ss[b] - 2.0 * m[b] * run.s[b] + m[b] * m[b] * run.n[b];
    return std::max(e, 0.0);
}

double sqError(const BinSums& run) { return std::accumulate(run.ss.begin(), run.ss.end(), 0.0); }

// ln(before/after) for run `i` predicted by signal `j` fitted on the runs in `use`.
double logRatio(const std::vector<std::vector<BinSums>>& sums, size_t j, size_t i, const std::vector<char>& use) {
    const double before = sqError(sums[j][i]), after = sqErrorAfter(sums[j][i], binMeans(sums[j], use));
    return before > 0 && after > 0 ? std::log(before / after) : 0.0;
}

// The feature (a signal at one resolution) whose step function, fitted on the runs in `use`
// (at least one), predicts them best: by the inner leave-one-run-out (each of them predicted
// from the others) when there are two or more, by its fit to the one run otherwise (then only at
// the base resolution, which a fit to itself cannot choose). Only the features in `among`.
// −1 when none has a positive score.
int chooseFeature(const std::vector<std::vector<BinSums>>& sums, const std::vector<char>& use, const std::vector<size_t>& among) {
    std::vector<size_t> members;
    for (size_t r = 0; r < use.size(); ++r)
        if (use[r]) members.push_back(r);
    int best = -1;
    double bestScore = 0.0;
    for (size_t j : among) {
        double score = 0.0;
        if (members.size() == 1) {
            score = logRatio(sums, j, members.front(), use);
        } else {
            for (size_t i : members) {
                std::vector<char> others = use;
                others[i] = 0;
                score += logRatio(sums, j, i, others);
            }
        }
        if (score > bestScore) bestScore = score, best = static_cast<int>(j);
    }
    return best;
}

// ln(before/after) for run i held out: the feature chosen among `among` on the other runs,
// fitted on them, predicts it (0 when none is chosen). `chosen` gets the feature, −1 for none.
double heldOutLogRatio(const std::vector<std::vector<BinSums>>& sums, size_t i, const std::vector<size_t>& among, int& chosen,
                       double& before, double& after) {
    std::vector<char> others(sums.front().size(), 1);
    others[i] = 0;
    chosen = chooseFeature(sums, others, among);
    before = sqError(sums.front()[i]);
    after = chosen < 0 ? before : sqErrorAfter(sums[static_cast<size_t>(chosen)][i], binMeans(sums[static_cast<size_t>(chosen)], others));
    return before > 0 && after > 0 ? std::log(before / after) : 0.0;
}

}  // namespace

// The resolutions tried per signal, as multiples of Rice's bin count: the inner
// leave-one-run-out chooses among them, so a sharp transient (ringing within milliseconds of a
// reversal) gets fine bins and a slow trend coarse ones, each judged on runs it was not fitted on.
constexpr double kResolutions[] = {0.25, 0.5, 1.0, 2.0, 4.0};
constexpr size_t kBaseResolution = 2;  // index of 1.0

StructureTest residualStructure(const std::vector<DiagnosticRun>& runs, double vStick) {
    std::vector<StructureRun> sr;
    for (const DiagnosticRun& r : runs)
        if (r.t_s.size() == r.residual.size()) sr.push_back({r.residual, candidateSignals(r, vStick)});
    return residualStructure(sr, candidateSignalNames());
}

StructureTest residualStructure(const std::vector<StructureRun>& allRuns, const std::vector<std::string>& names) {
    StructureTest out;
    std::vector<const StructureRun*> runs;
    for (const StructureRun& r : allRuns) {
        bool ok = !r.residual.empty() && r.predictors.size() == names.size();
        for (const auto& s : r.predictors) ok = ok && s.size() == r.residual.size();
        if (ok) runs.push_back(&r);
    }
    size_t total = 0;
    for (const StructureRun* r : runs)
        total += static_cast<size_t>(std::count_if(r->residual.begin(), r->residual.end(), [](double v) { return std::isfinite(v); }));
    out.runs = static_cast<int>(runs.size());
    if (runs.size() < 2 || names.empty()) return out;
    out.bins = static_cast<int>(std::ceil(2.0 * std::cbrt(static_cast<double>(total))));
    // Features: signal j at resolution k is feature j·R + k; sums[feature][run].
    constexpr size_t R = std::size(kResolutions);
    std::vector<std::vector<BinSums>> sums(names.size() * R, std::vector<BinSums>(runs.size()));
    for (size_t j = 0; j < names.size(); ++j) {
        std::vector<double> pooled;
        pooled.reserve(total);
        for (const StructureRun* r : runs)  // the samples that have a residual (the law channel masks some)
            for (size_t q = 0; q < r->residual.size(); ++q)
                if (std::isfinite(r->residual[q])) pooled.push_back(r->predictors[j][q]);
        std::sort(pooled.begin(), pooled.end());
        for (size_t k = 0; k < R; ++k) {
            const int bins = std::max(2, static_cast<int>(std::lround(kResolutions[k] * out.bins)));
            const std::vector<double> edges = quantileEdges(pooled, bins);
            for (size_t r = 0; r < runs.size(); ++r) {
                BinSums& b = sums[j * R + k][r];
                b.n.assign(edges.size() + 1, 0.0);
                b.s = b.ss = b.n;
                const std::vector<double>& res = runs[r]->residual;
                for (size_t q = 0; q < res.size(); ++q) {
                    if (!std::isfinite(res[q])) continue;
                    const size_t bin = binOf(edges, runs[r]->predictors[j][q]);
                    b.n[bin] += 1.0, b.s[bin] += res[q], b.ss[bin] += res[q] * res[q];
                }
            }
        }
    }
    // With two runs a feature is chosen by its fit to the other run, which always prefers finer
    // bins: only the base resolution then.
    auto featuresOf = [&](const std::vector<size_t>& which) {
        std::vector<size_t> f;
        for (size_t j : which)
            for (size_t k = 0; k < R; ++k)
                if (runs.size() > 2 || k == kBaseResolution) f.push_back(j * R + k);
        return f;
    };
    std::vector<size_t> all(names.size());
    std::iota(all.begin(), all.end(), size_t{0});
    std::vector<double> before, after;
    for (size_t i = 0; i < runs.size(); ++i) {
        int chosen = -1;
        double b = 0, a = 0;
        out.logRatios.push_back(heldOutLogRatio(sums, i, featuresOf(all), chosen, b, a));
        before.push_back(b);
        after.push_back(a);
        out.chosen.push_back(chosen < 0 ? "" : names[static_cast<size_t>(chosen) / R] + " (" +
                                                   std::to_string(sums[static_cast<size_t>(chosen)][i].n.size()) + " bins)");
    }
    out.test = pairedLogRatioTest(before, after);
    for (size_t j = 0; j < names.size(); ++j) {
        double m = 0.0;
        for (size_t i = 0; i < runs.size(); ++i) {
            int chosen = -1;
            double b = 0, a = 0;
            m += heldOutLogRatio(sums, i, featuresOf({j}), chosen, b, a);
        }
        out.bySignal.push_back({names[j], m / static_cast<double>(runs.size())});
    }
    std::stable_sort(out.bySignal.begin(), out.bySignal.end(),
                     [](const SignalGain& a, const SignalGain& b) { return a.meanLogRatio > b.meanLogRatio; });
    return out;
}

}  // namespace stickslip::identify
