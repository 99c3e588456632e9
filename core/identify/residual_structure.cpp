// residualStructure (diagnostics.hpp): is the residual predictable from the runs' own state, run
// to run? Every fit below is a per-group mean or line, so each run is reduced once to per-group
// sums per feature, and a fit on any set of runs and its squared error on any other run are sums
// over those tables: no sample is visited twice.
#include <algorithm>
#include <cmath>
#include <iterator>
#include <numeric>
#include <string>

#include "diagnostics.hpp"

namespace stickslip::identify {

namespace {

// One run's residual summed per group of one feature: a group is a quantile bin of the signal
// (a step function: the group's mean) or one sign of it (a line in the signal). The sums are
// sufficient for both fits and for the squared error of either on the run.
struct GroupSums {
    std::vector<double> n, x, xx, r, xr, rr;  // count, Σ x, Σ x², Σ r, Σ x r, Σ r² per group
    void resize(size_t groups) {
        for (auto* v : {&n, &x, &xx, &r, &xr, &rr}) v->assign(groups, 0.0);
    }
    void add(size_t g, double xv, double rv) {
        n[g] += 1.0, x[g] += xv, xx[g] += xv * xv, r[g] += rv, xr[g] += xv * rv, rr[g] += rv * rv;
    }
};

// Per group, r ≈ a + b x (b = 0: a step function, or a line whose x does not vary); 0 in a
// group none of the fitted runs reaches.
struct GroupFit {
    std::vector<double> a, b;
};
// Quantile bin edges of the sorted, finite pooled values `v` (interior edges, strictly increasing:
// ties merge bins).
std::vector<double> quantileEdges(const std::vector<double>& v, int bins) {
    std::vector<double> edges;
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

// A line's groups: the signal's negative values, zero (and non-finite, as 0), positive values.
// The signals are odd in the slip velocity, so these are the two slip directions and stick.
size_t signGroupOf(double& x) {
    if (!std::isfinite(x) || x == 0.0) {
        x = 0.0;
        return 1;
    }
    return x < 0 ? 0 : 2;
}

// The least-squares fit per group over the runs in `use` (true): a line when `line` and x varies
// in the group, its mean otherwise.
GroupFit fitGroups(const std::vector<GroupSums>& perRun, const std::vector<char>& use, bool line) {
    const size_t ng = perRun.empty() ? 0 : perRun.front().n.size();
    GroupSums p;
    p.resize(ng);
    for (size_t r = 0; r < perRun.size(); ++r) {
        if (!use[r]) continue;
        for (size_t g = 0; g < ng; ++g) {
            p.n[g] += perRun[r].n[g], p.x[g] += perRun[r].x[g], p.xx[g] += perRun[r].xx[g];
            p.r[g] += perRun[r].r[g], p.xr[g] += perRun[r].xr[g];
        }
    }
    GroupFit f{std::vector<double>(ng, 0.0), std::vector<double>(ng, 0.0)};
    for (size_t g = 0; g < ng; ++g) {
        if (!(p.n[g] > 0)) continue;
        const double sxx = p.xx[g] - p.x[g] * p.x[g] / p.n[g];
        if (line && p.n[g] >= 3 && sxx > 1e-12 * p.xx[g]) f.b[g] = (p.xr[g] - p.x[g] * p.r[g] / p.n[g]) / sxx;
        f.a[g] = (p.r[g] - f.b[g] * p.x[g]) / p.n[g];
    }
    return f;
}

// Σ (r − a − b x)² over one run, from its sums.
double sqErrorAfter(const GroupSums& run, const GroupFit& f) {
    double e = 0.0;
    for (size_t g = 0; g < f.a.size(); ++g) {
        const double a = f.a[g], b = f.b[g];
        e += run.rr[g] - 2.0 * a * run.r[g] - 2.0 * b * run.xr[g] + a * a * run.n[g] + 2.0 * a * b * run.x[g] + b * b * run.xx[g];
    }
    return std::max(e, 0.0);
}

double sqError(const GroupSums& run) { return std::accumulate(run.rr.begin(), run.rr.end(), 0.0); }

// One feature: a signal as a step function at one resolution, or as a line per sign.
struct Feature {
    size_t signal = 0;
    bool line = false;
    std::vector<GroupSums> perRun;
};

// ln(before/after) for run `i` predicted by feature `f` fitted on the runs in `use`.
double logRatio(const Feature& f, size_t i, const std::vector<char>& use) {
    const double before = sqError(f.perRun[i]), after = sqErrorAfter(f.perRun[i], fitGroups(f.perRun, use, f.line));
    return before > 0 && after > 0 ? std::log(before / after) : 0.0;
}

// The feature whose fit on the runs in `use` (at least one) predicts them best: by the inner
// leave-one-run-out (each of them predicted from the others) when there are two or more, by its
// fit to the one run otherwise (then only the base resolution is offered, which a fit to itself
// cannot choose). Only the features in `among`. −1 when none has a positive score.
int chooseFeature(const std::vector<Feature>& features, const std::vector<char>& use, const std::vector<size_t>& among) {
    std::vector<size_t> members;
    for (size_t r = 0; r < use.size(); ++r)
        if (use[r]) members.push_back(r);
    int best = -1;
    double bestScore = 0.0;
    for (size_t j : among) {
        double score = 0.0;
        if (members.size() == 1) {
            score = logRatio(features[j], members.front(), use);
        } else {
            for (size_t i : members) {
                std::vector<char> others = use;
                others[i] = 0;
                score += logRatio(features[j], i, others);
            }
        }
        if (score > bestScore) bestScore = score, best = static_cast<int>(j);
    }
    return best;
}

// ln(before/after) for run i held out: the feature chosen among `among` on the other runs,
// fitted on them, predicts it (0 when none is chosen). `chosen` gets the feature, −1 for none.
double heldOutLogRatio(const std::vector<Feature>& features, size_t i, const std::vector<size_t>& among, int& chosen,
                       double& before, double& after) {
    std::vector<char> others(features.front().perRun.size(), 1);
    others[i] = 0;
    chosen = chooseFeature(features, others, among);
    before = sqError(features.front().perRun[i]);
    if (chosen < 0) {
        after = before;
    } else {
        const Feature& f = features[static_cast<size_t>(chosen)];
        after = sqErrorAfter(f.perRun[i], fitGroups(f.perRun, others, f.line));
    }
    return before > 0 && after > 0 ? std::log(before / after) : 0.0;
}

}  // namespace

// The resolutions tried per signal, as multiples of Rice's bin count: the inner
// leave-one-run-out chooses among them, so a sharp transient (ringing within milliseconds of a
// reversal) gets fine bins and a slow trend coarse ones, each judged on runs it was not fitted on.
// Besides them, each signal as a line per sign: a step function cannot predict a run whose signal
// lies between the other runs' values (a normal load, a dwell time, a run's own velocity range,
// each different per run), a line interpolates.
constexpr double kResolutions[] = {0.25, 0.5, 1.0, 2.0, 4.0};
constexpr size_t kBaseResolution = 2;  // index of 1.0
constexpr size_t kPerSignal = std::size(kResolutions) + 1;  // the step functions, then the line

namespace {

// Every signal's features (kPerSignal each, in that order), each run reduced to its sums.
std::vector<Feature> buildFeatures(const std::vector<const StructureRun*>& runs, size_t signals, size_t total, int riceBins) {
    std::vector<Feature> features;
    features.reserve(signals * kPerSignal);
    for (size_t j = 0; j < signals; ++j) {
        std::vector<double> pooled;
        pooled.reserve(total);
        for (const StructureRun* r : runs)  // the samples that have a residual (the law channel masks some)
            for (size_t q = 0; q < r->residual.size(); ++q)
                if (std::isfinite(r->residual[q]) && std::isfinite(r->predictors[j][q])) pooled.push_back(r->predictors[j][q]);
        std::sort(pooled.begin(), pooled.end());
        for (size_t k = 0; k < kPerSignal; ++k) {
            Feature f{j, k == std::size(kResolutions), std::vector<GroupSums>(runs.size())};
            const std::vector<double> edges =
                f.line ? std::vector<double>{}
                       : quantileEdges(pooled, std::max(2, static_cast<int>(std::lround(kResolutions[k] * riceBins))));
            for (size_t r = 0; r < runs.size(); ++r) {
                GroupSums& g = f.perRun[r];
                g.resize(f.line ? 3 : edges.size() + 1);
                const std::vector<double>& res = runs[r]->residual;
                for (size_t q = 0; q < res.size(); ++q) {
                    if (!std::isfinite(res[q])) continue;
                    double x = runs[r]->predictors[j][q];
                    if (f.line)
                        g.add(signGroupOf(x), x, res[q]);
                    else
                        g.add(binOf(edges, x), 0.0, res[q]);
                }
            }
            features.push_back(std::move(f));
        }
    }
    return features;
}

std::string describe(const Feature& f, const std::vector<std::string>& names) {
    return names[f.signal] + (f.line ? " (line per sign)" : " (" + std::to_string(f.perRun.front().n.size()) + " bins)");
}

}  // namespace

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
    const std::vector<Feature> features = buildFeatures(runs, names.size(), total, out.bins);
    // With two runs a feature is chosen by its fit to the other run, which always prefers finer
    // bins (and a step function to a line): only the base resolution then.
    auto featuresOf = [&](const std::vector<size_t>& which) {
        std::vector<size_t> f;
        for (size_t j : which)
            for (size_t k = 0; k < kPerSignal; ++k)
                if (runs.size() > 2 || k == kBaseResolution) f.push_back(j * kPerSignal + k);
        return f;
    };
    std::vector<size_t> all(names.size());
    std::iota(all.begin(), all.end(), size_t{0});
    std::vector<double> before, after;
    for (size_t i = 0; i < runs.size(); ++i) {
        int chosen = -1;
        double b = 0, a = 0;
        out.logRatios.push_back(heldOutLogRatio(features, i, featuresOf(all), chosen, b, a));
        before.push_back(b);
        after.push_back(a);
        out.chosen.push_back(chosen < 0 ? "" : describe(features[static_cast<size_t>(chosen)], names));
    }
    out.test = pairedLogRatioTest(before, after);
    for (size_t j = 0; j < names.size(); ++j) {
        double m = 0.0;
        for (size_t i = 0; i < runs.size(); ++i) {
            int chosen = -1;
            double b = 0, a = 0;
            m += heldOutLogRatio(features, i, featuresOf({j}), chosen, b, a);
        }
        out.bySignal.push_back({names[j], m / static_cast<double>(runs.size())});
    }
    std::stable_sort(out.bySignal.begin(), out.bySignal.end(),
                     [](const SignalGain& a, const SignalGain& b) { return a.meanLogRatio > b.meanLogRatio; });
    return out;
}

}  // namespace stickslip::identify
