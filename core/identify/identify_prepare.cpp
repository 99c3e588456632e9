// Preparing measured runs for the loop: a cleaned run as an IdentifyRun, and the segment residual's
// starts and smoothed slider state.
#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <thread>

#include "../dsp/fourier.hpp"
#include "../dsp/iir.hpp"
#include "../dsp/savitzky_golay.hpp"
#include "../integrate/dynamics.hpp"
#include "identify_internal.hpp"
#include "preprocess.hpp"

namespace stickslip::identify {

bool makeIdentifyRun(const CleanRun& c, SetupKind setup, IdentifyRun& out, std::string* error) {
    using io::Signal;
    const io::Run& r = c.run;
    auto need = [&](Signal s, const char* what) {
        if (r.has(s)) return true;
        if (error) *error = r.file + ": no " + what + " signal (column " + io::defaultColumn(s) + ")";
        return false;
    };
    if (!need(Signal::Time, "time") || !need(Signal::Friction, "friction force") || !need(Signal::Slip, "slip") ||
        !need(Signal::RelVel, "relative velocity"))
        return false;
    if (setup == SetupKind::Dynamics && !need(Signal::SliderDisp, "slider displacement")) return false;
    const size_t b = std::min(c.begin, r.size()), e = std::min(c.end, r.size());
    if (e < b + 10) {
        if (error) *error = r.file + ": fewer than 10 samples left after trimming";
        return false;
    }
    auto cut = [&](Signal s) {
        if (!r.has(s)) return std::vector<double>{};
        return std::vector<double>(r[s].begin() + b, r[s].begin() + e);
    };
    IdentifyRun o;
    o.file = r.file;
    o.setup = setup;
    o.cutFromRecording = b > 0;
    o.t_s = cut(Signal::Time);
    o.slip_m = cut(Signal::Slip);
    o.relVel_mps = cut(Signal::RelVel);
    o.force_N = cut(Signal::Friction);
    if (setup == SetupKind::Dynamics) {
        o.slider_m = cut(Signal::SliderDisp);
        o.sliderVel_mps = cut(Signal::SliderVel);
        o.accel_mps2 = cut(Signal::SliderAccel);
        if (o.sliderVel_mps.empty() || o.accel_mps2.empty()) {
            // ẋ and ẍ by Savitzky–Golay from x when not measured.
            const auto& x = r[Signal::SliderDisp];
            auto v = dsp::savitzkyGolay(x, c.dt_s, 7, 3, 1), a = dsp::savitzkyGolay(x, c.dt_s, 7, 3, 2);
            if (o.sliderVel_mps.empty()) o.sliderVel_mps.assign(v.begin() + b, v.begin() + e);
            if (o.accel_mps2.empty()) o.accel_mps2.assign(a.begin() + b, a.begin() + e);
        }
    } else {
        auto a = dsp::savitzkyGolay(r[Signal::Slip], c.dt_s, 7, 3, 2);
        o.accel_mps2.assign(a.begin() + b, a.begin() + e);
    }
    o.filtered = !c.filter.empty();
    o.filters = c.filterSettings;
    double v = 0;
    o.normalForce_N = r.setting("tN", v) ? v : 1.0;
    if (r.setting("k", v)) o.stiffness_N_per_m = v;
    if (r.setting("m", v)) o.nominalMass_kg = v;
    if (r.setting("f", v)) o.frequency_Hz = v;
    else if (c.period_s > 0) o.frequency_Hz = 1.0 / c.period_s;
    if (setup == SetupKind::Dynamics && !(o.stiffness_N_per_m > 0)) {
        if (error) *error = r.file + ": dynamics set-up needs the rig stiffness k (manifest or --run-set FILE:k=VALUE)";
        return false;
    }
    out = std::move(o);
    return true;
}

std::function<bool(const io::Run&, IdentifyRun&, std::string&)> recordingPreparer(const PreprocessSettings& pre,
                                                                                  SetupKind setup) {
    return [pre, setup](const io::Run& rec, IdentifyRun& out, std::string& why) {
        CleanRun c;
        return preprocessRun(rec, pre, c, &why) && makeIdentifyRun(c, setup, out, &why);
    };
}

}  // namespace stickslip::identify

namespace stickslip::identify::detail {

// Stage motion u = g + x, cleaned: a least-squares harmonic at the run's forcing frequency
// when it fits to 10 % of its amplitude (the usual drive), else Savitzky–Golay smoothed.
// Slider x and ẋ smoothed over ±7 samples; relative velocity u̇ − ẋ; segments start at the
// largest |u̇ − ẋ| of each half forcing period (mid-slide), end at the next start (≤ 1 period).
void prepareSegments(const IdentifyRun& r, size_t dec, const IdentifyOptions& opt, Prepared& p) {
    const size_t N = r.t_s.size();
    const double dt = (r.t_s.back() - r.t_s.front()) / static_cast<double>(N - 1);
    std::vector<double> u(N);
    for (size_t i = 0; i < N; ++i) u[i] = r.slip_m[i] + r.slider_m[i];
    if (r.frequency_Hz > 0) {
        const dsp::HarmonicFit fit = dsp::harmonicFit(r.t_s, u, r.frequency_Hz, 1, 0, N);
        const double amp = fit.amplitude(1);
        if (amp > 0 && std::sqrt(fit.rss / N) < 0.1 * amp) {
            p.stageHarmonic = true;
            p.uc0 = fit.mean; p.ua = fit.cosine[0]; p.ub = fit.sine[0]; p.omega = fit.omega;
        }
    }
    const std::vector<double> us = dsp::savitzkyGolay(u, dt, 7, 3, 0), usd = dsp::savitzkyGolay(u, dt, 7, 3, 1);
    const std::vector<double> xs = dsp::savitzkyGolay(r.slider_m, dt, 7, 3, 0), vs = dsp::savitzkyGolay(r.slider_m, dt, 7, 3, 1);
    double cum = 0, ssx = 0;
    for (size_t i = 0; i < N; ++i) {
        if (i > 0) cum += std::abs(r.slip_m[i] - r.slip_m[i - 1]);
        ssx += r.slider_m[i] * r.slider_m[i];
        if (i % dec) continue;
        const double tt = r.t_s[i];
        p.u.push_back(p.stageHarmonic ? p.stageAt(tt) : us[i]);
        const double uDot = p.stageHarmonic ? p.omega * (-p.ua * std::sin(p.omega * tt) + p.ub * std::cos(p.omega * tt)) : usd[i];
        p.xs.push_back(xs[i]);
        p.vs.push_back(vs[i]);
        p.Vs.push_back(uDot - vs[i]);
        p.cumSlip.push_back(cum);
    }
    p.invRmsX = ssx > 0 ? 1.0 / std::sqrt(ssx / N) : 1.0;
    const size_t n = p.size();
    if (n < 4) return;
    const double half = r.frequency_Hz > 0 ? 0.5 / r.frequency_Hz : 0.1;
    const double dts = p.t[1] - p.t[0];
    std::vector<size_t> starts;
    for (size_t i = 0; i < n;) {
        size_t j = i, bi = n;
        double best = 0;
        for (; j < n && p.t[j] < p.t[i] + half; ++j)
            if (std::abs(p.Vs[j]) > best) { best = std::abs(p.Vs[j]); bi = j; }
        if (bi < n && best >= 2.0 * opt.stickVelocity_mps) starts.push_back(bi);
        i = std::max(j, i + 1);
    }
    const size_t maxLen = static_cast<size_t>(std::ceil(2.0 * half / dts));
    std::vector<std::pair<size_t, size_t>> segs;
    for (size_t k = 0; k < starts.size(); ++k) {
        const size_t i0 = starts[k];
        size_t i1 = k + 1 < starts.size() ? starts[k + 1] : n - 1;
        i1 = std::min(i1, i0 + maxLen);
        if (i1 > i0 + 1) segs.push_back({i0, i1});
    }
    const size_t maxSeg = static_cast<size_t>(std::max(opt.maxSegmentsPerRun, 1));
    if (segs.size() > maxSeg) {
        std::vector<std::pair<size_t, size_t>> kept;
        for (size_t q = 0; q < maxSeg; ++q) kept.push_back(segs[(q * segs.size()) / maxSeg]);
        segs = std::move(kept);
    }
    p.segments = std::move(segs);
}

// The cleaning filters redesigned at the decimated rate fs; one whose band reaches 0.45 fs is
// left out (the decimated samples cannot carry its effect).
dsp::Sos predictionFilterAt(const FilterSettings& fs, double rate_Hz) {
    dsp::Sos out;
    const double ny = 0.45 * rate_Hz;
    if (fs.bandStop && fs.bandStopCenter_Hz + 0.5 * fs.bandStopWidth_Hz < ny) {
        const dsp::Sos bs = dsp::butterworthBandstop(fs.bandStopOrder, fs.bandStopCenter_Hz - 0.5 * fs.bandStopWidth_Hz,
                                           fs.bandStopCenter_Hz + 0.5 * fs.bandStopWidth_Hz, rate_Hz);
        out.insert(out.end(), bs.begin(), bs.end());
    }
    if (fs.lowPass && fs.lowPass_Hz < ny) {
        const dsp::Sos lp = dsp::butterworthLowpass(fs.lowPassOrder, fs.lowPass_Hz, rate_Hz);
        out.insert(out.end(), lp.begin(), lp.end());
    }
    return out;
}

void prepareStepSlip(const IdentifyRun& r, size_t dec, int substeps, Prepared& p) {
    p.stepSlip.clear();
    if (dec <= 1 || substeps < 1 || p.size() < 2) return;
    const size_t S = static_cast<size_t>(substeps);
    p.stepSlip.reserve((p.size() - 1) * S);
    for (size_t i = 1; i < p.size(); ++i) {
        const size_t j0 = (i - 1) * dec;  // recorded index of decimated sample i − 1
        for (size_t k = 1; k <= S; ++k) {
            if (k == S) { p.stepSlip.push_back(p.g[i]); continue; }
            const double q = static_cast<double>(k * dec) / static_cast<double>(S);  // recorded intervals from j0
            const size_t j = std::min(j0 + static_cast<size_t>(q), r.slip_m.size() - 2);
            const double w = q - static_cast<double>(j - j0);
            p.stepSlip.push_back(r.slip_m[j] + w * (r.slip_m[j + 1] - r.slip_m[j]));
        }
    }
}

// The dynamics law channel's masks (Prepared::slides, Prepared::compared): the filtered prediction
// is the measurement outside `slides`, so within the filter's memory of a mask edge it mixes the
// two; there it is not the model's, and `compared` leaves it out (IdentifyOptions::maskEdgeGuard).
void prepareLawMasks(double vStick, Prepared& p) {
    const size_t n = p.size();
    p.slides.assign(n, 0);
    for (size_t i = 0; i < n; ++i) p.slides[i] = std::abs(p.V[i]) >= vStick;
    p.compared = p.slides;
    const long g = static_cast<long>(p.edgeGuard), nn = static_cast<long>(n);
    if (g <= 0) return;
    for (long i = 0; i < nn; ++i)
        if (!p.slides[static_cast<size_t>(i)])
            for (long j = std::max(0L, i - g); j <= std::min(nn - 1, i + g); ++j) p.compared[static_cast<size_t>(j)] = 0;
}

// Checks the runs, sets their accumulated slip, chooses the decimation and prepares every run
// (decimated signals, weights, prediction filter, segments). False with `why` on bad input.
bool prepareContext(std::vector<IdentifyRun>& runs, const IdentifyOptions& opt, Context& cx, int& decimation,
                    std::string& why) {
    cx.opt = &opt;
    // Slip accumulated before each run, in the order given (runs recorded on one specimen).
    double slip = 0, tNsum = 0;
    for (IdentifyRun& r : runs) {
        if (r.t_s.size() < 10 || r.force_N.size() != r.t_s.size() || r.slip_m.size() != r.t_s.size() ||
            r.relVel_mps.size() != r.t_s.size()) {
            why = r.file + ": run needs >= 10 samples of time, slip, velocity and force of equal length";
            return false;
        }
        if (r.setup == SetupKind::Dynamics &&
            (r.slider_m.size() != r.t_s.size() || r.sliderVel_mps.size() != r.t_s.size() || r.accel_mps2.size() != r.t_s.size())) {
            why = r.file + ": dynamics run needs slider displacement, velocity and acceleration";
            return false;
        }
        r.slipBefore_m = slip;
        for (size_t i = 1; i < r.slip_m.size(); ++i) slip += std::abs(r.slip_m[i] - r.slip_m[i - 1]);
        tNsum += r.normalForce_N;
        if (r.setup == SetupKind::Dynamics) cx.anyDynamics = true;
    }
    cx.tNref = tNsum / runs.size();
    size_t dec = static_cast<size_t>(std::max(opt.decimate, 0));
    if (dec == 0) {
        const IdentifyRun& r0 = runs.front();
        const double fs = 1.0 / ((r0.t_s.back() - r0.t_s.front()) / (r0.t_s.size() - 1));
        double fmax = 0;
        for (const IdentifyRun& r : runs) fmax = std::max(fmax, r.frequency_Hz);
        // Dynamics: 500 Hz, so that the cleaning filters (60 Hz band-stop, 100 Hz low-pass) can
        // be applied to the prediction well below the decimated Nyquist frequency and the law's
        // steps resolve slip onsets: at 250 Hz the error of the prediction's own resolution was
        // systematic enough for a sensor mass of 5.7 g to absorb it on D05 (gain 0.50 against
        // 0.004 of the noise null; at 500 Hz the gain is gone, ΔBIC +4.6).
        const double target = cx.anyDynamics ? 500.0 : 128.0 * (fmax > 0 ? fmax : 1.0);
        dec = static_cast<size_t>(std::max(1.0, std::floor(fs / target)));
    }
    decimation = static_cast<int>(dec);
    for (const IdentifyRun& r : runs) {
        Prepared p;
        p.run = &r;
        p.dec = dec;
        double ss = 0;
        for (double f : r.force_N) ss += f * f;
        p.invRmsF = ss > 0 ? 1.0 / std::sqrt(ss / r.force_N.size()) : 1.0;
        for (size_t i = 0; i < r.t_s.size(); i += dec) {
            p.t.push_back(r.t_s[i]);
            p.g.push_back(r.slip_m[i]);
            p.V.push_back(r.relVel_mps[i]);
            p.F.push_back(r.force_N[i]);
            if (!r.accel_mps2.empty()) p.a.push_back(r.accel_mps2[i]);
            if (r.setup == SetupKind::Dynamics) {
                p.x.push_back(r.slider_m[i]);
                p.xd.push_back(r.sliderVel_mps[i]);
            }
        }
        // Prescribed runs only. Their law channel compares every sample, dwells included, where the
        // line's corner cut changes the stick force through ε_T. In the spring–mass set-up the law
        // channel compares sliding samples only and g = u − x carries two sensors' noise; driven
        // through it there, D09's lag lost its held-out test (p 0.0625, session 20) and session 19
        // saw D13 gain a false sensor mass (docs/identify-results.md).
        if (opt.recordedStepSlip && r.setup == SetupKind::Prescribed) prepareStepSlip(r, dec, opt.substeps, p);
        if (r.filtered && p.size() > 16) p.predictionFilter = predictionFilterAt(r.filters, 1.0 / (p.t[1] - p.t[0]));
        if (opt.maskEdgeGuard && !p.predictionFilter.empty()) {
            const double gd = dsp::groupDelayAtDc(p.predictionFilter);
            p.edgeGuard = std::isfinite(gd) && gd > 0 ? static_cast<size_t>(std::ceil(gd)) : 0;
        }
        if (r.setup == SetupKind::Dynamics) {
            prepareLawMasks(opt.stickVelocity_mps, p);
            prepareSegments(r, dec, opt, p);
        }
        cx.runs.push_back(std::move(p));
    }
    return true;
}

}  // namespace stickslip::identify::detail
