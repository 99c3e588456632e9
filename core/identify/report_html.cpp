#include "report_html.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "fit_internal.hpp"

namespace stickslip::identify {

std::string htmlEscape(const std::string& s) {
    std::string o;
    for (char c : s) {
        switch (c) {
            case '&': o += "&amp;"; break;
            case '<': o += "&lt;"; break;
            case '>': o += "&gt;"; break;
            case '"': o += "&quot;"; break;
            default: o += c;
        }
    }
    return o;
}

namespace {

// The message formatter, with a dash for a number that is not there.
std::string fmt(double v, const char* f = "%.4g") { return std::isfinite(v) ? detail::fmt(v, f) : "&ndash;"; }

// 1–2–5 tick step covering `span` in about n ticks.
double niceStep(double span, int n) {
    const double raw = span / std::max(n, 1);
    const double p = std::pow(10.0, std::floor(std::log10(raw)));
    const double m = raw / p;
    return (m < 1.5 ? 1 : m < 3.5 ? 2 : m < 7.5 ? 5 : 10) * p;
}

}  // namespace

std::string svgLinePlot(const std::vector<SvgSeries>& series, const std::string& title, const std::string& xLabel,
                        const std::string& yLabel, int W, int H) {
    double x0 = INFINITY, x1 = -INFINITY, y0 = INFINITY, y1 = -INFINITY;
    for (const SvgSeries& s : series)
        for (size_t i = 0; i < s.x.size() && i < s.y.size(); ++i) {
            if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i])) continue;
            x0 = std::min(x0, s.x[i]); x1 = std::max(x1, s.x[i]);
            y0 = std::min(y0, s.y[i]); y1 = std::max(y1, s.y[i]);
        }
    // No finite point: the unit frame. One value of x (or of y) only: a frame of width 2
    // centred on it, so that the points are drawn in its middle.
    if (!std::isfinite(x0)) { x0 = 0; x1 = 1; } else if (!(x1 > x0)) { x0 -= 1; x1 += 1; }
    if (!std::isfinite(y0)) { y0 = 0; y1 = 1; } else if (!(y1 > y0)) { y0 -= 1; y1 += 1; }
    const double pad = 0.05 * (y1 - y0);
    y0 -= pad; y1 += pad;
    const int L = 70, R = 15, T = 28, B = 42;
    const double pw = W - L - R, ph = H - T - B;
    auto X = [&](double v) { return L + (v - x0) / (x1 - x0) * pw; };
    auto Y = [&](double v) { return T + (y1 - v) / (y1 - y0) * ph; };
    std::ostringstream o;
    o << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << W << "\" height=\"" << H << "\" viewBox=\"0 0 " << W << " "
      << H << "\" font-family=\"sans-serif\" font-size=\"11\">\n";
    o << "<rect x=\"" << L << "\" y=\"" << T << "\" width=\"" << pw << "\" height=\"" << ph
      << "\" fill=\"#fff\" stroke=\"#888\"/>\n";
    o << "<text x=\"" << W / 2 << "\" y=\"16\" text-anchor=\"middle\" font-size=\"13\">" << htmlEscape(title) << "</text>\n";
    const double sx = niceStep(x1 - x0, 6), sy = niceStep(y1 - y0, 5);
    for (double v = std::ceil(x0 / sx) * sx; v <= x1 + 1e-12 * sx; v += sx)
        o << "<line x1=\"" << X(v) << "\" x2=\"" << X(v) << "\" y1=\"" << T << "\" y2=\"" << T + ph
          << "\" stroke=\"#eee\"/><text x=\"" << X(v) << "\" y=\"" << T + ph + 14 << "\" text-anchor=\"middle\">" << fmt(v, "%.3g")
          << "</text>\n";
    for (double v = std::ceil(y0 / sy) * sy; v <= y1 + 1e-12 * sy; v += sy)
        o << "<line x1=\"" << L << "\" x2=\"" << L + pw << "\" y1=\"" << Y(v) << "\" y2=\"" << Y(v)
          << "\" stroke=\"#eee\"/><text x=\"" << L - 4 << "\" y=\"" << Y(v) + 4 << "\" text-anchor=\"end\">" << fmt(v, "%.3g")
          << "</text>\n";
    o << "<text x=\"" << L + pw / 2 << "\" y=\"" << H - 6 << "\" text-anchor=\"middle\">" << htmlEscape(xLabel) << "</text>\n";
    o << "<text transform=\"translate(14," << T + ph / 2 << ") rotate(-90)\" text-anchor=\"middle\">" << htmlEscape(yLabel)
      << "</text>\n";
    int li = 0;
    for (const SvgSeries& s : series) {
        std::string d;
        bool pen = false;
        char b[64];
        for (size_t i = 0; i < s.x.size() && i < s.y.size(); ++i) {
            if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i])) { pen = false; continue; }
            std::snprintf(b, sizeof b, "%c%.1f %.1f", pen ? 'L' : 'M', X(s.x[i]), Y(s.y[i]));
            d += b;
            pen = true;
        }
        o << "<path d=\"" << d << "\" fill=\"none\" stroke=\"" << s.color << "\" stroke-width=\"1\"/>\n";
        o << "<rect x=\"" << L + 8 << "\" y=\"" << T + 6 + 14 * li << "\" width=\"12\" height=\"3\" fill=\"" << s.color
          << "\"/><text x=\"" << L + 24 << "\" y=\"" << T + 11 + 14 * li << "\">" << htmlEscape(s.label) << "</text>\n";
        ++li;
    }
    o << "</svg>\n";
    return o.str();
}

// The recovery self-test's table (self_test.hpp), when it ran.
static void writeSelfTest(std::ostream& o, const SelfTestResult& st) {
    if (!st.ran) return;
    o << "<h3>Recovery self-test</h3>";
    if (!st.ok) {
        o << "<p>Not completed: " << htmlEscape(st.message) << "</p>\n";
        return;
    }
    o << "<p>Replicas of these runs: fitted baseline + the effect at the size shown (simulated) + AR(1) noise of the "
         "baseline residual (RMS " << fmt(st.noiseRms, "%.4g") << "); the selection's &Delta;BIC and noise-null tests in the "
         "linearised refit (n<sub>eff</sub> " << fmt(st.neff, "%.0f") << "); the held-out and size tests are not applied, so "
         "detection rates are upper bounds for the full loop. False alarms on " << st.falseAlarmReplicas
      << " replicas without an effect: <b>" << st.falseAlarms << "</b>.</p>"
         "<table><tr><th>effect</th><th>size</th><th>SNR</th><th>visible SNR</th><th>detected</th><th>confused</th>"
         "<th>missed</th><th>note</th></tr>\n";
    for (const SelfTestRow& w : st.rows) {
        std::string confused;
        for (const auto& [name, n] : w.confusedWith) confused += (confused.empty() ? "" : ", ") + name + " &times;" + std::to_string(n);
        std::string shape;  // the effect's other parameters as stated
        for (const auto& [name, v] : w.shape) shape += ", " + htmlEscape(name) + " = " + fmt(v, "%.4g");
        o << "<tr><td class=l>" << htmlEscape(w.effect) << "</td><td>" << htmlEscape(w.sizeParam) << " = " << fmt(w.size, "%.4g")
          << " " << htmlEscape(w.unit) << shape << "</td><td>" << fmt(w.snr, "%.2f") << "</td><td>" << fmt(w.visibleSnr, "%.2f")
          << "</td><td>" << w.detected << "/" << w.replicas << "</td><td>" << w.confused
          << (confused.empty() ? "" : " (" + confused + ")") << "</td><td>" << w.missed << "</td><td class=l>"
          << htmlEscape(w.note) << "</td></tr>\n";
    }
    o << "</table>\n";
}

namespace {

// Page head, the verdict, the error before and after, the baseline note.
void writeSummary(std::ostream& o, const IdentifyResult& r) {
    o << "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>StickSlip Lab: identify report</title>\n"
         "<style>body{font-family:sans-serif;max-width:1000px;margin:1em auto;color:#222}"
         "table{border-collapse:collapse;margin:.5em 0}td,th{border:1px solid #ccc;padding:2px 8px;text-align:right}"
         "th{background:#f3f3f3}td.l{text-align:left}.warn{color:#a40}</style></head><body>\n";
    o << "<h1>Missing-effect identification</h1>\n<p>Set-up: " << htmlEscape(r.setup) << ", residual: "
      << htmlEscape(r.residual) << ". " << r.fits << " fits, "
      << fmt(r.wallTime_s, "%.1f") << " s.</p>\n";
    o << "<h2>Result</h2><p>Effects added: <b>";
    if (r.effectsAdded.empty()) o << "none";
    for (size_t i = 0; i < r.effectsAdded.size(); ++i) o << (i ? ", " : "") << htmlEscape(r.effectsAdded[i].name);
    o << "</b>.</p>\n";
    if (r.unexplained)
        o << "<p class=\"warn\">Unexplained structure remains: " << htmlEscape(r.unexplainedReason) << "</p>\n";
    else
        o << "<p>No unexplained structure: what is left of the residual is not predicted from run to run by the "
             "runs' own state as an effect would have to be (" << htmlEscape(r.structureNote) << ").</p>\n";
    if (const std::string t = lawResolutionText(r.lawResolution); !t.empty() && !r.unexplained)
        o << "<p class=\"warn\">Numerical resolution: " << htmlEscape(t) << ".</p>\n";
    o << "<table><tr><th></th><th>fit NRMSE</th><th>held-out NRMSE</th></tr>"
      << "<tr><td class=l>before (baseline)</td><td>" << fmt(r.before.fitNrmse) << "</td><td>" << fmt(r.before.validationNrmse)
      << "</td></tr><tr><td class=l>after</td><td>" << fmt(r.after.fitNrmse) << "</td><td>" << fmt(r.after.validationNrmse)
      << "</td></tr></table>\n";
    if (!r.baselineNote.empty()) o << "<p>Baseline: " << htmlEscape(r.baselineNote) << ".</p>\n";
}

// Fit and held-out error of every run before and after (the table is closed by the next section).
void writePerRun(std::ostream& o, const IdentifyResult& r) {
    o << "<h3>Per run</h3><table><tr><th>run</th><th>role</th><th>NRMSE before</th><th>held-out before</th>"
         "<th>NRMSE after</th><th>held-out after</th></tr>\n";
    for (size_t i = 0; i < r.before.runs.size(); ++i) {
        const RunError& b = r.before.runs[i];
        const RunError* a = i < r.after.runs.size() ? &r.after.runs[i] : nullptr;
        o << "<tr><td class=l>" << htmlEscape(b.file) << "</td><td class=l>" << b.role << "</td><td>" << fmt(b.nrmse) << "</td><td>"
          << fmt(b.heldOutNrmse) << "</td><td>" << (a ? fmt(a->nrmse) : "") << "</td><td>" << (a ? fmt(a->heldOutNrmse) : "")
          << "</td></tr>\n";
    }
}

// The effects added, with their parameters and the residual correlations that pointed to them.
void writeEffectsAdded(std::ostream& o, const IdentifyResult& r) {
    o << "</table>\n<h3>Effects added</h3><table><tr><th>effect</th><th>parameter</th><th>value</th><th>std. error</th>"
         "<th>&Delta;BIC</th><th>pointed to by (r before)</th><th>fit gain at the law's step / finer</th></tr>\n";
    for (const AddedEffect& e : r.effectsAdded) {
        std::string ptr;
        for (const auto& c : e.pointedBy) ptr += c.signal + " " + fmt(c.correlation, "%.3f") + "; ";
        // The share of the fit's sum of squares the effect removes, at the fits' law step and with
        // every law step split finer (AddedEffect::LawStepGain).
        const std::string step = e.lawStep.checked() ? fmt(100.0 * e.lawStep.gain(), "%.1f") + " % / " +
                                                           fmt(100.0 * e.lawStep.gainRefined(), "%.1f") + " % (&times;" +
                                                           std::to_string(e.lawStep.refinement) + ")"
                                                     : "&ndash;";
        for (const ParamEstimate& p : e.params)
            o << "<tr><td class=l>" << htmlEscape(e.name) << "</td><td class=l>" << htmlEscape(p.name) << "</td><td>" << fmt(p.value)
              << "</td><td>" << fmt(p.stderr_) << "</td><td>" << fmt(e.deltaBic, "%.1f") << "</td><td class=l>" << htmlEscape(ptr)
              << "</td><td>" << step << "</td></tr>\n";
    }
}

// Every candidate tried, with the numbers of each test of the selection rule and its verdict.
void writeCandidates(std::ostream& o, const IdentifyResult& r) {
    o << "</table>\n<h3>Candidates</h3><p>" << htmlEscape(selectionRule(r)) << " Each row says which test stopped the candidate."
         "</p><table><tr><th>effect</th><th>round</th><th>&Delta;BIC</th>"
         "<th>fit NRMSE</th><th>gain / noise quantile</th><th>held-out NRMSE</th><th>held-out p</th><th>|size &minus; vanishing value| / s.e.</th><th>t crit.</th>"
         "<th>verdict</th></tr>\n";
    for (const CandidateScore& c : r.candidates) {
        const bool ho = c.heldOutUnits > 0, sz = !c.sizeParam.empty() && c.sizeStderr > 0;
        o << "<tr><td class=l>" << htmlEscape(c.name) << "</td><td>" << c.round << "</td><td>"
          << (c.applicable ? fmt(c.deltaBic, "%.1f") : "&ndash;") << "</td><td>" << (c.applicable ? fmt(c.fitNrmse) : "&ndash;")
          << "</td><td>" << (c.nullReplicas > 0 && c.nullGain > 0 ? fmt(c.gain / c.nullGain, "%.3g") : "&ndash;")
          << "</td><td>" << (c.heldOutNrmse >= 0 ? fmt(c.heldOutNrmse) : "&ndash;") << "</td><td>"
          << (ho && c.heldOutP >= 0 ? fmt(c.heldOutP, "%.3g") : "&ndash;") << "</td><td>"
          << (sz ? fmt(std::abs(c.sizeValue - c.sizeNull) / c.sizeStderr, "%.2f") : "&ndash;") << "</td><td>"
          << (sz ? fmt(c.sizeCritical, "%.2f") : "&ndash;") << "</td><td class=l>"
          << htmlEscape(verdictOf(c)) << "</td></tr>\n";
    }
    o << "</table>\n";
}

// Baseline and final parameters.
void writeParameters(std::ostream& o, const IdentifyResult& r) {
    o << "<h3>Parameters</h3><table><tr><th>parameter</th><th>baseline</th><th>&plusmn;</th></tr>\n";
    for (const ParamEstimate& p : r.baseline)
        o << "<tr><td class=l>" << htmlEscape(p.name) << "</td><td>" << fmt(p.value) << "</td><td>" << fmt(p.stderr_) << "</td></tr>\n";
    o << "</table><table><tr><th>parameter</th><th>final</th><th>&plusmn;</th></tr>\n";
    for (const ParamEstimate& p : r.final)
        o << "<tr><td class=l>" << htmlEscape(p.name) << "</td><td>" << fmt(p.value) << "</td><td>" << fmt(p.stderr_) << "</td></tr>\n";
}

// The "unexplained" verdict's evidence (residualStructure): per held-out run, d before and after
// and the feature the other runs chose; the test's summary per model.
void writeStructure(std::ostream& o, const IdentifyResult& r) {
    const StructureTest& b = r.diagnosticsBefore.structure;
    const StructureTest& a = r.diagnosticsAfter.structure;
    if (b.runs < 2) return;
    o << "<h3>Run-to-run structure</h3><p>Each run held out in turn, its residual predicted from the other runs by the step "
         "function or line per sign of the signal they choose; d = ln(MSE before / after), &gt; 0: predictable from the "
         "run's own state. Before: mean d " << fmt(b.test.meanLogRatio, "%.3g") << ", sign-flip mid-p " << fmt(b.test.midP, "%.3g")
      << "; after: mean d " << fmt(a.test.meanLogRatio, "%.3g") << ", sign-flip mid-p " << fmt(a.test.midP, "%.3g") << ".</p>\n";
    o << "<table><tr><th>run held out</th><th>d before</th><th>predicted by</th><th>d after</th><th>predicted by</th></tr>\n";
    for (size_t i = 0; i < static_cast<size_t>(b.runs); ++i) {
        const std::string name = b.runs == static_cast<int>(r.traces.size()) ? r.traces[i].file : "run " + std::to_string(i + 1);
        auto d = [&](const StructureTest& t) { return i < t.logRatios.size() ? fmt(t.logRatios[i], "%.3f") : std::string("&ndash;"); };
        auto by = [&](const StructureTest& t) {
            return i < t.chosen.size() ? htmlEscape(t.chosen[i].empty() ? std::string("none") : t.chosen[i]) : std::string("&ndash;");
        };
        o << "<tr><td class=l>" << htmlEscape(name) << "</td><td>" << d(b) << "</td><td class=l>" << by(b) << "</td><td>" << d(a)
          << "</td><td class=l>" << by(a) << "</td></tr>\n";
    }
    o << "</table>\n";
}

// Residual correlations with the candidate signals, whiteness, autocorrelation and spectrum.
void writeDiagnostics(std::ostream& o, const IdentifyResult& r) {
    o << "</table>\n<h2>Residual diagnostics</h2><table><tr><th>signal</th><th>r before</th><th>r after</th></tr>\n";
    for (size_t i = 0; i < r.diagnosticsBefore.correlations.size(); ++i)
        o << "<tr><td class=l>" << r.diagnosticsBefore.correlations[i].signal << "</td><td>"
          << fmt(r.diagnosticsBefore.correlations[i].correlation, "%.3f") << "</td><td>"
          << (i < r.diagnosticsAfter.correlations.size() ? fmt(r.diagnosticsAfter.correlations[i].correlation, "%.3f") : "")
          << "</td></tr>\n";
    o << "</table><p>Ljung&ndash;Box p before " << fmt(r.diagnosticsBefore.whiteness.pValue) << ", after "
      << fmt(r.diagnosticsAfter.whiteness.pValue) << "; structure ratio before "
      << fmt(r.diagnosticsBefore.whiteness.structureRatio, "%.3f") << ", after "
      << fmt(r.diagnosticsAfter.whiteness.structureRatio, "%.3f") << ".</p>\n";
    writeStructure(o, r);
    {
        std::vector<SvgSeries> acf;
        for (const auto* d : {&r.diagnosticsBefore, &r.diagnosticsAfter}) {
            SvgSeries s{{}, d->whiteness.acf, d == &r.diagnosticsBefore ? "#c33" : "#36c", d == &r.diagnosticsBefore ? "before" : "after"};
            for (size_t k = 0; k < s.y.size(); ++k) s.x.push_back(static_cast<double>(k * d->whiteness.decimation));
            acf.push_back(s);
        }
        o << svgLinePlot(acf, "Residual autocorrelation", "lag [samples]", "ACF");
        std::vector<SvgSeries> sp;
        for (const auto* d : {&r.diagnosticsBefore, &r.diagnosticsAfter}) {
            SvgSeries s{{}, {}, d == &r.diagnosticsBefore ? "#c33" : "#36c", d == &r.diagnosticsBefore ? "before" : "after"};
            for (size_t k = 1; k < d->spectrum.frequency_Hz.size() && d->spectrum.frequency_Hz[k] <= 150; ++k) {
                s.x.push_back(d->spectrum.frequency_Hz[k]);
                s.y.push_back(std::log10(std::max(d->spectrum.power[k], 1e-30)));
            }
            sp.push_back(s);
        }
        o << svgLinePlot(sp, "Residual spectrum (longest run); forcing harmonics at " +
                                 (r.diagnosticsBefore.spectrum.harmonics_Hz.empty() ? std::string("?")
                                                                                    : fmt(r.diagnosticsBefore.spectrum.harmonics_Hz[0], "%.3g")) +
                                 " Hz multiples",
                         "frequency [Hz]", "log10 power");
    }
}

// Per run: measured and predicted force, residual and force-velocity loops (SVG).
void writeRunTraces(std::ostream& o, const IdentifyResult& r) {
    o << "<h2>Runs</h2>\n";
    for (const RunTrace& t : r.traces) {
        // At most ~3 forcing periods or 1500 samples for readability.
        const size_t n = std::min<size_t>(t.t_s.size(), 1500);
        SvgSeries m{{}, {}, "#000", "measured"}, b{{}, {}, "#c33", "before"}, a{{}, {}, "#36c", "after"};
        SvgSeries rb{{}, {}, "#c33", "residual before"}, ra{{}, {}, "#36c", "residual after"};
        SvgSeries lm{{}, {}, "#000", "measured"}, lb{{}, {}, "#c33", "before"}, la{{}, {}, "#36c", "after"};
        for (size_t i = 0; i < n; ++i) {
            const double x = t.t_s[i];
            m.x.push_back(x); m.y.push_back(t.measured_N[i]);
            b.x.push_back(x); b.y.push_back(t.before_N[i]);
            a.x.push_back(x); a.y.push_back(t.after_N[i]);
            rb.x.push_back(x); rb.y.push_back(t.measured_N[i] - t.before_N[i]);
            ra.x.push_back(x); ra.y.push_back(t.measured_N[i] - t.after_N[i]);
            const double v = t.relVel_mps[i];
            lm.x.push_back(v); lm.y.push_back(t.measured_N[i]);
            lb.x.push_back(v); lb.y.push_back(t.before_N[i]);
            la.x.push_back(v); la.y.push_back(t.after_N[i]);
        }
        o << "<h3>" << htmlEscape(t.file) << "</h3>\n";
        o << svgLinePlot({m, b, a}, "Force: measured vs predicted", "t [s]", "F [N]");
        o << svgLinePlot({rb, ra}, "Residual", "t [s]", "F measured - predicted [N]", 640, 220);
        o << svgLinePlot({lm, lb, la}, "Loops: force vs slip velocity", "V [m/s]", "F [N]", 420, 320);
    }
}

// Where the wall time and the fits went, stage by stage (IdentifyResult::timeline).
void writeTimeline(std::ostream& o, const IdentifyResult& r) {
    if (r.timeline.empty()) return;
    o << "<h2>Where the time went</h2><table><tr><th>stage</th><th>start [s]</th><th>wall [s]</th><th>fits</th></tr>\n";
    for (const IdentifyStage& st : r.timeline)
        o << "<tr><td class=l>" << htmlEscape(st.label) << "</td><td>" << fmt(st.start_s, "%.1f") << "</td><td>"
          << fmt(st.end_s - st.start_s, "%.1f") << "</td><td>" << st.fits << "</td></tr>\n";
    o << "</table>\n";
}

}  // namespace

std::string renderHtmlReport(const IdentifyResult& r) {
    std::ostringstream o;
    writeSummary(o, r);
    writePerRun(o, r);
    writeEffectsAdded(o, r);
    writeCandidates(o, r);
    writeSelfTest(o, r.selfTest);
    writeParameters(o, r);
    writeDiagnostics(o, r);
    writeRunTraces(o, r);
    writeTimeline(o, r);
    o << "</body></html>\n";
    return o.str();
}

}  // namespace stickslip::identify
