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

}  // namespace stickslip::gui
