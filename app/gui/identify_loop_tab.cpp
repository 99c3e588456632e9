#include "identify_loop_tab.hpp"

#include <QCheckBox>
#include <QDoubleSpinBox>
#include <QFormLayout>
#include <QGridLayout>
#include <QHBoxLayout>
#include <QLabel>
#include <QListWidget>
#include <QSpinBox>
#include <QTableWidget>
#include <QVBoxLayout>

#include "core/identify/effects/registry.hpp"
#include "identify_tables.hpp"
#include "self_test_view.hpp"

namespace stickslip::gui {

using namespace stickslip::identify;

namespace {

const char* kLawParams[] = {"mu", "C1", "eta", "Dc", "vc", "epsT", "r"};

}  // namespace

IdentifyLoopTab::IdentifyLoopTab(QWidget* parent) : IdentifyJobTab(parent) {
    auto* w = this;
    auto* v = new QVBoxLayout(w);
    auto* intro = new QLabel(tr("Fit the baseline law, look at what its residual still contains, add the catalogue effect "
                                "that explains it best (BIC, then held-out error), repeat."), w);
    intro->setWordWrap(true);
    intro->setStyleSheet("color: #555;");
    v->addWidget(intro);
    auto* form = new QFormLayout;
    buildFreeLaw(form);
    buildCandidates(form);
    buildLoopLimits(form);
    v->addLayout(form);

    selfTest_ = new SelfTestView(w);
    v->addWidget(selfTest_);

    v->addLayout(makeRunRow(tr("Identify"), tr("Load runs, then Identify.")));
    v->addWidget(statusLabel());
    unexplained_ = new QLabel(w);
    unexplained_->setWordWrap(true);
    v->addWidget(unexplained_);
    buildTables(v);
    v->addLayout(makeExportRow());
    v->addStretch(1);
}

void IdentifyLoopTab::buildFreeLaw(QFormLayout* form) {
    auto* freeBox = new QWidget(this);
    auto* fg = new QGridLayout(freeBox);
    fg->setContentsMargins(0, 0, 0, 0);
    int k = 0;
    for (const char* n : kLawParams) {
        auto* c = new QCheckBox(paramTitle(n).section(' ', 0, 0), freeBox);
        free_[n] = c;
        fg->addWidget(c, k / 4, k % 4);
        ++k;
    }
    const IdentifyOptions defaults;  // the same baseline as stickslip-cli identify
    QStringList names;
    for (const std::string& n : defaults.freeLaw) names << QString::fromStdString(n);
    setIdentifyFree(names);
    form->addRow(tr("Free law"), freeBox);
}

void IdentifyLoopTab::buildCandidates(QFormLayout* form) {
    candidateList_ = new QListWidget(this);
    for (const EffectInfo& e : effectCatalogue()) {
        auto* it = new QListWidgetItem(QString::fromStdString(e.name), candidateList_);
        it->setFlags(Qt::ItemIsUserCheckable | Qt::ItemIsEnabled);
        it->setCheckState(Qt::Checked);
        it->setToolTip(QString::fromStdString(e.description + "\n\nSignature: " + e.signature));
    }
    candidateList_->setMaximumHeight(5 * 20 + 8);
    form->addRow(tr("Candidates"), candidateList_);
}

void IdentifyLoopTab::buildLoopLimits(QFormLayout* form) {
    auto* row = new QHBoxLayout;
    maxEffects_ = new QSpinBox(this);
    maxEffects_->setRange(1, 9);
    maxEffects_->setValue(3);
    maxEffects_->setPrefix(tr("at most "));
    maxEffects_->setSuffix(tr(" effects"));
    bicMargin_ = new QDoubleSpinBox(this);
    bicMargin_->setRange(0, 1000);
    bicMargin_->setObjectName("bicMargin");
    bicMargin_->setToolTip(tr("Penalised-fit test: an effect must lower the BIC by more than this margin. 0: any "
                              "decrease."));
    // The box shows the test itself, ΔBIC < −margin; at margin 0 that is "ΔBIC < 0.00", not "< −0.00".
    const auto showTest = [this](double m) { bicMargin_->setPrefix(m > 0 ? tr("ΔBIC < −") : tr("ΔBIC < ")); };
    connect(bicMargin_, qOverload<double>(&QDoubleSpinBox::valueChanged), this, showTest);
    bicMargin_->setValue(IdentifyOptions{}.bicMargin);
    showTest(bicMargin_->value());
    // Selection test (2b): the relevance margin on the held-out gain (IdentifyOptions::minHeldOutGain).
    minHeldOutGain_ = new QDoubleSpinBox(this);
    minHeldOutGain_->setRange(0, 99);
    minHeldOutGain_->setDecimals(1);
    minHeldOutGain_->setValue(100.0 * IdentifyOptions{}.minHeldOutGain);
    minHeldOutGain_->setPrefix(tr("held-out gain ≥ "));
    minHeldOutGain_->setSuffix(tr(" %"));
    minHeldOutGain_->setToolTip(tr("Relevance margin: an effect must also lower the held-out MSE by at least this much on "
                                   "average over the held-out runs. A consistent gain smaller than this is a sliver of "
                                   "structure the candidate does not describe. 0: significance alone."));
    multistarts_ = new QSpinBox(this);
    multistarts_->setRange(1, 20);
    multistarts_->setValue(2);
    multistarts_->setPrefix(tr("starts "));
    row->addWidget(maxEffects_);
    row->addWidget(bicMargin_);
    row->addWidget(minHeldOutGain_);
    row->addWidget(multistarts_);
    form->addRow(tr("Loop"), row);
}

void IdentifyLoopTab::buildTables(QVBoxLayout* v) {
    beforeAfter_ = makeTable({tr("Model"), tr("fit NRMSE"), tr("held-out NRMSE")}, this);
    v->addWidget(new QLabel(tr("<b>Error before and after</b>"), this));
    v->addWidget(beforeAfter_);
    baselineBounds_ = new QLabel(this);
    baselineBounds_->setWordWrap(true);
    baselineBounds_->hide();
    v->addWidget(baselineBounds_);
    fitHeight(beforeAfter_, 2);
    effects_ = makeTable({tr("Effect added"), tr("ΔBIC"), tr("held-out"), tr("Parameters")}, this);
    v->addWidget(new QLabel(tr("<b>Effects added</b> (parameters ± 1σ)"), this));
    v->addWidget(effects_);
    fitHeight(effects_, 1);
    candidates_ = makeTable({tr("Candidate"), tr("Round"), tr("ΔBIC"), tr("fit NRMSE"), tr("Verdict")}, this);
    v->addWidget(new QLabel(tr("<b>Candidates</b>"), this));
    v->addWidget(candidates_);
    fitHeight(candidates_, 4);
    timeline_ = makeTable({tr("Stage"), tr("start [s]"), tr("wall [s]"), tr("fits")}, this);
    v->addWidget(new QLabel(tr("<b>Where the time went</b>"), this));
    v->addWidget(timeline_);
    fitHeight(timeline_, 4);
}

void IdentifyLoopTab::setIdentifyFree(const QStringList& names) {
    for (auto& [n, box] : free_) box->setChecked(names.contains(QString::fromStdString(n)));
}

void IdentifyLoopTab::setCandidates(const QStringList& names) {
    for (int i = 0; i < candidateList_->count(); ++i) {
        QListWidgetItem* it = candidateList_->item(i);
        it->setCheckState(names.isEmpty() || names.contains(it->text()) ? Qt::Checked : Qt::Unchecked);
    }
}

void IdentifyLoopTab::setMaxEffects(int n) { maxEffects_->setValue(n); }

void IdentifyLoopTab::setMultistarts(int n) { multistarts_->setValue(n); }

bool IdentifyLoopTab::anyCandidate() const {
    bool any = false;
    for (int i = 0; i < candidateList_->count(); ++i) any = any || candidateList_->item(i)->checkState() == Qt::Checked;
    return any;
}

void IdentifyLoopTab::fillRequest(IdentifyRequest& r) const {
    r.options.freeLaw.clear();
    for (const char* n : kLawParams)
        if (free_.at(n)->isChecked()) r.options.freeLaw.push_back(n);
    bool all = true;
    std::vector<std::string> cands;
    for (int i = 0; i < candidateList_->count(); ++i) {
        if (candidateList_->item(i)->checkState() == Qt::Checked) cands.push_back(candidateList_->item(i)->text().toStdString());
        else all = false;
    }
    if (!all) r.options.candidates = cands;
    r.options.maxEffects = maxEffects_->value();
    r.options.bicMargin = bicMargin_->value();
    r.options.minHeldOutGain = minHeldOutGain_->value() / 100.0;
    r.options.multistarts = multistarts_->value();
}

// --- outcome -------------------------------------------------------------------------------

void IdentifyLoopTab::clearUnexplained() { unexplained_->clear(); }

void IdentifyLoopTab::showOutcome(const IdentifyOutcome& o) {
    const double s = o.elapsed_ms / 1000.0;
    const IdentifyResult& r = o.result;
    setProgress(1.0);
    QStringList added;
    for (const AddedEffect& e : r.effectsAdded) added << QString::fromStdString(e.name);
    setStatus(tr("Done in %1 s (%2 fits, %3 set-up). Effects added: %4.")
                  .arg(s, 0, 'f', 1).arg(r.fits).arg(QString::fromStdString(r.setup),
                       added.isEmpty() ? tr("none") : added.join(", ")));
    // The resolution warning is part of the unexplained reason when there is one; else on its own.
    const QString resolution = QString::fromStdString(lawResolutionText(r.lawResolution));
    const bool warn = r.unexplained || !resolution.isEmpty();
    if (r.unexplained)
        unexplained_->setText(tr("<b>Unexplained structure remains</b>: %1").arg(QString::fromStdString(r.unexplainedReason).toHtmlEscaped()));
    else if (!resolution.isEmpty())
        unexplained_->setText(tr("<b>Numerical resolution</b>: %1").arg(resolution.toHtmlEscaped()));
    else
        unexplained_->setText(tr("<b>No unexplained structure</b>: what is left of the residual is not predicted from run to "
                                 "run by the runs' own state."));
    unexplained_->setStyleSheet(warn ? "QLabel { color: #9a5b00; }" : "QLabel { color: #2a6b2a; }");
    showBeforeAfter(r, added);
    showEffects(r);
    showCandidates(r);
    showTimeline(r);
    selfTest_->show(r.selfTest);
}

void IdentifyLoopTab::showBeforeAfter(const IdentifyResult& r, const QStringList& added) {
    beforeAfter_->setRowCount(2);
    setCell(beforeAfter_, 0, 0, tr("before (baseline)"), QString::fromStdString(r.baselineNote));
    // A baseline parameter on its bound, what a second start made of it, and whether a baseline
    // adopted later (a restart, the backward check) left it.
    QStringList bounds;
    for (const BoundVerdict& b : r.baselineBounds) bounds << boundSentence(b);
    baselineBounds_->setText(bounds.join(" "));
    baselineBounds_->setVisible(!bounds.isEmpty());
    setCell(beforeAfter_, 0, 1, formatNrmse(r.before.fitNrmse));
    setCell(beforeAfter_, 0, 2, formatNrmse(r.before.validationNrmse));
    setCell(beforeAfter_, 1, 0, added.isEmpty() ? tr("after (unchanged)") : tr("after (+ %1)").arg(added.join(", ")));
    setCell(beforeAfter_, 1, 1, formatNrmse(r.after.fitNrmse));
    setCell(beforeAfter_, 1, 2, formatNrmse(r.after.validationNrmse));
    beforeAfter_->resizeColumnsToContents();
    fitHeight(beforeAfter_, 2);
}

void IdentifyLoopTab::showEffects(const IdentifyResult& r) {
    effects_->setRowCount(static_cast<int>(r.effectsAdded.size()));
    for (size_t i = 0; i < r.effectsAdded.size(); ++i) {
        const AddedEffect& e = r.effectsAdded[i];
        const int row = static_cast<int>(i);
        QStringList ps;
        for (const ParamEstimate& p : e.params) ps << QStringLiteral("%1 = %2").arg(QString::fromStdString(p.name), formatEstimate(p.value, p.stderr_));
        QStringList why;
        for (const SignalCorrelation& c : e.pointedBy) why << QStringLiteral("%1 (r = %2)").arg(QString::fromStdString(c.signal)).arg(c.correlation, 0, 'f', 2);
        setCell(effects_, row, 0, QString::fromStdString(e.name), why.isEmpty() ? QString() : tr("pointed to by ") + why.join(", "));
        setCell(effects_, row, 1, QString::number(e.deltaBic, 'f', 1));
        // The law-step check (AddedEffect::LawStepGain) as the held-out cell's tooltip.
        setCell(effects_, row, 2, QStringLiteral("%1 → %2").arg(formatNrmse(e.heldOutBefore), formatNrmse(e.heldOutAfter)),
                QString::fromStdString(lawStepText(e)));
        setCell(effects_, row, 3, ps.join("; "), ps.join("\n"));
        effects_->item(row, 3)->setTextAlignment(Qt::AlignLeft | Qt::AlignVCenter);
    }
    effects_->resizeColumnsToContents();
    fitHeight(effects_, 1);
}

void IdentifyLoopTab::showCandidates(const IdentifyResult& r) {
    candidates_->setRowCount(static_cast<int>(r.candidates.size()));
    for (size_t i = 0; i < r.candidates.size(); ++i) {
        const CandidateScore& c = r.candidates[i];
        const int row = static_cast<int>(i);
        QStringList ps;
        for (const ParamEstimate& p : c.params) ps << QStringLiteral("%1 = %2").arg(QString::fromStdString(p.name), formatEstimate(p.value, p.stderr_));
        setCell(candidates_, row, 0, QString::fromStdString(c.name), ps.join("\n"));
        setCell(candidates_, row, 1, QString::number(c.round));
        setCell(candidates_, row, 2, c.applicable ? QString::number(c.deltaBic, 'f', 1) : QStringLiteral("–"));
        setCell(candidates_, row, 3, c.applicable ? formatNrmse(c.fitNrmse) : QStringLiteral("–"));
        const QString verdict = QString::fromStdString(verdictOf(c));
        setCell(candidates_, row, 4, verdict, verdict);
        candidates_->item(row, 4)->setTextAlignment(Qt::AlignLeft | Qt::AlignVCenter);
        if (c.accepted) candidates_->item(row, 0)->setForeground(QColor(44, 120, 44));
    }
    candidates_->resizeColumnsToContents();
    fitHeight(candidates_, 4);
}

// The stages the loop's progress named (the baseline, each candidate of each round, restarts,
// noise nulls, held-out checks, the self-test, the report): the same rows as the HTML report's.
void IdentifyLoopTab::showTimeline(const IdentifyResult& r) {
    timeline_->setRowCount(static_cast<int>(r.timeline.size()));
    for (size_t i = 0; i < r.timeline.size(); ++i) {
        const IdentifyStage& st = r.timeline[i];
        const int row = static_cast<int>(i);
        setCell(timeline_, row, 0, QString::fromStdString(st.label));
        timeline_->item(row, 0)->setTextAlignment(Qt::AlignLeft | Qt::AlignVCenter);
        setCell(timeline_, row, 1, QString::number(st.start_s, 'f', 1));
        setCell(timeline_, row, 2, QString::number(st.end_s - st.start_s, 'f', 1));
        setCell(timeline_, row, 3, QString::number(st.fits));
    }
    timeline_->resizeColumnsToContents();
    fitHeight(timeline_, 6);
}

}  // namespace stickslip::gui
