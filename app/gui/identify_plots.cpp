#include "identify_plots.hpp"

#include <QComboBox>
#include <QFileInfo>
#include <QHBoxLayout>
#include <QLabel>
#include <QTabWidget>
#include <QTableWidget>
#include <QVBoxLayout>
#include <cmath>

#include "identify_tables.hpp"
#include "widgets/series_plot.hpp"

namespace stickslip::gui {

using namespace stickslip::identify;

IdentifyPlots::IdentifyPlots(QWidget* parent) : QWidget(parent) {
    auto* w = this;
    auto* v = new QVBoxLayout(w);
    v->setContentsMargins(0, 0, 0, 0);
    auto* row = new QHBoxLayout;
    row->addWidget(new QLabel(tr("Run"), w));
    run_ = new QComboBox(w);
    run_->setMinimumContentsLength(24);
    run_->setSizeAdjustPolicy(QComboBox::AdjustToMinimumContentsLengthWithIcon);
    row->addWidget(run_);
    source_ = new QLabel(tr("Nothing fitted yet."), w);
    source_->setStyleSheet("color: #555;");
    row->addWidget(source_, 1);
    v->addLayout(row);
    plots_ = new QTabWidget(w);
    overlay_ = new widgets::SeriesPlot(w);
    overlay_->setTitles(tr("Measured versus predicted friction force"), tr("time t [s]"), tr("friction force F [N]"));
    residual_ = new widgets::SeriesPlot(w);
    residual_->setTitles(tr("Residual (measured − predicted)"), tr("time t [s]"), tr("residual [N]"));
    spectrum_ = new widgets::SeriesPlot(w);
    spectrum_->setTitles(tr("Residual spectrum (dotted: forcing harmonics)"), tr("frequency f [Hz]"), tr("power [N²/Hz]"));
    spectrum_->setLogY(true);
    acf_ = new widgets::SeriesPlot(w);
    acf_->setTitles(tr("Residual autocorrelation"), tr("lag [decimated samples]"), tr("ρ"));
    correlations_ = makeTable({tr("Candidate signal"), tr("r before"), tr("r after")}, w);
    plots_->addTab(overlay_, tr("Measured vs predicted"));
    plots_->addTab(residual_, tr("Residual"));
    plots_->addTab(spectrum_, tr("Spectrum"));
    plots_->addTab(acf_, tr("Autocorrelation"));
    plots_->addTab(correlations_, tr("Correlations"));
    auto* structure = new QWidget(w);
    auto* sv = new QVBoxLayout(structure);
    structureSummary_ = new QLabel(structure);
    structureSummary_->setWordWrap(true);
    structureRuns_ = makeTable({tr("Run held out"), tr("d baseline"), tr("predicted by"), tr("d final"), tr("predicted by")}, structure);
    structureSignals_ = makeTable({tr("Signal alone"), tr("mean d baseline"), tr("mean d final")}, structure);
    sv->addWidget(structureSummary_);
    sv->addWidget(structureRuns_, 3);
    sv->addWidget(structureSignals_, 2);
    plots_->addTab(structure, tr("Structure"));
    v->addWidget(plots_, 1);
    connect(run_, QOverload<int>::of(&QComboBox::currentIndexChanged), this, [this] { refresh(); });
}

void IdentifyPlots::showFit(const FitOutcome* fit) {
    fit_ = fit;
    identify_ = nullptr;
    refresh();
}

void IdentifyPlots::showIdentify(const IdentifyOutcome* identify) {
    identify_ = identify;
    fit_ = nullptr;
    refresh();
}

// The run choices follow what is shown; the selection is kept while the names are the same.
void IdentifyPlots::syncRunChoices() {
    QStringList names;
    if (fit_ && !fit_->fits.empty())
        for (const RunOverlay& o : fit_->fits.front().overlays) names << QString::fromStdString(o.file) + (o.role == "validation" ? tr(" (validation)") : QString());
    else if (identify_)
        for (const RunTrace& t : identify_->result.traces) names << QFileInfo(QString::fromStdString(t.file)).fileName();
    QStringList current;
    for (int i = 0; i < run_->count(); ++i) current << run_->itemText(i);
    if (current != names) {
        const QSignalBlocker block(run_);
        run_->clear();
        run_->addItems(names);
        run_->setCurrentIndex(names.isEmpty() ? -1 : 0);
    }
}

void IdentifyPlots::refresh() {
    syncRunChoices();
    const int k = run_->currentIndex();
    Series over, res;
    const Diagnostics* diag = nullptr;
    const Diagnostics* diagAfter = nullptr;
    if (fit_ && k >= 0) {
        diag = fitSeries(k, over, res);
    } else if (identify_ && k >= 0 && k < static_cast<int>(identify_->result.traces.size())) {
        identifySeries(k, over, res);
        const IdentifyResult& r = identify_->result;
        diag = &r.diagnosticsBefore;
        diagAfter = r.effectsAdded.empty() ? nullptr : &r.diagnosticsAfter;
    } else {
        source_->setText(tr("Nothing fitted yet."));
    }
    overlay_->setSeries(over);
    residual_->setSeries(res);
    showDiagnostics(diag, diagAfter);
    showCorrelations(diag, diagAfter);
    showStructure(diag, diagAfter);
}

const Diagnostics* IdentifyPlots::fitSeries(int k, Series& over, Series& res) {
    source_->setText(tr("Fit: %1").arg(fit_->fits.size() > 1 ? tr("rate-state (solid) and Coulomb (dashed)")
                                                              : lawName(fit_->fits.front().law)));
    bool first = true;
    const LawKind primary = fit_->fits.front().law;  // solid; a second law side by side dashed
    for (const LawFit& lf : fit_->fits) {
        if (k >= static_cast<int>(lf.overlays.size())) continue;
        const RunOverlay& o = lf.overlays[static_cast<size_t>(k)];
        if (first) over.push_back({tr("measured"), o.t_s, o.measured_N, kMeasured, false, true, 1.0});
        first = false;
        const QColor c = lawColor(lf.law);
        const bool dashed = lf.law != primary;
        over.push_back({tr("%1 predicted").arg(lawName(lf.law)), o.t_s, o.predicted_N, c, dashed, false, 1.4});
        std::vector<double> r(o.t_s.size());
        for (size_t j = 0; j < r.size(); ++j) r[j] = o.measured_N[j] - o.predicted_N[j];
        res.push_back({lawName(lf.law), o.t_s, r, c, dashed, false, 1.0});
    }
    return fit_->fits.front().diagnostics.spectrum.frequency_Hz.empty() ? nullptr : &fit_->fits.front().diagnostics;
}

void IdentifyPlots::identifySeries(int k, Series& over, Series& res) {
    const IdentifyResult& r = identify_->result;
    const RunTrace& t = r.traces[static_cast<size_t>(k)];
    source_->setText(r.effectsAdded.empty() ? tr("Identify: baseline (no effect added)") : tr("Identify: baseline and extended model"));
    // Dynamics compares only the sliding samples: leave the others out.
    std::vector<double> ts, m, b, a;
    for (size_t j = 0; j < t.t_s.size(); ++j) {
        if (j < t.used.size() && !t.used[j]) continue;
        ts.push_back(t.t_s[j]);
        m.push_back(t.measured_N[j]);
        b.push_back(j < t.before_N.size() ? t.before_N[j] : NAN);
        a.push_back(j < t.after_N.size() ? t.after_N[j] : NAN);
    }
    over.push_back({tr("measured"), ts, m, kMeasured, false, true, 1.0});
    over.push_back({tr("baseline"), ts, b, kBefore, true, false, 1.3});
    std::vector<double> rb(ts.size()), ra(ts.size());
    for (size_t j = 0; j < ts.size(); ++j) {
        rb[j] = m[j] - b[j];
        ra[j] = m[j] - a[j];
    }
    if (!r.effectsAdded.empty()) over.push_back({tr("extended"), ts, a, kAfter, false, false, 1.4});
    res.push_back({tr("baseline"), ts, rb, kBefore, false, false, 1.0});
    if (!r.effectsAdded.empty()) res.push_back({tr("extended"), ts, ra, kAfter, false, false, 1.0});
}

void IdentifyPlots::showDiagnostics(const Diagnostics* diag, const Diagnostics* diagAfter) {
    Series spec, acf;
    std::vector<double> harmonics;
    auto addDiag = [&](const Diagnostics& d, const QString& label, const QColor& c) {
        spec.push_back({label, d.spectrum.frequency_Hz, d.spectrum.power, c, false, false, 1.0});
        std::vector<double> lag(d.whiteness.acf.size());
        for (size_t j = 0; j < lag.size(); ++j) lag[j] = static_cast<double>(j);
        acf.push_back({label + QStringLiteral(" (Ljung–Box p = %1)").arg(d.whiteness.pValue, 0, 'g', 2), lag, d.whiteness.acf, c, false, false, 1.2});
        if (harmonics.empty()) harmonics = d.spectrum.harmonics_Hz;
    };
    const bool identify = identify_ != nullptr;
    if (diag) addDiag(*diag, identify ? tr("baseline") : tr("residual"), identify ? kBefore : kRate);
    if (diagAfter) addDiag(*diagAfter, tr("extended"), kAfter);
    spectrum_->setSeries(spec);
    spectrum_->setVerticalLines(harmonics);
    acf_->setSeries(acf);
    acf_->setHorizontalLines({0.0});
}

void IdentifyPlots::showCorrelations(const Diagnostics* diag, const Diagnostics* diagAfter) {
    correlations_->setRowCount(0);
    if (!diag) return;
    correlations_->setRowCount(static_cast<int>(diag->correlations.size()));
    for (size_t i = 0; i < diag->correlations.size(); ++i) {
        const int row = static_cast<int>(i);
        setCell(correlations_, row, 0, QString::fromStdString(diag->correlations[i].signal));
        setCell(correlations_, row, 1, QString::number(diag->correlations[i].correlation, 'f', 3));
        double after = NAN;
        if (diagAfter)
            for (const SignalCorrelation& c : diagAfter->correlations)
                if (c.signal == diag->correlations[i].signal) after = c.correlation;
        setCell(correlations_, row, 2, std::isfinite(after) ? QString::number(after, 'f', 3) : QStringLiteral("–"));
    }
    correlations_->resizeColumnsToContents();
}

// The "unexplained" verdict's evidence (residualStructure): d = ln(MSE before / MSE after
// subtracting what the other runs predict) per held-out run and per signal alone; d > 0 in every
// run is structure that repeats from run to run. Nothing is computed here: the worker's result.
void IdentifyPlots::showStructure(const Diagnostics* diag, const Diagnostics* diagAfter) {
    structureRuns_->setRowCount(0);
    structureSignals_->setRowCount(0);
    if (!diag || diag->structure.runs < 2) {
        structureSummary_->setText(tr("Run-to-run structure: not tested (it needs two runs or more)."));
        return;
    }
    const StructureTest& b = diag->structure;
    const bool identify = identify_ != nullptr;
    // Nothing added: the final model is the baseline, and so is its test.
    const StructureTest* a = diagAfter ? &diagAfter->structure : identify ? &b : nullptr;
    auto summary = [](const StructureTest& t) {
        return tr("mean d %1, sign-flip mid-p %2, t-test p %3").arg(t.test.meanLogRatio, 0, 'g', 3).arg(t.test.midP, 0, 'g', 2).arg(t.test.pValue, 0, 'g', 2);
    };
    structureSummary_->setText(
        tr("Each run held out in turn, its residual predicted from the other runs by the step function or line per sign of "
           "the signal they choose; d = ln(MSE before / after), > 0: the run's residual is predictable from its own state. "
           "%1: %2.").arg(identify ? tr("Baseline") : tr("Residual"), summary(b)) +
        (a == &b ? tr(" Final: the baseline (nothing added).") : a ? tr(" Final: %1.").arg(summary(*a)) : QString()));
    QStringList names;
    if (identify_ && static_cast<int>(identify_->result.traces.size()) == b.runs)
        for (const RunTrace& t : identify_->result.traces) names << QFileInfo(QString::fromStdString(t.file)).fileName();
    if (fit_ && !fit_->fits.empty()) {  // the fit's diagnostics: its fitted runs, in order
        for (const RunOverlay& o : fit_->fits.front().overlays)
            if (o.role != "validation") names << QFileInfo(QString::fromStdString(o.file)).fileName();
        if (names.size() != b.runs) names.clear();
    }
    structureRuns_->setRowCount(b.runs);
    for (int i = 0; i < b.runs; ++i) {
        const size_t k = static_cast<size_t>(i);
        setCell(structureRuns_, i, 0, i < names.size() ? names[i] : tr("run %1").arg(i + 1));
        setCell(structureRuns_, i, 1, k < b.logRatios.size() ? QString::number(b.logRatios[k], 'f', 3) : QStringLiteral("–"));
        setCell(structureRuns_, i, 2, k < b.chosen.size() && !b.chosen[k].empty() ? QString::fromStdString(b.chosen[k]) : tr("none"));
        const bool haveA = a && k < a->logRatios.size();
        setCell(structureRuns_, i, 3, haveA ? QString::number(a->logRatios[k], 'f', 3) : QStringLiteral("–"));
        setCell(structureRuns_, i, 4, haveA && k < a->chosen.size() ? QString::fromStdString(a->chosen[k].empty() ? "none" : a->chosen[k]) : QStringLiteral("–"));
    }
    structureSignals_->setRowCount(static_cast<int>(b.bySignal.size()));
    for (size_t j = 0; j < b.bySignal.size(); ++j) {
        const int row = static_cast<int>(j);
        setCell(structureSignals_, row, 0, QString::fromStdString(b.bySignal[j].signal));
        setCell(structureSignals_, row, 1, QString::number(b.bySignal[j].meanLogRatio, 'f', 3));
        double after = NAN;
        if (a)
            for (const SignalGain& g : a->bySignal)
                if (g.signal == b.bySignal[j].signal) after = g.meanLogRatio;
        setCell(structureSignals_, row, 2, std::isfinite(after) ? QString::number(after, 'f', 3) : QStringLiteral("–"));
    }
    structureRuns_->resizeColumnsToContents();
    structureSignals_->resizeColumnsToContents();
}

}  // namespace stickslip::gui
