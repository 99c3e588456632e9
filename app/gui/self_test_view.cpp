#include "self_test_view.hpp"

#include <QCheckBox>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QLabel>
#include <QLineEdit>
#include <QRegularExpression>
#include <QSpinBox>
#include <QTableWidget>
#include <QVBoxLayout>

using namespace stickslip::identify;

namespace {

void cell(QTableWidget* t, int row, int col, const QString& text, const QString& tip = {}) {
    auto* item = new QTableWidgetItem(text);
    if (!tip.isEmpty()) item->setToolTip(tip);
    item->setTextAlignment((col > 1 ? Qt::AlignRight : Qt::AlignLeft) | Qt::AlignVCenter);
    t->setItem(row, col, item);
}

}  // namespace

SelfTestView::SelfTestView(QWidget* parent) : QWidget(parent) {
    auto* v = new QVBoxLayout(this);
    v->setContentsMargins(0, 0, 0, 0);
    auto* row = new QHBoxLayout;
    enabled_ = new QCheckBox(tr("Recovery self-test"), this);
    enabled_->setToolTip(tr("Inject each candidate effect into replicas of these runs (fitted baseline + effect + noise of the "
                            "baseline residual) and count how often the selection finds it, names another effect, or finds "
                            "one where there is none."));
    replicas_ = new QSpinBox(this);
    replicas_->setRange(1, 10000);
    replicas_->setValue(20);
    replicas_->setSuffix(tr(" replicas"));
    levels_ = new QLineEdit(QStringLiteral("0.25, 0.5, 1"), this);
    levels_->setToolTip(tr("Signal levels: RMS of the injected effect over the RMS of the baseline residual, one row each"));
    row->addWidget(enabled_);
    row->addWidget(replicas_);
    row->addWidget(new QLabel(tr("levels"), this));
    row->addWidget(levels_, 1);
    v->addLayout(row);
    auto* row2 = new QHBoxLayout;
    stated_ = new QLineEdit(this);
    stated_->setPlaceholderText(tr("e.g. stick_healing=0.0115 stick_healing.tc_s=0.00157"));
    stated_->setToolTip(tr("Effects stated in full, as an answer key or a paper gives them: EFFECT=VALUE sets the size "
                           "parameter (SI units) and replaces the levels for that effect; EFFECT.PARAMETER=VALUE sets one of "
                           "its other parameters (default: its start). Separate items by spaces, commas or semicolons."));
    row2->addWidget(new QLabel(tr("stated"), this));
    row2->addWidget(stated_, 1);
    v->addLayout(row2);
    summary_ = new QLabel(this);
    summary_->setWordWrap(true);
    v->addWidget(summary_);
    table_ = new QTableWidget(0, 9, this);
    table_->setHorizontalHeaderLabels({tr("Effect"), tr("Size"), tr("SNR"), tr("visible"), tr("detected"), tr("confused"),
                                       tr("missed"), tr("Shape"), tr("Note")});
    table_->horizontalHeaderItem(2)->setToolTip(tr("RMS of the injected signal / RMS of the baseline residual"));
    table_->horizontalHeaderItem(3)->setToolTip(tr("The same for the part of the signal the baseline's refit cannot mimic"));
    table_->horizontalHeaderItem(7)->setToolTip(tr("The effect's other parameters as stated (blank: injected at their starts)"));
    table_->verticalHeader()->setVisible(false);
    table_->verticalHeader()->setDefaultSectionSize(22);
    table_->setEditTriggers(QAbstractItemView::NoEditTriggers);
    table_->setAlternatingRowColors(true);
    table_->horizontalHeader()->setStretchLastSection(true);
    table_->setMinimumHeight(120);
    table_->setVisible(false);
    v->addWidget(table_);
    auto sync = [this](bool on) {
        replicas_->setEnabled(on);
        levels_->setEnabled(on);
        stated_->setEnabled(on);
    };
    connect(enabled_, &QCheckBox::toggled, this, sync);
    sync(false);
}

void SelfTestView::setEnabledTest(bool on) { enabled_->setChecked(on); }
void SelfTestView::setLevels(const QString& text) { levels_->setText(text); }
void SelfTestView::setStated(const QString& text) { stated_->setText(text); }

bool SelfTestView::apply(IdentifyOptions& o, QString& why) const {
    o.selfTest = SelfTestOptions{};
    if (!enabled_->isChecked()) return true;
    o.selfTest.replicas = replicas_->value();
    o.selfTest.levels.clear();
    for (const QString& part : levels_->text().split(',', Qt::SkipEmptyParts)) {
        bool ok = false;
        const double l = part.trimmed().toDouble(&ok);
        if (!ok) {
            why = tr("Self-test level '%1' is not a number").arg(part.trimmed());
            return false;
        }
        o.selfTest.levels.push_back(l);
    }
    std::vector<std::string> items;
    for (const QString& part : stated_->text().split(QRegularExpression(QStringLiteral("[\\s,;]+")), Qt::SkipEmptyParts))
        items.push_back(part.toStdString());
    if (std::string e; !o.selfTest.parseStated(items, e)) {
        why = tr("Self-test, stated: %1").arg(QString::fromStdString(e));
        return false;
    }
    const std::string err = formatIssues(o.selfTest.validate());
    if (!err.empty()) {
        why = QString::fromStdString(err);
        return false;
    }
    return true;
}

void SelfTestView::show(const SelfTestResult& r) {
    table_->setVisible(r.ran);
    if (!r.ran) {
        summary_->clear();
        table_->setRowCount(0);
        return;
    }
    if (!r.ok) {
        summary_->setText(tr("Self-test: %1").arg(QString::fromStdString(r.message)));
        table_->setRowCount(0);
        return;
    }
    summary_->setText(tr("<b>Self-test</b>: false alarms on %1 replicas without an effect: %2. Noise RMS %3, n_eff %4. "
                         "Detection uses the ΔBIC and noise-null tests in the linearised refit (the held-out and size "
                         "tests are not applied: rates are upper bounds for the full loop).")
                          .arg(r.falseAlarmReplicas)
                          .arg(r.falseAlarms)
                          .arg(r.noiseRms, 0, 'g', 3)
                          .arg(r.neff, 0, 'f', 0));
    table_->setRowCount(static_cast<int>(r.rows.size()));
    for (size_t i = 0; i < r.rows.size(); ++i) {
        const SelfTestRow& w = r.rows[i];
        const int row = static_cast<int>(i);
        QStringList confused;
        for (const auto& [name, n] : w.confusedWith) confused << QStringLiteral("%1 ×%2").arg(QString::fromStdString(name)).arg(n);
        cell(table_, row, 0, QString::fromStdString(w.effect));
        cell(table_, row, 1, QStringLiteral("%1 %2").arg(w.size, 0, 'g', 4).arg(QString::fromStdString(w.unit)),
             QString::fromStdString(w.sizeParam));
        cell(table_, row, 2, QString::number(w.snr, 'f', 2));
        cell(table_, row, 3, QString::number(w.visibleSnr, 'f', 2));
        cell(table_, row, 4, QStringLiteral("%1/%2").arg(w.detected).arg(w.replicas));
        cell(table_, row, 5, QString::number(w.confused), confused.join(", "));
        cell(table_, row, 6, QString::number(w.missed));
        QStringList shape;
        for (const auto& [name, v] : w.shape) shape << QStringLiteral("%1 = %2").arg(QString::fromStdString(name)).arg(v, 0, 'g', 4);
        cell(table_, row, 7, shape.join(QStringLiteral(", ")));
        table_->item(row, 7)->setTextAlignment(Qt::AlignLeft | Qt::AlignVCenter);
        cell(table_, row, 8, QString::fromStdString(w.note), QString::fromStdString(w.note));
        table_->item(row, 8)->setTextAlignment(Qt::AlignLeft | Qt::AlignVCenter);
    }
    table_->resizeColumnsToContents();
    int h = table_->horizontalHeader()->height() + 4;
    for (int k = 0; k < table_->rowCount(); ++k) h += table_->rowHeight(k);
    table_->setMinimumHeight(std::min(std::max(h, 120), 420));
}
