// `stickslip-cli reproduce --figure 19|20|22|23 --out DIR`: recomputes one of the paper's
// numerical figures (Figs 19-23, ../shared/MODEL.md) and writes its data as CSV and the
// figure as SVG and PNG, rendered headless (offscreen Qt platform) with the same plot widgets
// the app uses. The resolution is deliberately coarser than the paper's by default so a run
// finishes in about a minute; every knob is an option (see --help and README). Defaults:
// 100 values of A from 0.1 to 5 mm, continuation upwards, 40 settle + 40 sampled cycles per
// value, T/4000 steps; Figs 22/23 a 40-cycle run (after 40 settle cycles) and a 2000-point
// Poincaré section (the paper's Fig. 22b has 40 000: pass --section-points 40000).
//
//   19, 20: continuation bifurcation sweeps in A (rate-state and Coulomb side by side).
//   22:     A = 0.40 mm: phase portrait, Poincaré section, spectrum, autocorrelation.
//   23:     eta = 0.2 s/m: bifurcation sweep in A, and at A = 4 mm the phase portrait,
//           Poincaré section and spectrum.
#include <cmath>
#include <filesystem>
#include <iostream>
#include <memory>
#include <sstream>

#include "cancel.hpp"
#include "cli_common.hpp"
#include "commands.hpp"
#include "core/friction/friction_law.hpp"
#include "core/analysis/correlation.hpp"
#include "core/analysis/poincare.hpp"
#include "core/analysis/spectrum.hpp"
#include "core/analysis/sweep.hpp"
#include "core/integrate/simulate.hpp"
#include "core/io/csv_table.hpp"
#include "core/io/run_csv.hpp"
#include "core/presets.hpp"

#ifdef STICKSLIP_HAVE_WIDGETS
#include <QApplication>
#include <QDir>
#include <QElapsedTimer>

#include "widgets/autocorrelation_plot.hpp"
#include "widgets/bifurcation_plot.hpp"
#include "widgets/phase_portrait_plot.hpp"
#include "widgets/plot_export.hpp"
#include "widgets/poincare_plot.hpp"
#include "widgets/spectrum_plot.hpp"
#include <qwt_plot.h>
#endif

namespace stickslip::cli {

#ifdef STICKSLIP_HAVE_WIDGETS
namespace {

struct ReproduceOptions {
    int figure = 0;
    std::string out;
    std::vector<std::string> sets;   // KEY=VALUE overrides of the figure's preset
    int steps = 100;                 // swept A values (paper: a slow continuous sweep)
    double from_m = 0.1e-3;          // sweep start [m]
    double to_m = 5.0e-3;            // sweep end [m]
    std::string direction = "up";    // up | down | both
    long settle = 40;                // settle cycles per swept value / before a section
    long samples = 40;               // Poincaré samples per swept value
    long stepsPerPeriod = 4000;      // N: dt = T/N (the presets use 10 000)
    double tolerance = 0.0;          // > 0: error-controlled steps (adaptive.hpp) instead of dt = T/N
    long cycles = 40;                // recorded cycles for phase portraits and spectra
    long sectionPoints = 2000;       // Poincaré points for Figs 22/23 (paper: 40 000)
    bool coulomb = true;             // also the Coulomb model for Figs 19/20
    int threads = 0;                 // unused by continuation; kept for symmetry with sweep
};

// Writes a '\r'-updated progress line on stderr.
RunControl progressTo(const std::string& what) {
    RunControl ctl;
    ctl.cancel = &cancelFlag();
    ctl.progress = [what, last = -1](double f) mutable {
        const int pct = 10 * static_cast<int>(std::floor(10.0 * f));
        if (pct != last) {
            last = pct;
            std::cerr << "\r  " << what << ": " << pct << " %" << std::flush;
            if (pct >= 100) std::cerr << '\n';
        }
    };
    return ctl;
}

// After Ctrl-C nothing more is written (the files already written are whole), exit 5.
bool stopIfCancelled(int& exitCode) {
    if (!cancelRequested()) return false;
    if (exitCode != kCancelled) reportError("reproduce", "cancelled; no further output written", kCancelled, exitCode);
    return true;
}

bool writeText(const std::string& path, const std::string& text, int& exitCode) {
    if (stopIfCancelled(exitCode)) return false;
    std::string error;
    if (!io::writeFileAtomically(path, text, &error)) {
        reportError("reproduce", error, kBadInput, exitCode);
        return false;
    }
    std::cout << "wrote " << path << '\n';
    return true;
}

bool exportFigure(const std::vector<const QwtPlot*>& plots, int columns, const QSizeF& size_mm,
                  const std::string& stem, int& exitCode) {
    if (stopIfCancelled(exitCode)) return false;
    widgets::ExportOptions eo;
    eo.size_mm = size_mm;
    eo.resolution_dpi = 110;
    for (const char* ext : {".svg", ".png"}) {
        const QString path = QString::fromStdString(stem + ext);
        QString error;
        if (!widgets::exportPlots(plots, columns, path, &error, eo)) {
            reportError("reproduce", error.toStdString(), kBadInput, exitCode);
            return false;
        }
        std::cout << "wrote " << path.toStdString() << '\n';
    }
    return true;
}

std::string num(double v) {
    std::ostringstream s;
    s.precision(10);
    s << v;
    return s.str();
}

// Continuation sweep of A for one law; reports a failure and returns false.
bool sweepA(const SimParams& base, LawKind law, const ReproduceOptions& o, SweepResult& out, int& exitCode) {
    SimParams p = base;
    p.law = law;
    SweepOptions so;
    so.key = "A";
    so.from = o.from_m;
    so.to = o.to_m;
    so.steps = o.steps;
    so.mode = SweepMode::Continuation;
    parseSweepDirection(o.direction, so.direction);
    so.settleCycles = o.settle;
    so.sampleCycles = o.samples;
    so.stepsPerPeriod = o.stepsPerPeriod;
    if (const auto issues = so.validate(p); !issues.empty()) {
        reportError("reproduce", formatIssues(issues), kBadArguments, exitCode);
        return false;
    }
    QElapsedTimer clock;
    clock.start();
    out = bifurcationSweep(p, so, progressTo(std::string("sweep A, ") + lawInfo(law).label));
    std::cerr << "  " << out.points.size() << " values in " << clock.elapsed() / 1000.0 << " s\n";
    if (!out.ok()) {
        if (stopIfCancelled(exitCode)) return false;
        reportError("reproduce", "sweep failed: " + out.message, kRunFailed, exitCode);
        return false;
    }
    return true;
}

void appendSweepCsv(std::ostringstream& csv, std::ostringstream& summary, const SweepResult& r, LawKind law) {
    const char* model = toString(law);
    for (const SweepPoint& pt : r.points) {
        const char* dir = pt.direction < 0 ? "down" : "up";
        for (size_t i = 0; i < pt.section.size(); ++i) {
            csv << model << ',' << num(pt.value) << ',' << dir << ',' << i << ',' << num(pt.section.slider_m[i]) << ','
                << num(pt.section.relVel_mps[i]) << ',' << num(pt.section.ratio[i]) << '\n';
        }
        summary << model << ',' << num(pt.value) << ',' << dir << ',' << toString(pt.classification.motion) << ','
                << pt.classification.period << ',' << num(pt.classification.stickFraction) << ','
                << num(pt.classification.maxRelVel_mps) << '\n';
    }
}

void fillBifurcation(widgets::BifurcationPlot& plot, const SweepResult& r, LawKind law, const QString& title) {
    plot.plot()->setTitle(title);
    for (const SweepPoint& pt : r.points) plot.appendPoint(pt, law);
    plot.rescale();
}

// The run behind a phase portrait and spectrum: settle cycles discarded, then `cycles` kept,
// dt = T/N, output every T/400.
bool recordedRun(const SimParams& base, const ReproduceOptions& o, SimParams& p, RunResult& run, int& exitCode) {
    p = base;
    p.setup = SetupKind::Dynamics;
    p.integration.dt_s = p.drive.period() / static_cast<double>(o.stepsPerPeriod);
    p.integration.outputInterval_s = p.drive.period() / 400.0;
    p.transientCycles = static_cast<double>(o.settle);
    p.cycles = static_cast<double>(o.cycles);
    if (const auto issues = p.validate(); !issues.empty()) {
        reportError("reproduce", formatIssues(issues), kBadArguments, exitCode);
        return false;
    }
    run = simulate(p, progressTo("time series"));
    if (!run.ok()) {
        if (stopIfCancelled(exitCode)) return false;
        reportError("reproduce", std::string("run ") + toString(run.status) + ": " + run.message, kRunFailed, exitCode);
        return false;
    }
    return true;
}

bool section(const SimParams& base, const ReproduceOptions& o, PoincareSection& s, int& exitCode) {
    PoincareOptions po;
    po.stepsPerPeriod = o.stepsPerPeriod;
    po.settleCycles = o.settle;
    po.cycles = o.sectionPoints;
    if (const auto issues = po.validate(); !issues.empty()) {
        reportError("reproduce", formatIssues(issues), kBadArguments, exitCode);
        return false;
    }
    s = poincareSection(base, po, progressTo("Poincare section"));
    if (!s.ok()) {
        if (stopIfCancelled(exitCode)) return false;
        reportError("reproduce", "Poincare section failed: " + s.message, kRunFailed, exitCode);
        return false;
    }
    return true;
}

std::string sectionCsv(const PoincareSection& s) {
    std::ostringstream csv;
    csv << "# Poincare section, one point per forcing period (phase 0)\n";
    csv << "sample,t_s,slider_disp_m,rel_vel_mps,friction_ratio\n";
    for (size_t i = 0; i < s.size(); ++i)
        csv << i << ',' << num(s.t_s[i]) << ',' << num(s.slider_m[i]) << ',' << num(s.relVel_mps[i]) << ','
            << num(s.ratio[i]) << '\n';
    return csv.str();
}

std::vector<double> sliderSeries(const RunResult& run) {
    std::vector<double> x;
    x.reserve(run.samples.size());
    for (const Sample& s : run.samples) x.push_back(s.slider_m);
    return x;
}

std::string header(int figure, const SimParams& p, const ReproduceOptions& o) {
    std::ostringstream h;
    h << "# stickslip-cli reproduce --figure " << figure << "\n# ";
    if (o.tolerance > 0) h << "integration = adaptive, tolerance = " << num(o.tolerance);
    else h << "steps_per_period = " << o.stepsPerPeriod;
    h << ", settle_cycles = " << o.settle << "\n# params:";
    for (const auto& key : paramKeys()) {
        double v = 0;
        if (getParam(p, key, v)) h << ' ' << key << '=' << num(v);
    }
    h << '\n';
    return h.str();
}

// The figure's parameters (its preset with the --set overrides, validated) and the output
// directory. False (exit code set) on bad input.
bool figureParams(const ReproduceOptions& o, SimParams& base, int& exitCode) {
    Preset preset;
    if (!findPreset("fig" + std::to_string(o.figure), preset)) {
        reportError("reproduce", "no preset for figure " + std::to_string(o.figure), kBadArguments, exitCode);
        return false;
    }
    base = preset.params;
    base.integration.tolerance = o.tolerance;
    for (const auto& s : o.sets) {
        std::string key, why;
        double v = 0;
        if (!parseAssignment(s, key, v, &why) || !setParam(base, key, v, &why)) {
            reportError("reproduce", why, kBadArguments, exitCode);
            return false;
        }
    }
    if (const auto issues = base.validate(); !issues.empty()) {
        reportError("reproduce", formatIssues(issues), kBadArguments, exitCode);
        return false;
    }
    std::error_code ec;
    std::filesystem::create_directories(o.out, ec);
    if (ec) {
        reportError("reproduce", o.out + ": cannot create directory: " + ec.message(), kBadInput, exitCode);
        return false;
    }
    return true;
}

// <stem>_sweep.csv and <stem>_summary.csv of the rate-state sweep and, when given, the Coulomb one.
bool writeSweepCsvs(const ReproduceOptions& o, const SimParams& base, const std::string& stem, const SweepResult& rs,
                    const SweepResult* cl, int& exitCode) {
    std::ostringstream csv, summary;
    csv << header(o.figure, base, o) << "model,param_value,direction,sample,slider_disp_m,rel_vel_mps,friction_ratio\n";
    summary << header(o.figure, base, o) << "model,param_value,direction,class,period,stick_fraction,max_rel_vel_mps\n";
    appendSweepCsv(csv, summary, rs, LawKind::RateState);
    if (cl) appendSweepCsv(csv, summary, *cl, LawKind::Coulomb);
    return writeText(stem + "_sweep.csv", csv.str(), exitCode) && writeText(stem + "_summary.csv", summary.str(), exitCode);
}

const QString kAmplitudeTitle = QStringLiteral("stage amplitude A [mm]");
const QString kSectionTitle = QStringLiteral("Poincaré samples of slider x [mm]");

// Figs 19 and 20: the amplitude sweep, rate-state and (unless --no-coulomb) Coulomb panels.
void bifurcationFigure(const ReproduceOptions& o, const SimParams& base, const std::string& stem, int& exitCode) {
    const std::string fig = "Fig. " + std::to_string(o.figure);
    SweepResult rs, cl;
    if (!sweepA(base, LawKind::RateState, o, rs, exitCode)) return;
    if (o.coulomb && !sweepA(base, LawKind::Coulomb, o, cl, exitCode)) return;
    if (!writeSweepCsvs(o, base, stem, rs, o.coulomb ? &cl : nullptr, exitCode)) return;
    const QString setText = QStringLiteral("k = %1 N/m, t_N = %2 N, f = %3 Hz, ε_T = %4 N/m")
                                .arg(base.rig.stiffness_N_per_m)
                                .arg(base.rig.normalForce_N)
                                .arg(base.drive.frequency_Hz)
                                .arg(base.lawParams<RateStateParams>().epsT_N_per_m, 0, 'g', 3);
    widgets::BifurcationPlot a, c;
    a.setAxes(kAmplitudeTitle, 1e3, kSectionTitle, 1e3);
    c.setAxes(kAmplitudeTitle, 1e3, kSectionTitle, 1e3);
    fillBifurcation(a, rs, LawKind::RateState, QString::fromStdString(fig) + QStringLiteral(", rate-state model: ") + setText);
    std::vector<const QwtPlot*> plots{a.plot()};
    if (o.coulomb) {
        fillBifurcation(c, cl, LawKind::Coulomb, QString::fromStdString(fig) + QStringLiteral(", Coulomb model (μ = %1)").arg(base.lawParams<CoulombParams>().mu));
        plots.push_back(c.plot());
    }
    exportFigure(plots, 1, QSizeF(180, o.coulomb ? 200 : 110), stem, exitCode);
}

// <stem>_spectrum.csv and <stem>_autocorrelation.csv of the slider displacement.
bool writeSignalCsvs(const ReproduceOptions& o, const SimParams& base, const std::string& stem, const PowerSpectrum& psd,
                     const Correlation& ac, int& exitCode) {
    std::ostringstream csv;
    csv << header(o.figure, base, o) << "frequency_Hz,psd_slider_m2_per_Hz\n";
    for (size_t i = 0; i < psd.frequency_Hz.size(); ++i) csv << num(psd.frequency_Hz[i]) << ',' << num(psd.psd[i]) << '\n';
    if (!writeText(stem + "_spectrum.csv", csv.str(), exitCode)) return false;
    std::ostringstream acsv;
    acsv << header(o.figure, base, o) << "lag_s,autocorrelation\n";
    for (size_t i = 0; i < ac.lag_s.size(); ++i) acsv << num(ac.lag_s[i]) << ',' << num(ac.r[i]) << '\n';
    return writeText(stem + "_autocorrelation.csv", acsv.str(), exitCode);
}

// Figs 22 and 23: one settled motion at the preset's A (phase portrait, Poincaré section,
// spectrum, autocorrelation); Fig. 23 puts the bifurcation sweep at this η first.
void motionFigure(const ReproduceOptions& o, const SimParams& base, const std::string& stem, int& exitCode) {
    const std::string fig = "Fig. " + std::to_string(o.figure);
    SimParams runParams;
    RunResult run;
    PoincareSection sec;
    if (!recordedRun(base, o, runParams, run, exitCode)) return;
    if (!section(base, o, sec, exitCode)) return;
    std::string error;
    if (!io::writeRunCsv(stem + "_run.csv", runParams, run, &error, {"reproduce --figure " + std::to_string(o.figure)})) {
        reportError("reproduce", error, kBadInput, exitCode);
        return;
    }
    std::cout << "wrote " << stem << "_run.csv\n";
    if (!writeText(stem + "_poincare.csv", header(o.figure, base, o) + sectionCsv(sec), exitCode)) return;

    const double fs = 1.0 / runParams.integration.outputInterval_s;
    const std::vector<double> x = sliderSeries(run);
    const PowerSpectrum psd = powerSpectrum(x, fs);
    const Correlation ac = autocorrelation(x, fs, static_cast<size_t>(std::lround(10.0 * runParams.drive.period() * fs)));
    if (!writeSignalCsvs(o, base, stem, psd, ac, exitCode)) return;

    const QString at = QStringLiteral("A = %1 mm, η = %2 s/m").arg(base.drive.amplitude_m * 1e3).arg(base.lawParams<RateStateParams>().eta_s_per_m);
    widgets::PhasePortraitPlot phase;
    phase.setRun(run);
    phase.plot()->setTitle(QString::fromStdString(fig) + QStringLiteral(" phase portrait, ") + at);
    phase.rescale();
    widgets::PoincarePlot poincare;
    poincare.setSection(sec);
    poincare.plot()->setTitle(QStringLiteral("Poincaré section (%1 points)").arg(sec.size()));
    poincare.rescale();
    widgets::SpectrumPlot spectrum;
    spectrum.setValueTitle(QStringLiteral("PSD of slider x [m²/Hz]"));
    spectrum.setSpectrum(psd.frequency_Hz, psd.psd);
    spectrum.plot()->setTitle(QStringLiteral("Spectrum of x (Welch, Hann)"));
    spectrum.rescale();
    spectrum.plot()->setAxisScale(QwtPlot::xBottom, 0.0, 12.0 * base.drive.frequency_Hz);   // up to the 12th harmonic
    spectrum.plot()->replot();
    widgets::AutocorrelationPlot autocorr;
    autocorr.setAutocorrelation(ac.lag_s, ac.r);
    autocorr.plot()->setTitle(QStringLiteral("Autocorrelation of x"));
    autocorr.rescale();

    if (o.figure == 22) {
        exportFigure({phase.plot(), poincare.plot(), spectrum.plot(), autocorr.plot()}, 2, QSizeF(240, 170), stem,
                     exitCode);
        return;
    }
    SweepResult rs;
    if (!sweepA(base, LawKind::RateState, o, rs, exitCode)) return;
    if (!writeSweepCsvs(o, base, stem, rs, nullptr, exitCode)) return;
    widgets::BifurcationPlot bif;
    bif.setAxes(kAmplitudeTitle, 1e3, kSectionTitle, 1e3);
    fillBifurcation(bif, rs, LawKind::RateState,
                    QString::fromStdString(fig) + QStringLiteral(", rate-state, η = %1 s/m").arg(base.lawParams<RateStateParams>().eta_s_per_m));
    exportFigure({bif.plot(), phase.plot(), poincare.plot(), spectrum.plot()}, 2, QSizeF(240, 170), stem, exitCode);
}

void runFigure(const ReproduceOptions& o, int& exitCode) {
    SimParams base;
    if (!figureParams(o, base, exitCode)) return;
    // Headless Qt: the widgets need a QApplication; never a display.
    std::unique_ptr<QApplication> app;
    if (!QApplication::instance()) {
        if (qEnvironmentVariableIsEmpty("QT_QPA_PLATFORM")) qputenv("QT_QPA_PLATFORM", "offscreen");
        static int argc = 1;
        static char name[] = "stickslip-cli";
        static char* argv[] = {name, nullptr};
        app = std::make_unique<QApplication>(argc, argv);
    }
    const std::string stem = (std::filesystem::path(o.out) / ("fig" + std::to_string(o.figure))).string();
    if (o.figure == 19 || o.figure == 20) bifurcationFigure(o, base, stem, exitCode);
    else motionFigure(o, base, stem, exitCode);
}

}  // namespace
#endif

void addReproduceCommand(CLI::App& root, int& exitCode) {
    auto* cmd = root.add_subcommand(
        "reproduce", "Recompute a figure of the paper (19, 20, 22, 23): data as CSV, figure as SVG and PNG");
#ifdef STICKSLIP_HAVE_WIDGETS
    auto o = std::make_shared<ReproduceOptions>();
    cmd->add_option("--figure", o->figure, "Figure number: 19, 20, 22 or 23")
        ->required()
        ->check(CLI::IsMember({19, 20, 22, 23}));
    cmd->add_option("--out", o->out, "Output directory (created if missing)")->required();
    cmd->add_option("--set", o->sets, "Override a preset parameter, KEY=VALUE (e.g. k=410); repeatable");
    cmd->add_option("--steps", o->steps, "Swept amplitude values for bifurcation diagrams")
        ->capture_default_str()
        ->check(CLI::Range(1, 100000));
    cmd->add_option("--from", o->from_m, "First swept amplitude A [m]")->capture_default_str();
    cmd->add_option("--to", o->to_m, "Last swept amplitude A [m]")->capture_default_str();
    cmd->add_option("--direction", o->direction, "Sweep direction")
        ->capture_default_str()
        ->check(CLI::IsMember({"up", "down", "both"}));
    cmd->add_option("--settle", o->settle, "Settle cycles discarded per swept value / before a section")
        ->capture_default_str()
        ->check(CLI::Range(0L, 1000000L));
    cmd->add_option("--samples", o->samples, "Poincare samples kept per swept value")
        ->capture_default_str()
        ->check(CLI::Range(1L, 1000000L));
    cmd->add_option("--steps-per-period", o->stepsPerPeriod, "Time steps per forcing period (dt = T/N)")
        ->capture_default_str()
        ->check(CLI::Range(50L, 1000000L));
    cmd->add_option("--tolerance", o->tolerance,
                    "Integrate adaptively to this relative displacement error (1e-5 to 0.5) instead of dt = T/N: "
                    "error-controlled steps, stick-slip switches located, Poincare samples at the exact phase from "
                    "the dense output")
        ->type_name("TOL");
    cmd->add_option("--cycles", o->cycles, "Recorded cycles for the phase portrait and spectrum (Figs 22, 23)")
        ->capture_default_str()
        ->check(CLI::Range(1L, 1000000L));
    cmd->add_option("--section-points", o->sectionPoints, "Poincare section points (Figs 22, 23; paper: 40000)")
        ->capture_default_str()
        ->check(CLI::Range(1L, 10000000L));
    cmd->add_flag("--no-coulomb", [o](std::int64_t) { o->coulomb = false; }, "Skip the Coulomb panel (Figs 19, 20)");
    cmd->callback([o, &exitCode] { runFigure(*o, exitCode); });
#else
    cmd->callback([&exitCode] {
        reportError("reproduce", "this build has no plot widgets (configure with -DSTICKSLIP_BUILD_GUI=ON)",
                    kRunFailedGeneric, exitCode);
    });
#endif
}

}  // namespace stickslip::cli
