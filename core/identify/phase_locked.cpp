#include <algorithm>
#include <cmath>
#include <limits>

#include "../dsp/iir.hpp"
#include "diagnostics.hpp"

namespace stickslip::identify {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr int kMinCycles = 3;  // each cycle predicted by the mean of at least two others
constexpr int kMinBins = 4;
constexpr int kBandOrder = 4;  // the order of the cleaning low-pass (FilterSettings)

struct RunGain {
    double base = 0, error = 0;  // Σ x², Σ (x − S_other)² over the whole cycles
    int bins = 0;
};

// One run: cycle k covers t0 + [k, k+1)/f; each cycle's own mean is removed; each cycle's
// samples are predicted by the bin means of all the other cycles. The bin means are taken of
// the residual below band_Hz (zero-phase Butterworth; all of it when band_Hz ≤ 0 or above the
// samples' reach); the gain is judged against the whole residual.
RunGain runGain(const DiagnosticRun& run, int samplesPerBin, double vStick, double band_Hz) {
    RunGain g;
    const size_t n = std::min(run.t_s.size(), run.residual.size());
    if (n < 2) return g;
    const double f = forcingFrequencyOf(run, vStick);
    const double t0 = run.t_s.front();
    const double dt = (run.t_s[n - 1] - t0) / static_cast<double>(n - 1);
    if (!(dt > 0) || !(f > 0)) return g;
    const int cycles = static_cast<int>(std::floor((run.t_s[n - 1] - t0) * f));
    const int bins = static_cast<int>(std::floor(1.0 / (f * dt) / std::max(samplesPerBin, 1)));
    if (cycles < kMinCycles || bins < kMinBins) return g;
    const std::vector<double> r(run.residual.begin(), run.residual.begin() + static_cast<long>(n));
    const bool band = band_Hz > 0 && band_Hz < 0.45 / dt;
    const std::vector<double> y = band ? dsp::filtfilt(dsp::butterworthLowpass(kBandOrder, band_Hz, 1.0 / dt), r) : r;
    std::vector<int> cyc(n), bin(n);
    std::vector<double> cycSum(static_cast<size_t>(cycles), 0.0), cycSumY(cycSum), cycN(cycSum);
    for (size_t i = 0; i < n; ++i) {
        // A millionth of a bin forward: samples on a regular grid whose cycle holds a whole
        // number of bins sit exactly on bin edges, where rounding would scatter them.
        const double ph = (run.t_s[i] - t0) * f + 1e-6 / bins;
        cyc[i] = static_cast<int>(std::floor(ph));
        bin[i] = std::min(bins - 1, static_cast<int>((ph - std::floor(ph)) * bins));
        if (cyc[i] < 0 || cyc[i] >= cycles) continue;
        const size_t c = static_cast<size_t>(cyc[i]);
        cycSum[c] += r[i];
        cycSumY[c] += y[i];
        cycN[c] += 1.0;
    }
    // Bin sums over all cycles and per cycle: a cycle is predicted by the mean of the others.
    const size_t B = static_cast<size_t>(bins);
    std::vector<double> sum(B, 0.0), cnt(B, 0.0), cycBinSum(static_cast<size_t>(cycles) * B, 0.0), cycBinN(cycBinSum);
    for (size_t i = 0; i < n; ++i) {
        if (cyc[i] < 0 || cyc[i] >= cycles) continue;
        const size_t c = static_cast<size_t>(cyc[i]), k = static_cast<size_t>(bin[i]);
        const double v = y[i] - cycSumY[c] / cycN[c];
        sum[k] += v;
        cnt[k] += 1.0;
        cycBinSum[c * B + k] += v;
        cycBinN[c * B + k] += 1.0;
    }
    for (size_t i = 0; i < n; ++i) {
        if (cyc[i] < 0 || cyc[i] >= cycles) continue;
        const size_t c = static_cast<size_t>(cyc[i]), k = static_cast<size_t>(bin[i]);
        const double x = r[i] - cycSum[c] / cycN[c];
        const double others = cnt[k] - cycBinN[c * B + k];
        const double s = others > 0 ? (sum[k] - cycBinSum[c * B + k]) / others : 0.0;
        g.base += x * x;
        g.error += (x - s) * (x - s);
    }
    g.bins = bins;
    return g;
}

}  // namespace

PhaseLocked phaseLockedStructure(const std::vector<DiagnosticRun>& runs, int samplesPerBin, double vStick, double band_Hz) {
    PhaseLocked out;
    out.band_Hz = band_Hz;
    std::vector<double> before, after;
    for (const DiagnosticRun& run : runs) {
        const RunGain g = runGain(run, samplesPerBin, vStick, band_Hz);
        const bool used = g.bins > 0 && g.base > 0 && g.error > 0;
        out.binsPerCycle.push_back(used ? g.bins : 0);
        out.runLogRatio.push_back(used ? std::log(g.base / g.error) : kNaN);
        if (!used) continue;
        before.push_back(g.base);
        after.push_back(g.error);
    }
    out.runs = static_cast<int>(before.size());
    if (out.runs == 0) return out;
    out.test = pairedLogRatioTest(before, after);
    out.meanLogRatio = out.test.meanLogRatio;
    out.share = -std::expm1(-out.meanLogRatio);
    return out;
}

}  // namespace stickslip::identify
