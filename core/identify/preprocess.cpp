#include "preprocess.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>

namespace stickslip::identify {

namespace {

using cd = std::complex<double>;

// Bilinear transform s -> z = (1 + s/(2fs)) / (1 − s/(2fs)).
cd bilinear(cd s, double fs) { return (1.0 + s / (2.0 * fs)) / (1.0 - s / (2.0 * fs)); }

// Pre-warped analog frequency for a digital frequency f: Ω = 2 fs tan(π f / fs).
double prewarp(double f, double fs) { return 2.0 * fs * std::tan(std::numbers::pi * f / fs); }

// Unit-cutoff Butterworth prototype poles in the upper half plane (and −1 if order is odd):
// p_k = exp(iπ(2k + N + 1)/(2N)), k = 0..N−1, all with Re p < 0.
std::vector<cd> prototypeUpperPoles(int order, bool& hasRealPole) {
    std::vector<cd> out;
    hasRealPole = (order % 2) == 1;
    for (int k = 0; k < order; ++k) {
        const cd p = std::polar(1.0, std::numbers::pi * (2.0 * k + order + 1) / (2.0 * order));
        if (p.imag() > 1e-12) out.push_back(p);
    }
    return out;
}

// Scales b so that the section has unit gain at z = 1 (DC): both our designs pass DC.
Biquad normalizeDC(Biquad q) {
    const double g = (q.b0 + q.b1 + q.b2) / (1.0 + q.a1 + q.a2);
    q.b0 /= g; q.b1 /= g; q.b2 /= g;
    return q;
}

Biquad sectionFromPoles(cd z1, cd z2, double b0, double b1, double b2) {
    // (1 − z1 z⁻¹)(1 − z2 z⁻¹) = 1 − (z1+z2) z⁻¹ + z1 z2 z⁻²; real when z2 = conj(z1) or both real.
    Biquad q;
    q.b0 = b0; q.b1 = b1; q.b2 = b2;
    q.a1 = -(z1 + z2).real();
    q.a2 = (z1 * z2).real();
    return normalizeDC(q);
}

}  // namespace

Sos butterworthLowpass(int order, double fc, double fs) {
    Sos sos;
    if (order < 1 || !(fc > 0.0) || !(fc < fs / 2.0)) return sos;
    const double W = prewarp(fc, fs);
    bool real = false;
    for (const cd& p : prototypeUpperPoles(order, real)) {
        const cd z = bilinear(W * p, fs);
        sos.push_back(sectionFromPoles(z, std::conj(z), 1.0, 2.0, 1.0));  // zeros at z = −1 (s = ∞)
    }
    if (real) {
        const double z = bilinear(cd(-W, 0.0), fs).real();
        Biquad q;
        q.b0 = 1.0; q.b1 = 1.0; q.b2 = 0.0; q.a1 = -z; q.a2 = 0.0;
        sos.push_back(normalizeDC(q));
    }
    return sos;
}

// Low-pass → band-stop: s_lp = B s / (s² + Ω0²), B = Ω2 − Ω1. Each prototype pole
// p maps to the two roots of p s² − B s + p Ω0² = 0, and contributes zeros s = ±iΩ0.
Sos butterworthBandstop(int order, double f1, double f2, double fs) {
    Sos sos;
    if (order < 1 || !(f1 > 0.0) || !(f2 > f1) || !(f2 < fs / 2.0)) return sos;
    // The notch (Ω0) sits exactly at the digital centre frequency; the width B is that of the
    // pre-warped edges, so the −3 dB edges land within a fraction of a hertz of f1 and f2.
    const double W1 = prewarp(f1, fs), W2 = prewarp(f2, fs);
    const double W0 = prewarp(0.5 * (f1 + f2), fs), B = W2 - W1;
    const cd zz = bilinear(cd(0.0, W0), fs);  // digital zero on the unit circle
    const double b1 = -2.0 * zz.real();
    auto roots = [&](cd p) {
        const cd disc = std::sqrt(cd(B * B, 0.0) - 4.0 * p * p * W0 * W0);
        return std::pair<cd, cd>{(B + disc) / (2.0 * p), (B - disc) / (2.0 * p)};
    };
    bool real = false;
    for (const cd& p : prototypeUpperPoles(order, real)) {
        const auto [s1, s2] = roots(p);
        const cd z1 = bilinear(s1, fs), z2 = bilinear(s2, fs);
        sos.push_back(sectionFromPoles(z1, std::conj(z1), 1.0, b1, 1.0));
        sos.push_back(sectionFromPoles(z2, std::conj(z2), 1.0, b1, 1.0));
    }
    if (real) {
        const auto [s1, s2] = roots(cd(-1.0, 0.0));  // conjugate pair, or two real roots
        sos.push_back(sectionFromPoles(bilinear(s1, fs), bilinear(s2, fs), 1.0, b1, 1.0));
    }
    return sos;
}

double sosMagnitude(const Sos& sos, double f, double fs) {
    const cd zi = std::polar(1.0, -2.0 * std::numbers::pi * f / fs);  // z⁻¹
    cd h = 1.0;
    for (const Biquad& q : sos) h *= (q.b0 + q.b1 * zi + q.b2 * zi * zi) / (1.0 + q.a1 * zi + q.a2 * zi * zi);
    return std::abs(h);
}

std::vector<double> sosFilter(const Sos& sos, const std::vector<double>& x) {
    std::vector<double> y = x;
    if (x.empty()) return y;
    for (const Biquad& q : sos) {
        // Transposed direct form II, started in the steady state of a constant input y[0]:
        // out = G in, z1 = out − b0 in, z2 = b2 in − a2 out.
        const double in0 = y[0];
        const double G = (q.b0 + q.b1 + q.b2) / (1.0 + q.a1 + q.a2);
        double z1 = G * in0 - q.b0 * in0, z2 = q.b2 * in0 - q.a2 * G * in0;
        for (double& v : y) {
            const double in = v;
            const double out = q.b0 * in + z1;
            z1 = q.b1 * in - q.a1 * out + z2;
            z2 = q.b2 * in - q.a2 * out;
            v = out;
        }
    }
    return y;
}

namespace {

// The cascade of sosFilter applied in place to x[0..n), forward or backward (backward = sosFilter
// of the reversed sequence, reversed back). Every section sees the same inputs and does the same
// operations as in sosFilter (same numbers), but the sections are advanced together sample by
// sample, so that their recursions overlap in the processor instead of running one after another.
void sosFilterInPlace(const Sos& sos, double* x, size_t n, bool backward) {
    const size_t ns = sos.size();
    if (n == 0 || ns == 0) return;
    std::vector<double> z(2 * ns);  // z1, z2 of every section
    double* const z1 = z.data();
    double* const z2 = z.data() + ns;
    auto run = [&](auto index) {
        // Sample 0: each section starts in the steady state of its own first input.
        double v = x[index(0)];
        for (size_t s = 0; s < ns; ++s) {
            const Biquad& q = sos[s];
            const double in0 = v;
            const double G = (q.b0 + q.b1 + q.b2) / (1.0 + q.a1 + q.a2);
            z1[s] = G * in0 - q.b0 * in0;
            z2[s] = q.b2 * in0 - q.a2 * G * in0;
            const double out = q.b0 * in0 + z1[s];
            z1[s] = q.b1 * in0 - q.a1 * out + z2[s];
            z2[s] = q.b2 * in0 - q.a2 * out;
            v = out;
        }
        x[index(0)] = v;
        for (size_t k = 1; k < n; ++k) {
            double in = x[index(k)];
            for (size_t s = 0; s < ns; ++s) {
                const Biquad& q = sos[s];
                const double out = q.b0 * in + z1[s];
                z1[s] = q.b1 * in - q.a1 * out + z2[s];
                z2[s] = q.b2 * in - q.a2 * out;
                in = out;
            }
            x[index(k)] = in;
        }
    };
    if (backward) run([n](size_t k) { return n - 1 - k; });
    else run([](size_t k) { return k; });
}

size_t reflectionPad(const Sos& sos, size_t n) { return std::min(n - 1, static_cast<size_t>(3 * (2 * sos.size() + 1))); }

// Zero-phase filtering of buf[pad, pad + n) in place, buf having `pad` free samples at each end
// that receive the odd reflections (as scipy.signal.sosfiltfilt).
void filtfiltPadded(const Sos& sos, std::vector<double>& buf, size_t pad, size_t n) {
    const double first = buf[pad], last = buf[pad + n - 1];
    for (size_t i = 1; i <= pad; ++i) {
        buf[pad - i] = 2.0 * first - buf[pad + i];
        buf[pad + n - 1 + i] = 2.0 * last - buf[pad + n - 1 - i];
    }
    sosFilterInPlace(sos, buf.data(), buf.size(), false);
    sosFilterInPlace(sos, buf.data(), buf.size(), true);
}

size_t computeImpulseResponseLength(const Sos& sos, double tolerance) {
    for (size_t n = size_t{1} << 12;; n *= 2) {
        std::vector<double> imp(n, 0.0);
        imp[1] = 1.0;  // imp[0] = 0: sosFilter starts in the steady state of a zero input
        const std::vector<double> h = sosFilter(sos, imp);
        double peak = 0.0;
        for (double v : h) peak = std::max(peak, std::abs(v));
        size_t last = 0;
        for (size_t i = 0; i < h.size(); ++i)
            if (std::abs(h[i]) > tolerance * peak) last = i;
        if (last + 16 < n || n >= (size_t{1} << 20)) return last + 1;
    }
}

bool sameSos(const Sos& a, const Sos& b) {
    if (a.size() != b.size()) return false;
    for (size_t i = 0; i < a.size(); ++i)
        if (a[i].b0 != b[i].b0 || a[i].b1 != b[i].b1 || a[i].b2 != b[i].b2 || a[i].a1 != b[i].a1 || a[i].a2 != b[i].a2)
            return false;
    return true;
}

}  // namespace

std::vector<double> filtfilt(const Sos& sos, const std::vector<double>& x) {
    const size_t n = x.size();
    if (sos.empty() || n < 2) return x;
    // The odd reflection is as long as the filter's memory (impulseResponseLength), not
    // scipy's 3·(2·sections + 1) samples: with the narrow 60 Hz band-stop (≈ 600 samples of
    // memory at 1 kHz) that short pad left an edge transient of several µm on a smooth slip
    // record over the last ≈ 300 samples, which the prescribed-slip law turns into ε_T·Δg of
    // up to 0.8 N in the fit window (ε_T −1 %, tst_fit_prescribed::filteredRunsRecoverTheLaw).
    const size_t pad = std::min(n - 1, std::max(reflectionPad(sos, n), impulseResponseLength(sos)));
    std::vector<double> buf(n + 2 * pad);
    std::copy(x.begin(), x.end(), buf.begin() + static_cast<long>(pad));
    filtfiltPadded(sos, buf, pad, n);
    return std::vector<double>(buf.begin() + static_cast<long>(pad), buf.begin() + static_cast<long>(pad + n));
}

size_t impulseResponseLength(const Sos& sos, double tolerance) {
    if (sos.empty()) return 0;
    // Remembered per thread for the last few filters: predictions ask for the same filter's
    // length at every evaluation of a fit.
    struct Known {
        Sos sos;
        double tolerance;
        size_t length;
    };
    thread_local std::vector<Known> known;
    for (const Known& k : known)
        if (k.tolerance == tolerance && sameSos(k.sos, sos)) return k.length;
    const size_t len = computeImpulseResponseLength(sos, tolerance);
    if (known.size() >= 8) known.erase(known.begin());
    known.push_back(Known{sos, tolerance, len});
    return len;
}

std::vector<double> filtfiltZeroExtended(const Sos& sos, const std::vector<double>& x, size_t margin) {
    if (sos.empty() || x.empty()) return x;
    if (margin == 0) margin = impulseResponseLength(sos);
    // filtfilt of x with `margin` zeros on each side, built in one buffer with filtfilt's padding.
    const size_t n = x.size() + 2 * margin;
    const size_t pad = reflectionPad(sos, n);
    std::vector<double> buf(n + 2 * pad, 0.0);
    std::copy(x.begin(), x.end(), buf.begin() + static_cast<long>(pad + margin));
    filtfiltPadded(sos, buf, pad, n);
    return std::vector<double>(buf.begin() + static_cast<long>(pad + margin), buf.begin() + static_cast<long>(pad + margin + x.size()));
}

std::vector<double> savitzkyGolay(const std::vector<double>& y, double dt, int h, int order, int deriv) {
    const long n = static_cast<long>(y.size());
    std::vector<double> out(y.size(), 0.0);
    if (n == 0) return out;
    h = std::max(0, std::min(h, static_cast<int>((n - 1) / 2)));
    const int w = 2 * h + 1;
    order = std::min(order, w - 1);
    if (deriv > order) return out;  // the polynomial has no such derivative: zero
    // Weights for evaluating derivative `deriv` at position c of the window (c = 0..w−1):
    // the fit coefficients are (AᵀA)⁻¹Aᵀ y with A_jk = (j − c)^k, and the derivative at the
    // evaluation point is deriv! · coefficient[deriv] / dt^deriv.
    double fact = 1.0;
    for (int k = 2; k <= deriv; ++k) fact *= k;
    const double scale = fact / std::pow(dt, deriv);
    std::vector<Eigen::VectorXd> weights(static_cast<size_t>(w));
    for (int c = 0; c < w; ++c) {
        Eigen::MatrixXd A(w, order + 1);
        for (int j = 0; j < w; ++j)
            for (int k = 0; k <= order; ++k) A(j, k) = std::pow(static_cast<double>(j - c), k);
        const Eigen::MatrixXd P = (A.transpose() * A).ldlt().solve(A.transpose());
        weights[static_cast<size_t>(c)] = P.row(deriv).transpose() * scale;
    }
    for (long i = 0; i < n; ++i) {
        const long s = std::clamp(i - h, 0L, n - w);
        const Eigen::VectorXd& wt = weights[static_cast<size_t>(i - s)];
        double acc = 0.0;
        for (int j = 0; j < w; ++j) acc += wt(j) * y[static_cast<size_t>(s + j)];
        out[static_cast<size_t>(i)] = acc;
    }
    return out;
}

static double median(std::vector<double> v) {
    if (v.empty()) return 0.0;
    const size_t mid = v.size() / 2;
    std::nth_element(v.begin(), v.begin() + static_cast<long>(mid), v.end());
    return v[mid];
}

double samplingIrregularity(const std::vector<double>& t) {
    if (t.size() < 3) return 0.0;
    std::vector<double> d(t.size() - 1);
    for (size_t i = 1; i < t.size(); ++i) d[i - 1] = t[i] - t[i - 1];
    const double med = median(d);
    double worst = 0.0;
    for (double x : d) worst = std::max(worst, std::abs(x - med) / med);
    return worst;
}

std::vector<double> resampleLinear(const std::vector<double>& t, const std::vector<double>& y, double t0, double dt, size_t n) {
    std::vector<double> out(n);
    size_t j = 0;
    for (size_t i = 0; i < n; ++i) {
        const double ti = t0 + static_cast<double>(i) * dt;
        while (j + 2 < t.size() && t[j + 1] < ti) ++j;
        const double a = (ti - t[j]) / (t[j + 1] - t[j]);
        out[i] = y[j] + std::clamp(a, 0.0, 1.0) * (y[j + 1] - y[j]);
    }
    return out;
}

double estimatePeriod(const std::vector<double>& t, const std::vector<double>& y) {
    if (y.size() < 4) return 0.0;
    double m = 0, s2 = 0;
    for (double v : y) m += v;
    m /= static_cast<double>(y.size());
    for (double v : y) s2 += (v - m) * (v - m);
    const double th = 0.1 * std::sqrt(s2 / static_cast<double>(y.size()));
    std::vector<double> ups;
    bool armed = false;
    double lastNeg = t[0];
    for (size_t i = 1; i < y.size(); ++i) {
        const double v = y[i] - m, v0 = y[i - 1] - m;
        if (v < -th) armed = true;
        if (v0 <= 0.0 && v > 0.0) lastNeg = t[i - 1] + (t[i] - t[i - 1]) * (-v0) / (v - v0);
        if (armed && v > th) {
            ups.push_back(lastNeg);
            armed = false;
        }
    }
    if (ups.size() < 2) return 0.0;
    std::vector<double> d;
    for (size_t i = 1; i < ups.size(); ++i) d.push_back(ups[i] - ups[i - 1]);
    return median(d);
}

std::pair<size_t, size_t> steadyAmplitudeWindow(const std::vector<double>& y, size_t per, double fraction) {
    const size_t n = y.size();
    if (n == 0 || per < 2) return {0, n};
    std::vector<double> amp(n);
    const size_t half = per / 2;
    for (size_t i = 0; i < n; ++i) {
        const size_t a = i > half ? i - half : 0, b = std::min(n, i + half + 1);
        const auto [lo, hi] = std::minmax_element(y.begin() + static_cast<long>(a), y.begin() + static_cast<long>(b));
        amp[i] = *hi - *lo;
    }
    const double th = fraction * *std::max_element(amp.begin(), amp.end());
    size_t bestB = 0, bestE = n, bestLen = 0;
    for (size_t i = 0; i < n;) {
        if (amp[i] < th) { ++i; continue; }
        size_t j = i;
        while (j < n && amp[j] >= th) ++j;
        if (j - i > bestLen) { bestLen = j - i; bestB = i; bestE = j; }
        i = j;
    }
    return {bestB, bestE};
}

std::vector<double> fourierFit(const std::vector<double>& t, const std::vector<double>& y, double f, int order, size_t b,
                               size_t e, double* rss) {
    const Eigen::Index cols = 1 + 2 * order;
    const double w = 2.0 * std::numbers::pi * f;
    auto basis = [&](double tt, Eigen::Index k) {
        if (k == 0) return 1.0;
        const double h = static_cast<double>((k + 1) / 2);
        return (k % 2) ? std::sin(h * w * tt) : std::cos(h * w * tt);
    };
    Eigen::MatrixXd AtA = Eigen::MatrixXd::Zero(cols, cols);
    Eigen::VectorXd Aty = Eigen::VectorXd::Zero(cols), row(cols);
    for (size_t i = b; i < e; ++i) {
        for (Eigen::Index k = 0; k < cols; ++k) row(k) = basis(t[i], k);
        AtA.noalias() += row * row.transpose();
        Aty += row * y[i];
    }
    const Eigen::VectorXd c = AtA.ldlt().solve(Aty);
    std::vector<double> out(t.size());
    double ss = 0;
    for (size_t i = 0; i < t.size(); ++i) {
        double v = 0;
        for (Eigen::Index k = 0; k < cols; ++k) v += c(k) * basis(t[i], k);
        out[i] = v;
        if (i >= b && i < e) ss += (v - y[i]) * (v - y[i]);
    }
    if (rss) *rss = ss;
    return out;
}

double refineFrequency(const std::vector<double>& t, const std::vector<double>& y, double f0, int order, double span) {
    auto cost = [&](double f) {
        double r = 0;
        fourierFit(t, y, f, order, 0, t.size(), &r);
        return r;
    };
    const double g = (std::sqrt(5.0) - 1.0) / 2.0;
    double a = f0 * (1 - span), b = f0 * (1 + span);
    double c = b - g * (b - a), d = a + g * (b - a);
    double fc = cost(c), fd = cost(d);
    for (int it = 0; it < 40 && (b - a) > 1e-9 * f0; ++it) {
        if (fc < fd) { b = d; d = c; fd = fc; c = b - g * (b - a); fc = cost(c); }
        else { a = c; c = d; fc = fd; d = a + g * (b - a); fd = cost(d); }
    }
    return 0.5 * (a + b);
}

std::vector<std::string> PreprocessSettings::validate(double fs) const {
    std::vector<std::string> v;
    auto num = [](double x) { return std::to_string(x); };
    if (filters.bandStop) {
        const double lo = filters.bandStopCenter_Hz - filters.bandStopWidth_Hz / 2, hi = filters.bandStopCenter_Hz + filters.bandStopWidth_Hz / 2;
        if (!(lo > 0.0)) v.push_back("band-stop: lower edge " + num(lo) + " Hz must be > 0");
        if (!(hi < fs / 2)) v.push_back("band-stop: upper edge " + num(hi) + " Hz must be below Nyquist " + num(fs / 2) + " Hz");
        if (filters.bandStopOrder < 1 || filters.bandStopOrder > 10) v.push_back("band-stop order " + std::to_string(filters.bandStopOrder) + " must be in [1, 10]");
    }
    if (filters.lowPass) {
        if (!(filters.lowPass_Hz > 0.0 && filters.lowPass_Hz < fs / 2))
            v.push_back("low-pass cut-off " + num(filters.lowPass_Hz) + " Hz must be in (0, " + num(fs / 2) + ") Hz");
        if (filters.lowPassOrder < 1 || filters.lowPassOrder > 12) v.push_back("low-pass order " + std::to_string(filters.lowPassOrder) + " must be in [1, 12]");
    }
    if (sgHalfWindow < 1) v.push_back("Savitzky-Golay half window must be >= 1");
    if (sgOrder < 1 || sgOrder > 2 * sgHalfWindow) v.push_back("Savitzky-Golay order must be in [1, 2*halfWindow]");
    if (!(trim.amplitudeFraction > 0.0 && trim.amplitudeFraction <= 1.0)) v.push_back("trim amplitude fraction must be in (0, 1]");
    if (trim.start_s < 0 || trim.end_s < 0) v.push_back("trim times must be >= 0");
    if (stageFourierOrder < 0 || stageFourierOrder > 50) v.push_back("stage Fourier order must be in [0, 50]");
    return v;
}

nlohmann::json toJson(const PreprocessSettings& s) {
    nlohmann::json j;
    j["band_stop"] = {{"on", s.filters.bandStop}, {"center_Hz", s.filters.bandStopCenter_Hz},
                      {"width_Hz", s.filters.bandStopWidth_Hz}, {"order", 2 * s.filters.bandStopOrder},
                      {"zero_phase", true}};
    j["low_pass"] = {{"on", s.filters.lowPass}, {"cutoff_Hz", s.filters.lowPass_Hz}, {"order", s.filters.lowPassOrder},
                     {"zero_phase", true}};
    j["resample_if_irregular"] = s.resample;
    j["savitzky_golay"] = {{"window", 2 * s.sgHalfWindow + 1}, {"order", s.sgOrder}};
    j["stage_fourier_order"] = s.stageFourierOrder;
    j["trim"] = {{"start_s", s.trim.start_s}, {"end_s", s.trim.end_s}, {"steady_amplitude", s.trim.steadyAmplitude},
                 {"amplitude_fraction", s.trim.amplitudeFraction}};
    return j;
}

bool preprocessRun(const io::Run& raw, const PreprocessSettings& s, CleanRun& out, std::string* error) {
    using io::Signal;
    CleanRun c;
    c.run = raw;
    io::Run& r = c.run;
    std::vector<double>& t = r[Signal::Time];
    if (t.size() < 8) {
        if (error) *error = raw.file + ": too few samples";
        return false;
    }
    // 1. uniform step
    {
        std::vector<double> d(t.size() - 1);
        for (size_t i = 1; i < t.size(); ++i) d[i - 1] = t[i] - t[i - 1];
        c.dt_s = median(d);
    }
    const double irr = samplingIrregularity(t);
    if (irr > s.irregularityTolerance) {
        if (!s.resample) {
            if (error) *error = raw.file + ": time step irregular by " + std::to_string(100 * irr) + " % and resampling is off";
            return false;
        }
        const size_t n = static_cast<size_t>(std::floor((t.back() - t.front()) / c.dt_s)) + 1;
        const std::vector<double> told = t;
        for (size_t k = 1; k < io::kSignalCount; ++k)
            if (!r.channels[k].empty()) r.channels[k] = resampleLinear(told, r.channels[k], told.front(), c.dt_s, n);
        t.resize(n);
        for (size_t i = 0; i < n; ++i) t[i] = told.front() + static_cast<double>(i) * c.dt_s;
        c.resampled = true;
        c.notes.push_back("resampled to a uniform step of " + std::to_string(c.dt_s) + " s");
    }
    const double fs = 1.0 / c.dt_s;
    const std::vector<std::string> bad = s.validate(fs);
    if (!bad.empty()) {
        if (error) {
            *error = raw.file + ": ";
            for (size_t i = 0; i < bad.size(); ++i) *error += (i ? "; " : "") + bad[i];
        }
        return false;
    }
    // 2. zero-phase filters on every measured signal
    Sos sos;
    if (s.filters.bandStop) {
        const Sos bs = butterworthBandstop(s.filters.bandStopOrder, s.filters.bandStopCenter_Hz - s.filters.bandStopWidth_Hz / 2,
                                           s.filters.bandStopCenter_Hz + s.filters.bandStopWidth_Hz / 2, fs);
        sos.insert(sos.end(), bs.begin(), bs.end());
    }
    if (s.filters.lowPass) {
        const Sos lp = butterworthLowpass(s.filters.lowPassOrder, s.filters.lowPass_Hz, fs);
        sos.insert(sos.end(), lp.begin(), lp.end());
    }
    if (!sos.empty()) {
        c.unfilteredForce_N = r.has(Signal::Friction) ? r[Signal::Friction] : std::vector<double>{};
        c.unfilteredSlider_m = r.has(Signal::SliderDisp) ? r[Signal::SliderDisp] : std::vector<double>{};
    }
    if (!sos.empty())
        for (size_t k = 1; k < io::kSignalCount; ++k)
            if (!r.channels[k].empty()) r.channels[k] = filtfilt(sos, r.channels[k]);
    // 3. derived signals
    auto sgd = [&](const std::vector<double>& y) { return savitzkyGolay(y, c.dt_s, s.sgHalfWindow, s.sgOrder, 1); };
    if (!r.has(Signal::Slip) && r.has(Signal::StageDisp)) {
        r[Signal::Slip] = r[Signal::StageDisp];
        if (r.has(Signal::SliderDisp)) {
            for (size_t i = 0; i < r[Signal::Slip].size(); ++i) r[Signal::Slip][i] -= r[Signal::SliderDisp][i];
            c.notes.push_back("slip g = stage_disp - slider_disp");
        } else {
            c.notes.push_back("no slider displacement: slider held (Fig. 15a), slip g = stage_disp");
        }
    }
    if (!r.has(Signal::StageVel) && r.has(Signal::StageDisp)) {
        r[Signal::StageVel] = sgd(r[Signal::StageDisp]);
        c.notes.push_back("stage_vel from stage_disp by Savitzky-Golay");
    }
    if (!r.has(Signal::SliderVel) && r.has(Signal::SliderDisp)) {
        r[Signal::SliderVel] = sgd(r[Signal::SliderDisp]);
        c.notes.push_back("slider_vel from slider_disp by Savitzky-Golay");
    }
    if (!r.has(Signal::RelVel)) {
        if (r.has(Signal::StageVel) && r.has(Signal::SliderVel)) {
            r[Signal::RelVel] = r[Signal::StageVel];
            for (size_t i = 0; i < r[Signal::RelVel].size(); ++i) r[Signal::RelVel][i] -= r[Signal::SliderVel][i];
            c.notes.push_back("rel_vel = stage_vel - slider_vel");
        } else if (r.has(Signal::StageVel) && !r.has(Signal::SliderDisp)) {
            r[Signal::RelVel] = r[Signal::StageVel];
            c.notes.push_back("rel_vel = stage_vel (slider held)");
        } else if (r.has(Signal::Slip)) {
            r[Signal::RelVel] = sgd(r[Signal::Slip]);
            c.notes.push_back("rel_vel from slip by Savitzky-Golay");
        }
    }
    // 4. drive period, and the smooth stage input of dynamics runs
    double f = 0.0;
    if (r.setting("f", f) && f > 0.0) c.period_s = 1.0 / f;
    else if (r.has(Signal::StageDisp)) c.period_s = estimatePeriod(t, r[Signal::StageDisp]);
    if (s.stageFourierOrder > 0 && c.period_s > 0.0 && r.has(Signal::SliderDisp) && r.has(Signal::StageDisp)) {
        const double fr = refineFrequency(t, r[Signal::StageDisp], 1.0 / c.period_s, s.stageFourierOrder);
        c.period_s = 1.0 / fr;
        r[Signal::StageDisp] = fourierFit(t, r[Signal::StageDisp], fr, s.stageFourierOrder, 0, t.size());
        if (!raw.has(Signal::StageVel)) r[Signal::StageVel] = sgd(r[Signal::StageDisp]);
        if (r.has(Signal::SliderVel) && !raw.has(Signal::RelVel)) {
            r[Signal::RelVel] = r[Signal::StageVel];
            for (size_t i = 0; i < r[Signal::RelVel].size(); ++i) r[Signal::RelVel][i] -= r[Signal::SliderVel][i];
        }
        r[Signal::Slip] = r[Signal::StageDisp];
        for (size_t i = 0; i < r[Signal::Slip].size(); ++i) r[Signal::Slip][i] -= r[Signal::SliderDisp][i];
        c.notes.push_back("stage_disp replaced by its Fourier fit (" + std::to_string(s.stageFourierOrder) +
                          " harmonics) at the refined drive frequency " + std::to_string(fr) + " Hz");
    }
    // 5. trimming
    const size_t n = t.size();
    size_t b = 0, e = n;
    if (s.trim.steadyAmplitude && c.period_s > 0.0 && r.has(Signal::StageDisp)) {
        const auto w = steadyAmplitudeWindow(r[Signal::StageDisp], static_cast<size_t>(std::lround(c.period_s / c.dt_s)), s.trim.amplitudeFraction);
        b = w.first;
        e = w.second;
    }
    const size_t cutB = static_cast<size_t>(std::lround(s.trim.start_s / c.dt_s));
    const size_t cutE = static_cast<size_t>(std::lround(s.trim.end_s / c.dt_s));
    b = std::max(b, cutB);
    e = std::min(e, n > cutE ? n - cutE : 0);
    // The filters' own start-up: drop ≈ 5 samples per section at each end. With filtfilt's
    // reflection as long as the filter's memory the edge transient is already small; a trim of
    // the band-stop's full settling length (≈ 280 samples) was tried and reverted: it changed
    // the identify loop's spurious frictional_lag on D05 from 1.4 ms (ΔBIC −7, rejected) to
    // 3.8 ms (ΔBIC −25, p 0.048, added), i.e. that candidate's estimate depends on the first
    // and last 0.25 s of the runs (open, docs/identify-results.md).
    const size_t settle = std::min<size_t>(n / 10, 5 * sos.size());
    b = std::max(b, settle);
    e = std::min(e, n - settle);
    if (e <= b + 8) {
        if (error) *error = raw.file + ": nothing left after trimming (window " + std::to_string(b) + ".." + std::to_string(e) + ")";
        return false;
    }
    c.begin = b;
    c.end = e;
    c.filter = sos;
    c.filterSettings = s.filters;
    c.notes.push_back("fit window " + std::to_string(t[b]) + " .. " + std::to_string(t[e - 1]) + " s");
    out = std::move(c);
    return true;
}

}  // namespace stickslip::identify
