#include "identify_fit_tab.hpp"

#include "core/friction/friction_law.hpp"

#include <QCheckBox>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QFileInfo>
#include <QFormLayout>
#include <QGridLayout>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QLabel>
#include <QPushButton>
#include <QSpinBox>
#include <QTableWidget>
#include <QVBoxLayout>
#include <algorithm>
#include <cmath>

#include "identify_tables.hpp"

namespace stickslip::gui {

using namespace stickslip::identify;

namespace {

// The free-parameter check boxes: every law key with a fit range (param_table), m* and ζ.
std::vector<std::string> fitParams() {
    std::vector<std::string> out;
    for (const ParamDef& d : paramTable())
        if (d.group == ParamGroup::FrictionLaw && d.fit.valid()) out.emplace_back(d.key);
    out.emplace_back("m");
    out.emplace_back("zeta");
    return out;
}

// The tables' law columns: one per registered law, in registry order.
QStringList lawHeaders() {
    QStringList h;
    for (LawKind law : allLaws()) h << lawName(law);
    return h;
}

}  // namespace

IdentifyFitTab::IdentifyFitTab(QWidget* parent) : IdentifyJobTab(parent) {
    auto* w = this;
    auto* v = new QVBoxLayout(w);
    auto* form = new QFormLayout;
    buildSettings(form);
    buildLossAndSplit(form);
    buildSolver(form);
    v->addLayout(form);

    v->addLayout(makeRunRow(tr("Fit"), tr("Load runs, then Fit.")));
    runButton()->setDefault(true);
    v->addWidget(statusLabel());

    params_ = makeTable(QStringList{tr("Parameter")} + lawHeaders(), w);
    fitHeight(params_, 5);
    v->addWidget(new QLabel(tr("<b>Parameters</b> (value ± 1σ standard error)"), w));
    v->addWidget(params_);
    identifiability_ = new QLabel(w);
    identifiability_->setWordWrap(true);
    v->addWidget(identifiability_);
    runs_ = makeTable(QStringList{tr("Run"), tr("Role"), tr("RMS [N]")} + lawHeaders(), w);
    fitHeight(runs_, 3);
    v->addWidget(new QLabel(tr("<b>NRMSE per run</b> (RMS error / RMS measured)"), w));
    v->addWidget(runs_);
    v->addLayout(makeExportRow());
    v->addStretch(1);
}

void IdentifyFitTab::buildSettings(QFormLayout* form) {
    model_ = new QComboBox(this);
    for (LawKind law : allLaws()) model_->addItem(lawName(law), QString::fromUtf8(toString(law)));
    model_->addItem(tr("both, side by side"), "both");
    form->addRow(tr("Model"), model_);
    auto* freeBox = new QWidget(this);
    auto* fg = new QGridLayout(freeBox);
    fg->setContentsMargins(0, 0, 0, 0);
    int k = 0;
    for (const std::string& n : fitParams()) {
        auto* c = new QCheckBox(paramTitle(n).section(' ', 0, 0), freeBox);
        c->setToolTip(tr("fit %1 (else held at its start value)").arg(paramTitle(n)));
        free_[n] = c;
        fg->addWidget(c, k / 3, k % 3);  // three per row: fits the panel's width
        ++k;
    }
    setFreeParameters({"mu", "eta", "Dc", "vc", "epsT"});
    form->addRow(tr("Free"), freeBox);
}

void IdentifyFitTab::buildLossAndSplit(QFormLayout* form) {
    auto* lossRow = new QHBoxLayout;
    loss_ = new QComboBox(this);
    loss_->addItem(tr("none (least squares)"), int(LossKind::None));
    loss_->addItem(tr("Huber"), int(LossKind::Huber));
    loss_->addItem(tr("Cauchy"), int(LossKind::Cauchy));
    lossScale_ = new QDoubleSpinBox(this);
    lossScale_->setRange(1e-3, 1e3);
    lossScale_->setDecimals(3);
    lossScale_->setValue(1.0);
    lossScale_->setPrefix(tr("scale "));
    lossRow->addWidget(loss_, 1);
    lossRow->addWidget(lossScale_);
    form->addRow(tr("Robust loss"), lossRow);
    auto* splitRow = new QHBoxLayout;
    split_ = new QCheckBox(tr("hold out the end of every run"), this);
    splitFraction_ = new QDoubleSpinBox(this);
    splitFraction_->setRange(0.1, 0.95);
    splitFraction_->setSingleStep(0.05);
    splitFraction_->setValue(0.7);
    splitFraction_->setPrefix(tr("fit first "));
    splitFraction_->setEnabled(false);
    splitRow->addWidget(split_, 1);
    splitRow->addWidget(splitFraction_);
    form->addRow(tr("Validation"), splitRow);
    connect(split_, &QCheckBox::toggled, splitFraction_, &QWidget::setEnabled);
}

void IdentifyFitTab::buildSolver(QFormLayout* form) {
    auto* solverRow = new QHBoxLayout;
    multistarts_ = new QSpinBox(this);
    multistarts_->setRange(1, 50);
    multistarts_->setValue(3);
    multistarts_->setPrefix(tr("starts "));
    maxIterations_ = new QSpinBox(this);
    maxIterations_->setRange(1, 1000);
    maxIterations_->setValue(40);
    maxIterations_->setPrefix(tr("iterations "));
    solverRow->addWidget(multistarts_);
    solverRow->addWidget(maxIterations_);
    solverRow->addStretch(1);
    form->addRow(tr("Solver"), solverRow);
    jackknife_ = new QCheckBox(tr("jackknife over runs"), this);
    jackknife_->setToolTip(tr("repeat the whole fit leaving each run out (3 or more runs): standard error = the larger "
                              "of the Jacobian and the jackknife value; honest where the cost has several minima, K more fits"));
    form->addRow(tr("Std. errors"), jackknife_);
}

void IdentifyFitTab::setModel(const QString& model) {
    const int i = model_->findData(model);
    if (i >= 0) model_->setCurrentIndex(i);
}

void IdentifyFitTab::setFreeParameters(const QStringList& names) {
    for (auto& [n, box] : free_) box->setChecked(names.contains(QString::fromStdString(n)));
}

void IdentifyFitTab::setMultistarts(int n) { multistarts_->setValue(n); }

void IdentifyFitTab::setMaxIterations(int n) { maxIterations_->setValue(n); }

void IdentifyFitTab::setTimeSplit(double fraction) {
    split_->setChecked(fraction > 0);
    if (fraction > 0) splitFraction_->setValue(fraction);
}

void IdentifyFitTab::fillRequest(FitRequest& r) const {
    const QString m = model_->currentData().toString();
    r.laws = {LawKind::RateState};
    if (m == "both") r.laws = {LawKind::RateState, LawKind::Coulomb};
    else parseLawKind(m.toStdString(), r.laws[0]);
    r.settings.free.clear();
    for (const std::string& n : fitParams())
        if (free_.at(n)->isChecked()) r.settings.free.push_back(n);
    r.settings.loss = static_cast<LossKind>(loss_->currentData().toInt());
    r.settings.lossScale = lossScale_->value();
    r.settings.multistarts = multistarts_->value();
    r.settings.maxIterations = maxIterations_->value();
    r.settings.jackknife = jackknife_->isChecked();
    r.splitTime = split_->isChecked() ? splitFraction_->value() : 0.0;
}

// --- outcome -------------------------------------------------------------------------------

void IdentifyFitTab::showOutcome(const FitOutcome& o) {
    const double s = o.elapsed_ms / 1000.0;
    setProgress(1.0);
    QStringList summary;
    for (const LawFit& lf : o.fits)
        summary << (std::isfinite(lf.fit.validationNrmse)
                        ? tr("%1: fit NRMSE %2, validation %3").arg(lawName(lf.law), formatNrmse(lf.fit.fitNrmse), formatNrmse(lf.fit.validationNrmse))
                        : tr("%1: fit NRMSE %2").arg(lawName(lf.law), formatNrmse(lf.fit.fitNrmse)));
    setStatus(tr("Done in %1 s. %2").arg(s, 0, 'f', 1).arg(summary.join(QStringLiteral("; "))));
    showParameters(o);
    showIdentifiability(o);
    showRuns(o);
}

// One row per name over all laws, value ± stderr in each law's column.
void IdentifyFitTab::showParameters(const FitOutcome& o) {
    std::vector<std::string> names;
    for (const LawFit& lf : o.fits)
        for (const auto& n : lf.fit.fit.names)
            if (std::find(names.begin(), names.end(), n) == names.end()) names.push_back(n);
    params_->setRowCount(static_cast<int>(names.size()));
    for (size_t i = 0; i < names.size(); ++i) {
        const int row = static_cast<int>(i);
        setCell(params_, row, 0, paramTitle(names[i]));
        for (int col = 1; col <= lawCount(); ++col) setCell(params_, row, col, QStringLiteral(""));
        for (const LawFit& lf : o.fits) {
            const int col = 1 + static_cast<int>(lf.law);
            const auto& f = lf.fit.fit;
            for (size_t j = 0; j < f.names.size(); ++j) {
                if (f.names[j] != names[i]) continue;
                const bool isFree = j < f.free.size() && f.free[j];
                setCell(params_, row, col, isFree ? formatEstimate(f.values[j], f.stderrs[j]) : formatEstimate(f.values[j], 0.0) + tr(" (fixed)"));
            }
        }
    }
    for (LawKind law : allLaws())
        params_->setColumnHidden(1 + static_cast<int>(law),
                                 std::none_of(o.fits.begin(), o.fits.end(), [law](const LawFit& l) { return l.law == law; }));
    params_->resizeColumnsToContents();
    params_->horizontalHeader()->setStretchLastSection(true);
    fitHeight(params_, 5);
}

void IdentifyFitTab::showIdentifiability(const FitOutcome& o) {
    QStringList warnings;
    bool bad = false;
    for (const LawFit& lf : o.fits) {
        const auto& f = lf.fit.fit;
        QString text = QString::fromStdString(f.identifiabilityMessage);
        // Strong correlations among the free parameters (|r| > 0.95) deserve a line of their own.
        QStringList pairs;
        const size_t p = f.freeNames.size();
        for (size_t a = 0; a < p && f.correlation.size() == p * p; ++a)
            for (size_t b = a + 1; b < p; ++b)
                if (std::abs(f.correlation[a * p + b]) > 0.95)
                    pairs << QStringLiteral("%1–%2 (r = %3)").arg(paramTitle(f.freeNames[a]).section(' ', 0, 0),
                                                                  paramTitle(f.freeNames[b]).section(' ', 0, 0))
                                 .arg(f.correlation[a * p + b], 0, 'f', 3);
        if (!pairs.isEmpty()) text += tr("; strongly correlated: %1").arg(pairs.join(", "));
        if (!lf.fit.stderrWarning.empty()) text += "; " + QString::fromStdString(lf.fit.stderrWarning);
        bad = bad || !f.identifiable || !pairs.isEmpty() || !lf.fit.stderrWarning.empty();
        warnings << QStringLiteral("<b>%1</b>: %2").arg(lawName(lf.law), text.toHtmlEscaped());
    }
    identifiability_->setText(warnings.join("<br>"));
    identifiability_->setStyleSheet(bad ? "QLabel { color: #9a5b00; }" : "QLabel { color: #2a6b2a; }");
}

void IdentifyFitTab::showRuns(const FitOutcome& o) {
    const auto& first = o.fits.front().fit.runs;
    runs_->setRowCount(static_cast<int>(first.size()));
    for (size_t i = 0; i < first.size(); ++i) {
        const int row = static_cast<int>(i);
        setCell(runs_, row, 0, QString::fromStdString(QFileInfo(QString::fromStdString(first[i].file)).fileName().toStdString()));
        setCell(runs_, row, 1, QString::fromStdString(first[i].role));
        setCell(runs_, row, 2, std::isfinite(first[i].rms_N) ? QString::number(first[i].rms_N, 'g', 4) : QStringLiteral("–"));
        for (int col = 3; col < 3 + lawCount(); ++col) setCell(runs_, row, col, QString());
        for (const LawFit& lf : o.fits) {
            if (i >= lf.fit.runs.size()) continue;
            const RunScore& r = lf.fit.runs[i];
            setCell(runs_, row, 3 + static_cast<int>(lf.law), r.ok ? formatNrmse(r.nrmse) : tr("failed"),
                    QString::fromStdString(r.message));
        }
    }
    for (int k = 0; k < lawCount(); ++k) runs_->setColumnHidden(3 + k, params_->isColumnHidden(1 + k));
    runs_->resizeColumnsToContents();
    fitHeight(runs_, 3);
}

}  // namespace stickslip::gui
