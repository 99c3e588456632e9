#include "analyze_run.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "../dsp/stats.hpp"
#include "correlation.hpp"
#include "loop_orientation.hpp"
#include "spectrum.hpp"
#include "zero_one_test.hpp"

namespace stickslip {

namespace {

using nlohmann::json;

const std::vector<double>* col(const io::CsvTable& t, const char* name) {
    const int j = t.column(name);
    return j >= 0 ? &t.columns[static_cast<std::size_t>(j)] : nullptr;
}

// "# k = 8446 N/m" style comment lines (run files written by `simulate`).
bool commentValue(const io::CsvTable& t, const std::string& key, double& v) {
    for (const std::string& c : t.comments) {
        std::istringstream is(c);
        std::string k, eq;
        double x = 0;
        if ((is >> k >> eq >> x) && k == key && eq == "=") { v = x; return true; }
    }
    return false;
}

// Derivative by the centred difference over ±h samples (h = 1: the plain central
// difference; larger h low-passes measurement noise), one-sided at the ends.
std::vector<double> centralDifference(const std::vector<double>& y, double fs, std::size_t h = 1) {
    const std::size_t n = y.size();
    std::vector<double> d(n, 0.0);
    if (n < 2) return d;
    for (std::size_t i = 0; i < n; ++i) {
        const std::size_t a = i >= h ? i - h : 0, b = std::min(n - 1, i + h);
        d[i] = (y[b] - y[a]) * fs / static_cast<double>(b - a);
    }
    return d;
}

// Centred moving average over ±h samples (window shrinks at the ends).
std::vector<double> movingAverage(const std::vector<double>& y, std::size_t h) {
    const std::size_t n = y.size();
    std::vector<double> out(n, 0.0), cum(n + 1, 0.0);
    for (std::size_t i = 0; i < n; ++i) cum[i + 1] = cum[i] + y[i];
    for (std::size_t i = 0; i < n; ++i) {
        const std::size_t a = i >= h ? i - h : 0, b = std::min(n - 1, i + h);
        out[i] = (cum[b + 1] - cum[a]) / static_cast<double>(b - a + 1);
    }
    return out;
}

// Stroboscopic series: y linearly interpolated at t0 + k T.
std::vector<double> stroboscopic(const std::vector<double>& t, const std::vector<double>& y, double T) {
    std::vector<double> out;
    if (t.size() < 2 || !(T > 0)) return out;
    std::size_t j = 0;
    for (double tk = t.front(); tk <= t.back(); tk += T) {
        while (j + 1 < t.size() && t[j + 1] < tk) ++j;
        if (j + 1 >= t.size()) break;
        const double s = (tk - t[j]) / (t[j + 1] - t[j]);
        out.push_back(y[j] + s * (y[j + 1] - y[j]));
    }
    return out;
}

json nullable(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

// The columns the analyses use, and the sampling.
struct RunColumns {
    const io::CsvTable& t;
    const std::vector<double>* time = nullptr;
    const std::vector<double>* stage = nullptr;
    const std::vector<double>* slider = nullptr;
    std::size_t n = 0;
    double fs = 0;
    const std::vector<double>* displacement() const { return slider ? slider : stage; }
    const char* displacementName() const { return slider ? "slider_disp_m" : "stage_disp_m"; }
};

// Forcing frequency: option, '# f = …' line, else the stage spectrum's main peak (0 = unknown).
double forcingFrequency(const RunColumns& c, double option, std::string& source) {
    double f = option;
    source = "option";
    if (!(f > 0) && commentValue(c.t, "f", f)) source = "file";
    if (!(f > 0) && c.stage) {
        // One segment as long as possible: the finest resolution for the frequency estimate.
        WelchOptions w;
        w.segmentLength = 16;
        while (w.segmentLength * 2 <= c.n) w.segmentLength *= 2;
        const PowerSpectrum ps = powerSpectrum(*c.stage, c.fs, w);
        const auto pk = ps.ok ? spectrumPeaks(ps, 1) : std::vector<SpectralPeak>{};
        if (!pk.empty()) { f = pk[0].frequency_Hz; source = "stage spectrum peak"; }
    }
    return f;
}

// Spectrum and autocorrelation of the slider displacement (else the stage).
void addSpectrum(json& j, const RunColumns& c, double f, double maxLag_s) {
    const std::vector<double>* sig = c.displacement();
    if (!sig) return;
    const std::string name = c.displacementName();
    const PowerSpectrum ps = powerSpectrum(*sig, c.fs);
    json s;
    s["signal"] = name;
    if (ps.ok) {
        s["resolution_Hz"] = ps.resolution_Hz;
        s["segments"] = ps.segments;
        json peaks = json::array();
        for (const SpectralPeak& p : spectrumPeaks(ps, 8, 1e-3))
            peaks.push_back({{"frequency_Hz", p.frequency_Hz}, {"psd", p.psd}});
        s["peaks"] = peaks;
        if (f > 0) s["broadband_fraction"] = broadbandFraction(ps, f, 4, 2);
    } else {
        s["error"] = ps.message;
    }
    j["spectrum"] = s;
    const std::size_t maxLag = std::min<std::size_t>(c.n - 1, static_cast<std::size_t>(maxLag_s * c.fs));
    const Correlation ac = autocorrelation(*sig, c.fs, maxLag);
    j["autocorrelation"] = {{"signal", name},
                            {"max_lag_s", static_cast<double>(maxLag) / c.fs},
                            {"decay_level", 0.36787944117144233},
                            {"decay_time_s", nullable(correlationDecayTime(ac))}};
}

// Phase lag between stage and slider.
void addPhaseLag(json& j, const RunColumns& c, double f, double wnOption) {
    if (!(c.stage && c.slider && f > 0)) return;
    double wn = wnOption;
    double k = 0, m = 0;
    if (!(wn > 0) && commentValue(c.t, "k", k) && commentValue(c.t, "m", m) && k > 0 && m > 0) wn = std::sqrt(k / m);
    const PhaseLag lag = stageSliderPhaseLag(*c.stage, *c.slider, c.fs, f, wn > 0 ? wn : 0.0);
    json pl;
    pl["lag_s"] = lag.lag_s;
    pl["fraction_of_period"] = lag.fractionOfPeriod;
    pl["correlation_peak"] = lag.peak;
    pl["natural_frequency_rad_s"] = wn > 0 ? json(wn) : json(nullptr);
    pl["nondimensional"] = wn > 0 ? json(lag.nondimensional) : json(nullptr);
    pl["sign_convention"] = "positive: slider lags the stage";
    j["phase_lag"] = pl;
}

// Relative velocity for the loops; `derived` when differentiated from displacements.
std::vector<double> relativeVelocity(const RunColumns& c, std::size_t h, bool& derived, json& used) {
    std::vector<double> V;
    derived = false;
    if (const auto* v = col(c.t, "rel_vel_mps")) {
        V = *v;
        used["rel_vel"] = "rel_vel_mps";
    } else if (const auto* sv = col(c.t, "stage_vel_mps")) {
        V = *sv;
        if (c.slider) {
            const auto xd = centralDifference(*c.slider, c.fs, h);
            for (std::size_t i = 0; i < c.n; ++i) V[i] -= xd[i];
            derived = true;
            used["rel_vel"] = "stage_vel_mps - d/dt slider_disp_m";
        } else {
            used["rel_vel"] = "stage_vel_mps";
        }
    } else if (c.stage) {
        std::vector<double> g = *c.stage;
        if (c.slider) for (std::size_t i = 0; i < c.n; ++i) g[i] -= (*c.slider)[i];
        V = centralDifference(g, c.fs, h);
        derived = true;
        used["rel_vel"] = c.slider ? "d/dt (stage_disp_m - slider_disp_m)" : "d/dt stage_disp_m";
    }
    return V;
}

// Friction ratio for the loops (or the friction force alone: the orientation does not depend on a positive scale).
std::vector<double> frictionRatio(const RunColumns& c, json& used) {
    std::vector<double> rho;
    if (const auto* r = col(c.t, "friction_ratio")) {
        rho = *r;
        used["friction_ratio"] = "friction_ratio";
    } else if (const auto* F = col(c.t, "friction_force_N")) {
        rho = *F;
        const auto* N = col(c.t, "normal_force_N");
        const char* nName = "normal_force_N";
        if (!N) { N = col(c.t, "band_tension_N"); nName = "band_tension_N"; }
        if (N) {
            for (std::size_t i = 0; i < c.n; ++i) rho[i] = (*N)[i] != 0 ? rho[i] / (*N)[i] : 0.0;
            used["friction_ratio"] = std::string("friction_force_N / ") + nName;
        } else {
            used["friction_ratio"] = "friction_force_N (no normal force column)";
        }
    }
    return rho;
}

// Friction-loop orientation per slip excursion and per forcing cycle. A velocity differentiated
// from measured displacements is noisy: difference over ±h samples, h ≈ 1/40 of a forcing period
// (a low-pass well above the forcing frequency), and average the ratio over the same window.
void addLoops(json& j, const RunColumns& c, double f, json& used) {
    const std::size_t h = f > 0 ? std::max<std::size_t>(1, static_cast<std::size_t>(std::lround(c.fs / (40.0 * f)))) : 1;
    bool derived = false;
    const std::vector<double> V = relativeVelocity(c, h, derived, used);
    std::vector<double> rho = frictionRatio(c, used);
    if (derived && !rho.empty()) {
        rho = movingAverage(rho, h);
        used["smoothing_half_window_samples"] = h;
    }
    if (V.empty() || rho.empty()) return;
    const FrictionLoops fl = frictionLoops(*c.time, V, rho);
    j["loops"] = {{"excursions", fl.signedArea.size()},
                  {"clockwise", fl.clockwise},
                  {"counter_clockwise", fl.counterClockwise},
                  {"degenerate", fl.degenerate},
                  {"definition", "one loop per slip excursion (one sign of V), |V| below 10 % of its peak left out"},
                  {"axes", "relative velocity (x) vs friction ratio (y)"}};
    if (!(f > 0)) return;
    const LoopOrientation lo = frictionLoopOrientation(*c.time, V, rho, 1.0 / f);
    j["cycle_loops"] = {{"cycles", lo.signedArea.size()},
                        {"clockwise", lo.clockwise},
                        {"counter_clockwise", lo.counterClockwise},
                        {"degenerate", lo.degenerate},
                        {"definition", "one closed curve per forcing cycle, elastic reversals included"}};
}

// 0–1 test on the stroboscopic (one per forcing period) slider displacement.
void addZeroOne(json& j, const RunColumns& c, double f) {
    const std::vector<double>* sig = c.displacement();
    if (!sig || !(f > 0)) return;
    const std::vector<double> strobe = stroboscopic(*c.time, *sig, 1.0 / f);
    const ZeroOneResult z = zeroOneTest(strobe);
    json zj;
    zj["series"] = std::string(c.displacementName()) + " once per forcing period";
    zj["samples"] = strobe.size();
    zj["K"] = z.ok ? json(z.K) : json(nullptr);
    if (!z.message.empty()) zj["note"] = z.message;
    j["zero_one_test"] = zj;
}

}  // namespace

bool analyzeRunTable(const io::CsvTable& t, const std::string& path, const AnalyzeSettings& settings,
                     const std::string& program, nlohmann::json& out, std::string* error) {
    auto fail = [&](const std::string& msg) {
        if (error) *error = msg;
        return false;
    };
    RunColumns c{t};
    c.time = col(t, "time_s");
    if (!c.time) return fail(path + ":" + std::to_string(t.headerLine) + ": no 'time_s' column");
    c.n = c.time->size();
    if (c.n < 64) return fail(path + ": " + std::to_string(c.n) + " data rows; need at least 64");
    std::vector<double> dts(c.n - 1);
    for (std::size_t i = 0; i + 1 < c.n; ++i) dts[i] = (*c.time)[i + 1] - (*c.time)[i];
    const double dt = dsp::median(std::move(dts));
    if (!(dt > 0)) return fail(path + ": time_s is not increasing");
    c.fs = 1.0 / dt;
    c.stage = col(t, "stage_disp_m");
    c.slider = col(t, "slider_disp_m");

    json j;
    j["input"] = path;
    j["program"] = program;
    j["rows"] = c.n;
    j["sample_rate_Hz"] = c.fs;
    json used = json::object();
    used["time"] = "time_s";
    std::string fSource;
    const double f = forcingFrequency(c, settings.frequency_Hz, fSource);
    j["forcing_frequency_Hz"] = f > 0 ? json(f) : json(nullptr);
    j["forcing_frequency_source"] = f > 0 ? fSource : "unknown";
    addSpectrum(j, c, f, settings.maxLag_s);
    addPhaseLag(j, c, f, settings.naturalFrequency_rad_s);
    addLoops(j, c, f, used);
    addZeroOne(j, c, f);
    j["columns_used"] = used;
    out = std::move(j);
    return true;
}

}  // namespace stickslip
