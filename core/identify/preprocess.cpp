#include "preprocess.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "../dsp/fourier.hpp"
#include "../dsp/kinematic_smoother.hpp"
#include "../dsp/sampling.hpp"
#include "../dsp/savitzky_golay.hpp"
#include "../dsp/stats.hpp"

namespace stickslip::identify {

ParamIssues PreprocessSettings::validate(double fs) const {
    ParamIssues v;
    auto add = [&](const char* field, std::string text) { v.push_back(ParamIssue::note(field, std::move(text))); };
    auto num = [](double x) { return std::to_string(x); };
    if (filters.bandStop) {
        const double lo = filters.bandStopCenter_Hz - filters.bandStopWidth_Hz / 2, hi = filters.bandStopCenter_Hz + filters.bandStopWidth_Hz / 2;
        if (!(lo > 0.0)) add("band_stop", "band-stop: lower edge " + num(lo) + " Hz must be > 0");
        if (!(hi < fs / 2)) add("band_stop", "band-stop: upper edge " + num(hi) + " Hz must be below Nyquist " + num(fs / 2) + " Hz");
        if (filters.bandStopOrder < 1 || filters.bandStopOrder > 10) add("band_stop_order", "band-stop order " + std::to_string(filters.bandStopOrder) + " must be in [1, 10]");
    }
    if (filters.lowPass) {
        if (!(filters.lowPass_Hz > 0.0 && filters.lowPass_Hz < fs / 2))
            add("low_pass", "low-pass cut-off " + num(filters.lowPass_Hz) + " Hz must be in (0, " + num(fs / 2) + ") Hz");
        if (filters.lowPassOrder < 1 || filters.lowPassOrder > 12) add("low_pass_order", "low-pass order " + std::to_string(filters.lowPassOrder) + " must be in [1, 12]");
    }
    if (sgHalfWindow < 1) add("sg_half_window", "Savitzky-Golay half window must be >= 1");
    if (sgOrder < 1 || sgOrder > 2 * sgHalfWindow) add("sg_order", "Savitzky-Golay order must be in [1, 2*halfWindow]");
    if (!(trim.amplitudeFraction > 0.0 && trim.amplitudeFraction <= 1.0)) add("trim_amplitude", "trim amplitude fraction must be in (0, 1]");
    if (trim.start_s < 0 || trim.end_s < 0) add("trim", "trim times must be >= 0");
    if (stageFourierOrder < 0 || stageFourierOrder > 50) add("stage_fourier_order", "stage Fourier order must be in [0, 50]");
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
    j["fuse_slider_acceleration"] = s.fuseSliderAcceleration;
    j["trim"] = {{"start_s", s.trim.start_s}, {"end_s", s.trim.end_s}, {"steady_amplitude", s.trim.steadyAmplitude},
                 {"amplitude_fraction", s.trim.amplitudeFraction}};
    return j;
}

namespace {

using io::Signal;

// Step 1: the median sampling step, and resampling to it when the time column is irregular.
bool makeUniform(const io::Run& raw, const PreprocessSettings& s, CleanRun& c, std::string* error) {
    io::Run& r = c.run;
    std::vector<double>& t = r[Signal::Time];
    {
        std::vector<double> d(t.size() - 1);
        for (size_t i = 1; i < t.size(); ++i) d[i - 1] = t[i] - t[i - 1];
        c.dt_s = dsp::median(std::move(d));
    }
    const double irr = dsp::samplingIrregularity(t);
    if (!(irr > s.irregularityTolerance)) return true;  // NaN (a broken time column): as before, no resampling
    if (!s.resample) {
        if (error) *error = raw.file + ": time step irregular by " + std::to_string(100 * irr) + " % and resampling is off";
        return false;
    }
    const size_t n = static_cast<size_t>(std::floor((t.back() - t.front()) / c.dt_s)) + 1;
    const std::vector<double> told = t;
    for (size_t k = 1; k < io::kSignalCount; ++k)
        if (!r.channels[k].empty()) r.channels[k] = dsp::resampleLinear(told, r.channels[k], told.front(), c.dt_s, n);
    t.resize(n);
    for (size_t i = 0; i < n; ++i) t[i] = told.front() + static_cast<double>(i) * c.dt_s;
    c.resampled = true;
    c.notes.push_back("resampled to a uniform step of " + std::to_string(c.dt_s) + " s");
    return true;
}

// Step 1b (opt-in): slider displacement and velocity from the raw displacement and
// acceleration, before the filters colour their noise (its level is estimated on them).
void fuseSliderKinematics(CleanRun& c) {
    io::Run& r = c.run;
    if (!r.has(Signal::SliderDisp) || !r.has(Signal::SliderAccel)) {
        c.notes.push_back("slider acceleration fusion skipped: needs slider_disp and slider_accel");
        return;
    }
    const dsp::KinematicEstimate k = dsp::smoothKinematics(r[Signal::SliderDisp], r[Signal::SliderAccel], c.dt_s);
    if (!k.ok) {
        c.notes.push_back("slider acceleration fusion skipped: " + k.message);
        return;
    }
    const bool velMeasured = r.has(Signal::SliderVel);
    r[Signal::SliderDisp] = k.x;
    if (!velMeasured) r[Signal::SliderVel] = k.v;
    char buf[200];
    std::snprintf(buf, sizeof buf, "slider_disp%s from slider_disp and slider_accel (RTS smoother; noise %.3g m, %.3g m/s^2; offset %.3g m/s^2)",
                  velMeasured ? "" : " and slider_vel", k.dispNoise, k.accelNoise, k.accelOffset);
    c.notes.push_back(buf);
}

// Step 2: the band-stop then low-pass cascade at rate fs (empty when both are off).
dsp::Sos designFilter(const FilterSettings& f, double fs) {
    dsp::Sos sos;
    if (f.bandStop) {
        const dsp::Sos bs = dsp::butterworthBandstop(f.bandStopOrder, f.bandStopCenter_Hz - f.bandStopWidth_Hz / 2,
                                                     f.bandStopCenter_Hz + f.bandStopWidth_Hz / 2, fs);
        sos.insert(sos.end(), bs.begin(), bs.end());
    }
    if (f.lowPass) {
        const dsp::Sos lp = dsp::butterworthLowpass(f.lowPassOrder, f.lowPass_Hz, fs);
        sos.insert(sos.end(), lp.begin(), lp.end());
    }
    return sos;
}

void subtractInto(std::vector<double>& out, const std::vector<double>& a, const std::vector<double>& b) {
    out = a;
    for (size_t i = 0; i < out.size(); ++i) out[i] -= b[i];
}

// Step 3: slip and the velocities that were not measured, from the filtered displacements.
void deriveSignals(CleanRun& c, const PreprocessSettings& s) {
    io::Run& r = c.run;
    auto sgd = [&](const std::vector<double>& y) { return dsp::savitzkyGolay(y, c.dt_s, s.sgHalfWindow, s.sgOrder, 1); };
    if (!r.has(Signal::Slip) && r.has(Signal::StageDisp)) {
        if (r.has(Signal::SliderDisp)) {
            subtractInto(r[Signal::Slip], r[Signal::StageDisp], r[Signal::SliderDisp]);
            c.notes.push_back("slip g = stage_disp - slider_disp");
        } else {
            r[Signal::Slip] = r[Signal::StageDisp];
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
    if (r.has(Signal::RelVel)) return;
    if (r.has(Signal::StageVel) && r.has(Signal::SliderVel)) {
        subtractInto(r[Signal::RelVel], r[Signal::StageVel], r[Signal::SliderVel]);
        c.notes.push_back("rel_vel = stage_vel - slider_vel");
    } else if (r.has(Signal::StageVel) && !r.has(Signal::SliderDisp)) {
        r[Signal::RelVel] = r[Signal::StageVel];
        c.notes.push_back("rel_vel = stage_vel (slider held)");
    } else if (r.has(Signal::Slip)) {
        r[Signal::RelVel] = sgd(r[Signal::Slip]);
        c.notes.push_back("rel_vel from slip by Savitzky-Golay");
    }
}

// Step 4: the drive period, and for dynamics runs the stage displacement replaced by its
// Fourier fit at the refined drive frequency (with the signals derived from it).
void driveAndSmoothStage(const io::Run& raw, CleanRun& c, const PreprocessSettings& s) {
    io::Run& r = c.run;
    const std::vector<double>& t = r[Signal::Time];
    double f = 0.0;
    if (r.setting("f", f) && f > 0.0) c.period_s = 1.0 / f;
    else if (r.has(Signal::StageDisp)) c.period_s = dsp::estimatePeriod(t, r[Signal::StageDisp]);
    if (!(s.stageFourierOrder > 0 && c.period_s > 0.0 && r.has(Signal::SliderDisp) && r.has(Signal::StageDisp))) return;
    const double fr = dsp::refineFrequency(t, r[Signal::StageDisp], 1.0 / c.period_s, s.stageFourierOrder);
    c.period_s = 1.0 / fr;
    r[Signal::StageDisp] = dsp::fourierFit(t, r[Signal::StageDisp], fr, s.stageFourierOrder, 0, t.size());
    if (!raw.has(Signal::StageVel))
        r[Signal::StageVel] = dsp::savitzkyGolay(r[Signal::StageDisp], c.dt_s, s.sgHalfWindow, s.sgOrder, 1);
    if (r.has(Signal::SliderVel) && !raw.has(Signal::RelVel))
        subtractInto(r[Signal::RelVel], r[Signal::StageVel], r[Signal::SliderVel]);
    subtractInto(r[Signal::Slip], r[Signal::StageDisp], r[Signal::SliderDisp]);
    c.notes.push_back("stage_disp replaced by its Fourier fit (" + std::to_string(s.stageFourierOrder) +
                      " harmonics) at the refined drive frequency " + std::to_string(fr) + " Hz");
}

// Step 5: the fit window [begin, end): steady drive amplitude, the requested cuts, and the
// filters' start-up at both ends.
bool trimWindow(const io::Run& raw, CleanRun& c, const PreprocessSettings& s, size_t sections, std::string* error) {
    const io::Run& r = c.run;
    const std::vector<double>& t = r[Signal::Time];
    const size_t n = t.size();
    size_t b = 0, e = n;
    if (s.trim.steadyAmplitude && c.period_s > 0.0 && r.has(Signal::StageDisp)) {
        const auto w = dsp::steadyAmplitudeWindow(r[Signal::StageDisp], static_cast<size_t>(std::lround(c.period_s / c.dt_s)), s.trim.amplitudeFraction);
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
    const size_t settle = std::min<size_t>(n / 10, 5 * sections);
    b = std::max(b, settle);
    e = std::min(e, n - settle);
    if (e <= b + 8) {
        if (error) *error = raw.file + ": nothing left after trimming (window " + std::to_string(b) + ".." + std::to_string(e) + ")";
        return false;
    }
    c.begin = b;
    c.end = e;
    c.notes.push_back("fit window " + std::to_string(t[b]) + " .. " + std::to_string(t[e - 1]) + " s");
    return true;
}

}  // namespace

bool preprocessRun(const io::Run& raw, const PreprocessSettings& s, CleanRun& out, std::string* error) {
    CleanRun c;
    c.run = raw;
    io::Run& r = c.run;
    if (r[Signal::Time].size() < 8) {
        if (error) *error = raw.file + ": too few samples";
        return false;
    }
    if (!makeUniform(raw, s, c, error)) return false;
    const double fs = 1.0 / c.dt_s;
    const ParamIssues bad = s.validate(fs);
    if (!bad.empty()) {
        if (error) {
            *error = raw.file + ": ";
            for (size_t i = 0; i < bad.size(); ++i) *error += (i ? "; " : "") + bad[i].message();
        }
        return false;
    }
    if (s.fuseSliderAcceleration) fuseSliderKinematics(c);
    // Zero-phase filters on every measured signal; the force and slider displacement are kept
    // unfiltered as well (CleanRun::unfilteredForce_N).
    const dsp::Sos sos = designFilter(s.filters, fs);
    if (!sos.empty()) {
        c.unfilteredForce_N = r.has(Signal::Friction) ? r[Signal::Friction] : std::vector<double>{};
        c.unfilteredSlider_m = r.has(Signal::SliderDisp) ? r[Signal::SliderDisp] : std::vector<double>{};
        for (size_t k = 1; k < io::kSignalCount; ++k)
            if (!r.channels[k].empty()) r.channels[k] = dsp::filtfilt(sos, r.channels[k]);
    }
    deriveSignals(c, s);
    driveAndSmoothStage(raw, c, s);
    if (!trimWindow(raw, c, s, sos.size(), error)) return false;
    c.filter = sos;
    c.filterSettings = s.filters;
    out = std::move(c);
    return true;
}

}  // namespace stickslip::identify
