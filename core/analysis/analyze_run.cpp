#include "analyze_run.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

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

}  // namespace

bool analyzeRunTable(const io::CsvTable& t, const std::string& path, const AnalyzeSettings& settings,
                     const std::string& program, nlohmann::json& out, std::string* error) {
    auto fail = [&](const std::string& msg) {
        if (error) *error = msg;
        return false;
    };
    const std::vector<double>* time = col(t, "time_s");
    if (!time) {
        return fail(path + ":" + std::to_string(t.headerLine) + ": no 'time_s' column");
    }
    const std::size_t n = time->size();
    if (n < 64) {
        return fail(path + ": " + std::to_string(n) + " data rows; need at least 64");
    }
    std::vector<double> dts(n - 1);
    for (std::size_t i = 0; i + 1 < n; ++i) dts[i] = (*time)[i + 1] - (*time)[i];
    std::nth_element(dts.begin(), dts.begin() + dts.size() / 2, dts.end());
    const double dt = dts[dts.size() / 2];
    if (!(dt > 0)) {
        return fail(path + ": time_s is not increasing");
    }
    const double fs = 1.0 / dt;
    const std::vector<double>* stage = col(t, "stage_disp_m");
    const std::vector<double>* slider = col(t, "slider_disp_m");

    json j;
    j["input"] = path;
    j["program"] = program;
    j["rows"] = n;
    j["sample_rate_Hz"] = fs;
    json used = json::object();
    used["time"] = "time_s";

    // Forcing frequency: option, '# f = …' line, else the stage spectrum's main peak.
    double f = settings.frequency_Hz;
    std::string fSource = "option";
    if (!(f > 0) && commentValue(t, "f", f)) fSource = "file";
    if (!(f > 0) && stage) {
        // One segment as long as possible: the finest resolution for the frequency estimate.
        WelchOptions w;
        w.segmentLength = 16;
        while (w.segmentLength * 2 <= n) w.segmentLength *= 2;
        const PowerSpectrum ps = powerSpectrum(*stage, fs, w);
        const auto pk = ps.ok ? spectrumPeaks(ps, 1) : std::vector<SpectralPeak>{};
        if (!pk.empty()) { f = pk[0].frequency_Hz; fSource = "stage spectrum peak"; }
    }
    j["forcing_frequency_Hz"] = f > 0 ? json(f) : json(nullptr);
    j["forcing_frequency_source"] = f > 0 ? fSource : "unknown";

    // Spectrum and autocorrelation of the slider displacement (else the stage).
    const std::vector<double>* sig = slider ? slider : stage;
    if (sig) {
        const std::string name = slider ? "slider_disp_m" : "stage_disp_m";
        const PowerSpectrum ps = powerSpectrum(*sig, fs);
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
        const std::size_t maxLag = std::min<std::size_t>(n - 1, static_cast<std::size_t>(settings.maxLag_s * fs));
        const Correlation ac = autocorrelation(*sig, fs, maxLag);
        j["autocorrelation"] = {{"signal", name},
                                {"max_lag_s", static_cast<double>(maxLag) / fs},
                                {"decay_level", 0.36787944117144233},
                                {"decay_time_s", nullable(correlationDecayTime(ac))}};
    }

    // Phase lag between stage and slider.
    if (stage && slider && f > 0) {
        double wn = settings.naturalFrequency_rad_s;
        double k = 0, m = 0;
        if (!(wn > 0) && commentValue(t, "k", k) && commentValue(t, "m", m) && k > 0 && m > 0) wn = std::sqrt(k / m);
        const PhaseLag lag = stageSliderPhaseLag(*stage, *slider, fs, f, wn > 0 ? wn : 0.0);
        json pl;
        pl["lag_s"] = lag.lag_s;
        pl["fraction_of_period"] = lag.fractionOfPeriod;
        pl["correlation_peak"] = lag.peak;
        pl["natural_frequency_rad_s"] = wn > 0 ? json(wn) : json(nullptr);
        pl["nondimensional"] = wn > 0 ? json(lag.nondimensional) : json(nullptr);
        pl["sign_convention"] = "positive: slider lags the stage";
        j["phase_lag"] = pl;
    }

    // Relative velocity and friction ratio for the loops. A velocity differentiated from
    // measured displacements is noisy: difference over ±h samples, h ≈ 1/40 of a forcing period
    // (a low-pass well above the forcing frequency), and average the ratio over the same window.
    std::vector<double> V, rho;
    const std::size_t h = f > 0 ? std::max<std::size_t>(1, static_cast<std::size_t>(std::lround(fs / (40.0 * f)))) : 1;
    bool derived = false;
    if (const auto* v = col(t, "rel_vel_mps")) { V = *v; used["rel_vel"] = "rel_vel_mps"; }
    else if (const auto* sv = col(t, "stage_vel_mps")) {
        V = *sv;
        if (slider) {
            const auto xd = centralDifference(*slider, fs, h);
            for (std::size_t i = 0; i < n; ++i) V[i] -= xd[i];
            derived = true;
            used["rel_vel"] = "stage_vel_mps - d/dt slider_disp_m";
        } else {
            used["rel_vel"] = "stage_vel_mps";
        }
    } else if (stage) {
        std::vector<double> g = *stage;
        if (slider) for (std::size_t i = 0; i < n; ++i) g[i] -= (*slider)[i];
        V = centralDifference(g, fs, h);
        derived = true;
        used["rel_vel"] = slider ? "d/dt (stage_disp_m - slider_disp_m)" : "d/dt stage_disp_m";
    }
    if (const auto* r = col(t, "friction_ratio")) { rho = *r; used["friction_ratio"] = "friction_ratio"; }
    else if (const auto* F = col(t, "friction_force_N")) {
        rho = *F;
        const auto* N = col(t, "normal_force_N");
        const char* nName = "normal_force_N";
        if (!N) { N = col(t, "band_tension_N"); nName = "band_tension_N"; }
        if (N) {
            for (std::size_t i = 0; i < n; ++i) rho[i] = (*N)[i] != 0 ? rho[i] / (*N)[i] : 0.0;
            used["friction_ratio"] = std::string("friction_force_N / ") + nName;
        } else {
            used["friction_ratio"] = "friction_force_N (no normal force column)";
        }
    }
    if (derived && !rho.empty()) {
        rho = movingAverage(rho, h);
        used["smoothing_half_window_samples"] = h;
    }
    if (!V.empty() && !rho.empty()) {
        const FrictionLoops fl = frictionLoops(*time, V, rho);
        j["loops"] = {{"excursions", fl.signedArea.size()},
                      {"clockwise", fl.clockwise},
                      {"counter_clockwise", fl.counterClockwise},
                      {"degenerate", fl.degenerate},
                      {"definition", "one loop per slip excursion (one sign of V), |V| below 10 % of its peak left out"},
                      {"axes", "relative velocity (x) vs friction ratio (y)"}};
    }
    if (!V.empty() && !rho.empty() && f > 0) {
        const LoopOrientation lo = frictionLoopOrientation(*time, V, rho, 1.0 / f);
        j["cycle_loops"] = {{"cycles", lo.signedArea.size()},
                            {"clockwise", lo.clockwise},
                            {"counter_clockwise", lo.counterClockwise},
                            {"degenerate", lo.degenerate},
                            {"definition", "one closed curve per forcing cycle, elastic reversals included"}};
    }

    // 0–1 test on the stroboscopic (one per forcing period) slider displacement.
    if (sig && f > 0) {
        const std::vector<double> strobe = stroboscopic(*time, *sig, 1.0 / f);
        const ZeroOneResult z = zeroOneTest(strobe);
        json zj;
        zj["series"] = std::string(slider ? "slider_disp_m" : "stage_disp_m") + " once per forcing period";
        zj["samples"] = strobe.size();
        zj["K"] = z.ok ? json(z.K) : json(nullptr);
        if (!z.message.empty()) zj["note"] = z.message;
        j["zero_one_test"] = zj;
    }
    j["columns_used"] = used;

    out = std::move(j);
    return true;
}

}  // namespace stickslip
