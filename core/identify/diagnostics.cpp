#include "diagnostics.hpp"

#include <fftw3.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>

namespace stickslip::identify {

std::vector<std::string> candidateSignalNames() {
    return {"signV",        "V",  "absV",      "dVdt",       "accel",      "displacement", "time_since_reversal",
            "time_stuck_before_slip", "accumulated_slip", "tN", "run_index", "cycle_index"};
}

namespace {

std::vector<double> centralDifference(const std::vector<double>& t, const std::vector<double>& y) {
    const size_t n = y.size();
    std::vector<double> d(n, 0.0);
    if (n < 2 || t.size() != n) return d;
    d[0] = (y[1] - y[0]) / (t[1] - t[0]);
    d[n - 1] = (y[n - 1] - y[n - 2]) / (t[n - 1] - t[n - 2]);
    for (size_t i = 1; i + 1 < n; ++i) d[i] = (y[i + 1] - y[i - 1]) / (t[i + 1] - t[i - 1]);
    return d;
}

}  // namespace

// Friction residuals flip with the slip direction, so every signal except absV is made odd
// in V (multiplied by sign V) — a constant or slowly varying effect on μ then shows up as a
// correlation with the signal rather than cancelling between the two directions.
std::vector<std::vector<double>> candidateSignals(const DiagnosticRun& run, double vStick) {
    const size_t n = run.residual.size();
    std::vector<std::vector<double>> out(candidateSignalNames().size(), std::vector<double>(n, 0.0));
    if (n == 0 || run.t_s.size() != n || run.relVel_mps.size() != n) return out;
    const std::vector<double>& V = run.relVel_mps;
    const std::vector<double> dV = centralDifference(run.t_s, V);
    const bool haveAcc = run.accel_mps2.size() == n;
    // Forcing frequency: given, or from the number of reversals.
    double f = run.forcingFrequency_Hz;
    double lastSign = 0;
    if (!(f > 0)) {
        int reversals = 0;
        for (size_t i = 0; i < n; ++i) {
            if (std::abs(V[i]) < vStick) continue;
            const double sg = V[i] > 0 ? 1 : -1;
            if (lastSign != 0 && sg != lastSign) ++reversals;
            lastSign = sg;
        }
        const double dur = run.t_s.back() - run.t_s.front();
        f = dur > 0 ? std::max(reversals, 1) / (2.0 * dur) : 1.0;
    }
    lastSign = 0;
    double tReversal = run.t_s[0], stickStart = run.t_s[0], lastStick = 0, slip = run.accumulatedSlipStart_m;
    bool inStick = true;
    const bool haveSlip = run.slip_m.size() == n;
    for (size_t i = 0; i < n; ++i) {
        const double t = run.t_s[i];
        const bool stuck = std::abs(V[i]) < vStick;
        const double sg = stuck ? 0.0 : (V[i] > 0 ? 1.0 : -1.0);
        if (!stuck) {
            if (lastSign != 0 && sg != lastSign) tReversal = t;
            lastSign = sg;
            if (inStick) { lastStick = t - stickStart; inStick = false; }
        } else if (!inStick) {
            inStick = true;
            stickStart = t;
        }
        if (i > 0 && haveSlip) slip += std::abs(run.slip_m[i] - run.slip_m[i - 1]);
        const double s = lastSign;  // direction of the current (or last) slip
        out[0][i] = sg;
        out[1][i] = V[i];
        out[2][i] = std::abs(V[i]);
        out[3][i] = dV[i];
        out[4][i] = haveAcc ? run.accel_mps2[i] : dV[i];
        out[5][i] = haveSlip ? run.slip_m[i] : 0.0;
        out[6][i] = s * (t - tReversal);
        out[7][i] = stuck ? 0.0 : s * lastStick;
        out[8][i] = s * slip;
        out[9][i] = s * run.normalForce_N;
        out[10][i] = s * run.runIndex;
        out[11][i] = s * std::floor((t - run.t_s[0]) * f);
    }
    return out;
}

double pearson(const std::vector<double>& a, const std::vector<double>& b) {
    const size_t n = std::min(a.size(), b.size());
    if (n < 2) return 0.0;
    double ma = 0, mb = 0;
    for (size_t i = 0; i < n; ++i) { ma += a[i]; mb += b[i]; }
    ma /= n; mb /= n;
    double sab = 0, saa = 0, sbb = 0;
    for (size_t i = 0; i < n; ++i) {
        const double da = a[i] - ma, db = b[i] - mb;
        sab += da * db; saa += da * da; sbb += db * db;
    }
    if (saa <= 0 || sbb <= 0) return 0.0;
    const double r = sab / std::sqrt(saa * sbb);
    return std::isfinite(r) ? r : 0.0;
}

std::vector<double> autocorrelation(const std::vector<double>& x, int maxLag) {
    const size_t n = x.size();
    std::vector<double> acf(std::max(maxLag, 0) + 1, 0.0);
    if (n < 2) { acf[0] = 1.0; return acf; }
    const double mean = std::accumulate(x.begin(), x.end(), 0.0) / n;
    size_t nfft = 1;
    while (nfft < 2 * n) nfft <<= 1;
    double* in = fftw_alloc_real(nfft);
    fftw_complex* spec = fftw_alloc_complex(nfft / 2 + 1);
    fftw_plan fwd = fftw_plan_dft_r2c_1d(static_cast<int>(nfft), in, spec, FFTW_ESTIMATE);
    fftw_plan bwd = fftw_plan_dft_c2r_1d(static_cast<int>(nfft), spec, in, FFTW_ESTIMATE);
    for (size_t i = 0; i < nfft; ++i) in[i] = i < n ? x[i] - mean : 0.0;
    fftw_execute(fwd);
    for (size_t k = 0; k < nfft / 2 + 1; ++k) {  // |X|², zero-padded: linear (not circular) correlation
        spec[k][0] = spec[k][0] * spec[k][0] + spec[k][1] * spec[k][1];
        spec[k][1] = 0.0;
    }
    fftw_execute(bwd);
    const double c0 = in[0];
    for (int k = 0; k <= maxLag; ++k) acf[k] = (c0 > 0 && static_cast<size_t>(k) < n) ? in[k] / c0 : (k == 0 ? 1.0 : 0.0);
    fftw_destroy_plan(fwd);
    fftw_destroy_plan(bwd);
    fftw_free(in);
    fftw_free(spec);
    return acf;
}

// Regularised upper incomplete gamma Q(a, x) (series for x < a+1, continued fraction else).
static double gammaQ(double a, double x) {
    if (x <= 0) return 1.0;
    const double lg = std::lgamma(a);
    if (x < a + 1.0) {
        double ap = a, sum = 1.0 / a, del = sum;
        for (int i = 0; i < 1000; ++i) {
            ap += 1.0; del *= x / ap; sum += del;
            if (std::abs(del) < std::abs(sum) * 1e-15) break;
        }
        return std::max(0.0, 1.0 - sum * std::exp(-x + a * std::log(x) - lg));
    }
    double b = x + 1.0 - a, c = 1.0 / 1e-300, d = 1.0 / b, h = d;
    for (int i = 1; i < 1000; ++i) {
        const double an = -i * (i - a);
        b += 2.0;
        d = an * d + b; if (std::abs(d) < 1e-300) d = 1e-300;
        c = b + an / c; if (std::abs(c) < 1e-300) c = 1e-300;
        d = 1.0 / d;
        const double del = d * c;
        h *= del;
        if (std::abs(del - 1.0) < 1e-15) break;
    }
    return std::exp(-x + a * std::log(x) - lg) * h;
}

double chiSquareSurvival(double x, double k) { return gammaQ(0.5 * k, 0.5 * x); }

void ljungBox(const std::vector<double>& acf, size_t n, int h, double& Q, double& p) {
    Q = 0.0;
    h = std::min<int>(h, static_cast<int>(acf.size()) - 1);
    for (int k = 1; k <= h; ++k)
        if (static_cast<size_t>(k) < n) Q += acf[k] * acf[k] / static_cast<double>(n - k);
    Q *= static_cast<double>(n) * (n + 2.0);
    p = h > 0 ? chiSquareSurvival(Q, h) : 1.0;
}

// Regularised incomplete beta I_x(a, b) (continued fraction, modified Lentz).
static double betaCf(double a, double b, double x) {
    const double tiny = 1e-300;
    double c = 1.0, d = 1.0 - (a + b) * x / (a + 1.0);
    if (std::abs(d) < tiny) d = tiny;
    d = 1.0 / d;
    double h = d;
    for (int m = 1; m < 1000; ++m) {
        const double m2 = 2.0 * m;
        double aa = m * (b - m) * x / ((a - 1.0 + m2) * (a + m2));
        d = 1.0 + aa * d; if (std::abs(d) < tiny) d = tiny;
        c = 1.0 + aa / c; if (std::abs(c) < tiny) c = tiny;
        d = 1.0 / d;
        h *= d * c;
        aa = -(a + m) * (a + b + m) * x / ((a + m2) * (a + 1.0 + m2));
        d = 1.0 + aa * d; if (std::abs(d) < tiny) d = tiny;
        c = 1.0 + aa / c; if (std::abs(c) < tiny) c = tiny;
        d = 1.0 / d;
        const double del = d * c;
        h *= del;
        if (std::abs(del - 1.0) < 1e-15) break;
    }
    return h;
}

static double incompleteBeta(double a, double b, double x) {
    if (x <= 0) return 0.0;
    if (x >= 1) return 1.0;
    const double lbt = std::lgamma(a + b) - std::lgamma(a) - std::lgamma(b) + a * std::log(x) + b * std::log1p(-x);
    if (x < (a + 1.0) / (a + b + 2.0)) return std::exp(lbt) * betaCf(a, b, x) / a;
    return 1.0 - std::exp(lbt) * betaCf(b, a, 1.0 - x) / b;
}

// Regularised lower incomplete gamma P(a, x) (Numerical Recipes 6.2: series, continued fraction).
static double incompleteGammaP(double a, double x) {
    if (!(x > 0.0)) return 0.0;
    const double lead = a * std::log(x) - x - std::lgamma(a);
    if (x < a + 1.0) {
        double ap = a, sum = 1.0 / a, del = sum;
        for (int n = 0; n < 1000 && std::abs(del) > std::abs(sum) * 1e-15; ++n) {
            ap += 1.0;
            del *= x / ap;
            sum += del;
        }
        return std::min(1.0, sum * std::exp(lead));
    }
    const double tiny = 1e-300;
    double b = x + 1.0 - a, c = 1.0 / tiny, d = 1.0 / b, h = d;
    for (int i = 1; i < 1000; ++i) {
        const double an = -i * (i - a);
        b += 2.0;
        d = an * d + b;
        if (std::abs(d) < tiny) d = tiny;
        c = b + an / c;
        if (std::abs(c) < tiny) c = tiny;
        d = 1.0 / d;
        const double del = d * c;
        h *= del;
        if (std::abs(del - 1.0) < 1e-15) break;
    }
    return std::max(0.0, 1.0 - std::exp(lead) * h);
}

double gammaCdf(double x, double shape, double scale) {
    if (!(shape > 0.0 && scale > 0.0)) return std::numeric_limits<double>::quiet_NaN();
    return incompleteGammaP(shape, x / scale);
}

double gammaQuantile(double p, double shape, double scale) {
    if (!(p > 0.0 && p < 1.0 && shape > 0.0 && scale > 0.0)) return std::numeric_limits<double>::quiet_NaN();
    double lo = 0.0, hi = shape * scale;  // the mean; grow until the cdf passes p
    while (gammaCdf(hi, shape, scale) < p) hi *= 2.0;
    for (int i = 0; i < 200 && hi - lo > 1e-14 * hi; ++i) {
        const double mid = 0.5 * (lo + hi);
        (gammaCdf(mid, shape, scale) < p ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
}

double studentTSurvival(double t, double dof) {
    if (!(dof > 0) || std::isnan(t)) return std::numeric_limits<double>::quiet_NaN();
    // P(|T| > |t|) = I_{ν/(ν+t²)}(ν/2, 1/2).
    const double two = incompleteBeta(0.5 * dof, 0.5, dof / (dof + t * t));
    return t >= 0 ? 0.5 * two : 1.0 - 0.5 * two;
}

double studentTQuantile(double p, double dof) {
    if (!(p > 0 && p < 1) || !(dof > 0)) return std::numeric_limits<double>::quiet_NaN();
    if (p < 0.5) return -studentTQuantile(1.0 - p, dof);
    double lo = 0.0, hi = 1.0;
    while (studentTSurvival(hi, dof) > 1.0 - p && hi < 1e12) hi *= 2.0;
    for (int i = 0; i < 200 && hi - lo > 1e-12 * hi; ++i) {
        const double mid = 0.5 * (lo + hi);
        (studentTSurvival(mid, dof) > 1.0 - p ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
}

PairedTest pairedLogRatioTest(const std::vector<double>& before, const std::vector<double>& after) {
    PairedTest r;
    std::vector<double> d;
    for (size_t i = 0; i < before.size() && i < after.size(); ++i)
        if (before[i] > 0 && after[i] > 0 && std::isfinite(before[i]) && std::isfinite(after[i]))
            d.push_back(std::log(before[i] / after[i]));
    r.units = static_cast<int>(d.size());
    if (d.size() < 2) {
        r.t = r.pValue = std::numeric_limits<double>::quiet_NaN();
        if (d.size() == 1) r.meanLogRatio = d[0];
        return r;
    }
    const double k = static_cast<double>(d.size());
    const double mean = std::accumulate(d.begin(), d.end(), 0.0) / k;
    double ss = 0;
    for (double v : d) ss += (v - mean) * (v - mean);
    const double se = std::sqrt(ss / (k - 1.0) / k);
    r.meanLogRatio = mean;
    r.t = se > 0 ? mean / se : (mean > 0 ? std::numeric_limits<double>::infinity()
                                         : mean < 0 ? -std::numeric_limits<double>::infinity() : 0.0);
    r.pValue = std::isinf(r.t) ? (r.t > 0 ? 0.0 : 1.0) : studentTSurvival(r.t, k - 1.0);
    if (d.size() <= 20) {
        const double observed = std::accumulate(d.begin(), d.end(), 0.0);
        const uint32_t patterns = 1u << d.size();
        const double tol = 1e-12 * (std::abs(observed) + 1.0);
        uint32_t above = 0, equal = 0;  // patterns whose sum exceeds / ties the observed one
        for (uint32_t m = 0; m < patterns; ++m) {
            double sum = 0;
            for (size_t i = 0; i < d.size(); ++i) sum += ((m >> i) & 1u) ? -std::abs(d[i]) : std::abs(d[i]);
            if (sum > observed + tol) ++above;
            else if (sum >= observed - tol) ++equal;
        }
        r.exactP = static_cast<double>(above + equal) / static_cast<double>(patterns);
        r.midP = (static_cast<double>(above) + 0.5 * static_cast<double>(equal)) / static_cast<double>(patterns);
    } else {
        r.exactP = r.midP = std::numeric_limits<double>::quiet_NaN();
    }
    return r;
}

double jackknifeStderr(const std::vector<double>& v) {
    if (v.size() < 2) return std::numeric_limits<double>::quiet_NaN();
    const double k = static_cast<double>(v.size());
    const double mean = std::accumulate(v.begin(), v.end(), 0.0) / k;
    double ss = 0;
    for (double x : v) ss += (x - mean) * (x - mean);
    return std::sqrt((k - 1.0) / k * ss);
}

double integratedAcfTime(const std::vector<double>& acf) {
    double tau = 1.0;
    for (size_t k = 1; k < acf.size(); ++k) {
        if (acf[k] < 0.05) break;
        tau += 2.0 * acf[k];
    }
    return tau;
}

Spectrum powerSpectrum(const std::vector<double>& x, double dt, double f0, int maxHarmonics) {
    Spectrum sp;
    const size_t n = x.size();
    if (n < 4 || !(dt > 0)) return sp;
    const double mean = std::accumulate(x.begin(), x.end(), 0.0) / n;
    double* in = fftw_alloc_real(n);
    fftw_complex* out = fftw_alloc_complex(n / 2 + 1);
    fftw_plan plan = fftw_plan_dft_r2c_1d(static_cast<int>(n), in, out, FFTW_ESTIMATE);
    double wsum = 0;
    for (size_t i = 0; i < n; ++i) {
        const double w = 0.5 - 0.5 * std::cos(2.0 * M_PI * i / (n - 1));  // Hann
        in[i] = (x[i] - mean) * w;
        wsum += w * w;
    }
    fftw_execute(plan);
    const double fs = 1.0 / dt;
    for (size_t k = 0; k < n / 2 + 1; ++k) {
        const double p = (out[k][0] * out[k][0] + out[k][1] * out[k][1]) / (fs * wsum) * ((k == 0 || 2 * k == n) ? 1.0 : 2.0);
        sp.frequency_Hz.push_back(k * fs / n);
        sp.power.push_back(p);
    }
    fftw_destroy_plan(plan);
    fftw_free(in);
    fftw_free(out);
    if (f0 > 0) {
        double total = 0, harm = 0;
        const double df = fs / n;
        for (int h = 1; h <= maxHarmonics && h * f0 < fs / 2; ++h) sp.harmonics_Hz.push_back(h * f0);
        for (size_t k = 1; k < sp.power.size(); ++k) {
            total += sp.power[k];
            for (double fh : sp.harmonics_Hz)
                if (std::abs(sp.frequency_Hz[k] - fh) <= 2.0 * df) { harm += sp.power[k]; break; }
        }
        sp.harmonicFraction = total > 0 ? harm / total : 0.0;
    }
    return sp;
}

Diagnostics diagnose(const std::vector<DiagnosticRun>& runs, int decimation, double vStick, StructureCheck structure) {
    Diagnostics d;
    const auto names = candidateSignalNames();
    std::vector<double> res;
    std::vector<std::vector<double>> sig(names.size());
    size_t longest = 0;
    double Qsum = 0;
    int lagsUsed = 0;
    size_t nDec = 0;
    std::vector<double> acfPooled;
    double varSum = 0, diffSum = 0;  // Σ (r − mean)², Σ (r_i − r_{i−1})²/2 over the decimated runs
    double ss = 0;
    size_t count = 0;
    decimation = std::max(decimation, 1);
    for (size_t r = 0; r < runs.size(); ++r) {
        const DiagnosticRun& run = runs[r];
        if (run.residual.size() > runs[longest].residual.size()) longest = r;
        res.insert(res.end(), run.residual.begin(), run.residual.end());
        const auto s = candidateSignals(run, vStick);
        for (size_t j = 0; j < names.size(); ++j) sig[j].insert(sig[j].end(), s[j].begin(), s[j].end());
        for (double v : run.residual) { ss += v * v; ++count; }
        // Whiteness per run on the decimated residual; the Q statistics of independent runs add.
        std::vector<double> dec;
        for (size_t i = 0; i < run.residual.size(); i += decimation) dec.push_back(run.residual[i]);
        if (dec.size() < 30) continue;
        const double mean = std::accumulate(dec.begin(), dec.end(), 0.0) / static_cast<double>(dec.size());
        for (size_t i = 0; i < dec.size(); ++i) {
            varSum += (dec[i] - mean) * (dec[i] - mean);
            if (i > 0) diffSum += 0.5 * (dec[i] - dec[i - 1]) * (dec[i] - dec[i - 1]) * dec.size() / (dec.size() - 1.0);
        }
        const int h = static_cast<int>(std::min<size_t>(20, dec.size() / 5));
        const auto acf = autocorrelation(dec, h);
        double Q = 0, p = 1;
        ljungBox(acf, dec.size(), h, Q, p);
        Qsum += Q;
        lagsUsed += h;
        nDec += dec.size();
        if (acfPooled.empty()) acfPooled.assign(acf.size(), 0.0);
        for (size_t k = 0; k < acf.size() && k < acfPooled.size(); ++k) acfPooled[k] += acf[k] * dec.size();
    }
    d.rms = count ? std::sqrt(ss / count) : 0.0;
    for (size_t j = 0; j < names.size(); ++j) d.correlations.push_back({names[j], pearson(res, sig[j])});
    if (nDec > 0) {
        for (double& v : acfPooled) v /= static_cast<double>(nDec);
        d.whiteness.acf = acfPooled;
        d.whiteness.lags = lagsUsed;
        d.whiteness.decimation = decimation;
        d.whiteness.ljungBoxQ = Qsum;
        d.whiteness.pValue = chiSquareSurvival(Qsum, lagsUsed);
        d.whiteness.white = d.whiteness.pValue >= 0.01;
        d.whiteness.structureRatio = diffSum > 0 ? varSum / diffSum - 1.0 : 0.0;
    }
    if (!runs.empty() && runs[longest].t_s.size() > 4) {
        const DiagnosticRun& run = runs[longest];
        const double dt = (run.t_s.back() - run.t_s.front()) / (run.t_s.size() - 1);
        d.spectrum = powerSpectrum(run.residual, dt, run.forcingFrequency_Hz);
        // τ_int on the undecimated residual of the longest run.
        d.integratedAcfTime = integratedAcfTime(autocorrelation(run.residual, 200));
    }
    if (structure == StructureCheck::Run) d.structure = residualStructure(runs, vStick);
    return d;
}

}  // namespace stickslip::identify
