#include "sweep_dialogs.hpp"

#include <QComboBox>
#include <QDialogButtonBox>
#include <QDoubleSpinBox>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QLabel>
#include <QProgressBar>
#include <QPushButton>
#include <QSpinBox>
#include <QVBoxLayout>

#include "param_specs.hpp"
#include "simulation_controller.hpp"

namespace stickslip::gui {

namespace {

// Keys worth sweeping (control and law parameters, not the integration ones).
QComboBox* keyBox(QWidget* parent, const QString& initial) {
    auto* box = new QComboBox(parent);
    for (const auto& s : parameterSpecs()) {
        if (s.group == ParamGroup::Integration || s.key == "phase") continue;
        box->addItem(paramScale(s.key).title, s.key);
    }
    box->setCurrentIndex(box->findData(initial));
    return box;
}

QDoubleSpinBox* valueBox(QWidget* parent, double v) {
    auto* b = new QDoubleSpinBox(parent);
    b->setDecimals(5);
    b->setRange(-1e9, 1e9);
    b->setStepType(QAbstractSpinBox::AdaptiveDecimalStepType);
    b->setValue(v);
    return b;
}

QSpinBox* intBox(QWidget* parent, int lo, int hi, int v) {
    auto* b = new QSpinBox(parent);
    b->setRange(lo, hi);
    b->setValue(v);
    return b;
}

double scaleOf(const QComboBox* key) { return paramScale(key->currentData().toString()).factor; }

QString seconds(double ms) { return QStringLiteral("%1 s").arg(ms / 1000.0, 0, 'f', 2); }

// The part every long-running dialog shares below its form: progress bar, status line and
// Run / Cancel / Close (Close hides the dialog; Cancel starts disabled).
struct RunControls {
    QProgressBar* progress;
    QLabel* status;
    QPushButton* run;
    QPushButton* cancel;
};

RunControls addRunControls(QDialog* dialog, QFormLayout* form, const QString& statusText, const QString& cancelText) {
    RunControls c;
    c.progress = new QProgressBar(dialog);
    c.progress->setRange(0, 1000);
    c.status = new QLabel(statusText, dialog);
    c.status->setWordWrap(true);
    c.run = new QPushButton(QObject::tr("Run"), dialog);
    c.cancel = new QPushButton(cancelText, dialog);
    c.cancel->setEnabled(false);
    auto* close = new QPushButton(QObject::tr("Close"), dialog);
    auto* buttons = new QHBoxLayout;
    buttons->addStretch(1);
    buttons->addWidget(c.run);
    buttons->addWidget(c.cancel);
    buttons->addWidget(close);
    auto* top = new QVBoxLayout(dialog);
    top->addLayout(form);
    top->addWidget(c.progress);
    top->addWidget(c.status);
    top->addLayout(buttons);
    QObject::connect(close, &QPushButton::clicked, dialog, &QDialog::hide);
    return c;
}

}  // namespace

SweepDialog::SweepDialog(SimulationController* controller, SettingsSource current, QWidget* parent)
    : QDialog(parent), controller_(controller), current_(std::move(current)) {
    setWindowTitle(tr("Bifurcation sweep"));
    setObjectName("sweepDialog");
    auto* form = new QFormLayout;
    key_ = keyBox(this, "A");
    from_ = valueBox(this, 0.1);
    to_ = valueBox(this, 5.0);
    steps_ = intBox(this, 1, 100000, 50);
    direction_ = new QComboBox(this);
    direction_->addItem(tr("up"), int(SweepDirection::Up));
    direction_->addItem(tr("down"), int(SweepDirection::Down));
    direction_->addItem(tr("up and down (overlaid)"), int(SweepDirection::Both));
    direction_->setCurrentIndex(2);
    settle_ = intBox(this, 0, 1000000, 50);
    sample_ = intBox(this, 1, 1000000, 50);
    form->addRow(tr("Parameter"), key_);
    form->addRow(tr("From (display unit)"), from_);
    form->addRow(tr("To"), to_);
    form->addRow(tr("Values"), steps_);
    form->addRow(tr("Direction"), direction_);
    form->addRow(tr("Settle cycles per value"), settle_);
    form->addRow(tr("Sampled cycles per value"), sample_);
    const RunControls rc = addRunControls(this, form, tr("The state is carried from one value to the next (continuation)."),
                                          tr("Cancel sweep"));
    progress_ = rc.progress;
    progress_->setValue(0);
    status_ = rc.status;
    runButton_ = rc.run;
    cancelButton_ = rc.cancel;

    connect(runButton_, &QPushButton::clicked, this, &SweepDialog::start);
    connect(cancelButton_, &QPushButton::clicked, this, &SweepDialog::cancelSweep);
    connect(controller_, &SimulationController::sweepProgress, this,
            [this](double f) { progress_->setValue(static_cast<int>(f * 1000.0)); });
    connect(controller_, &SimulationController::sweepFinished, this, &SweepDialog::onFinished);
}

SweepOptions SweepDialog::options() const {
    SweepOptions o;
    o.key = key_->currentData().toString().toStdString();
    const double sc = scaleOf(key_);
    o.from = from_->value() / sc;
    o.to = to_->value() / sc;
    o.steps = steps_->value();
    o.direction = static_cast<SweepDirection>(direction_->currentData().toInt());
    o.mode = SweepMode::Continuation;
    o.settleCycles = settle_->value();
    o.sampleCycles = sample_->value();
    return o;
}

void SweepDialog::setOptions(const SweepOptions& o) {
    key_->setCurrentIndex(key_->findData(QString::fromStdString(o.key)));
    const double sc = scaleOf(key_);
    from_->setValue(o.from * sc);
    to_->setValue(o.to * sc);
    steps_->setValue(o.steps);
    direction_->setCurrentIndex(direction_->findData(int(o.direction)));
    settle_->setValue(static_cast<int>(o.settleCycles));
    sample_->setValue(static_cast<int>(o.sampleCycles));
}

QString SweepDialog::statusText() const { return status_->text(); }

void SweepDialog::start() {
    const ModelSettings s = current_();
    const SweepOptions o = options();
    const ParamIssues issues = o.validate(s.params);
    if (!issues.empty()) {
        status_->setText(QString::fromStdString(formatIssues(issues)));
        return;
    }
    progress_->setValue(0);
    status_->setText(tr("Running…"));
    runButton_->setEnabled(false);
    cancelButton_->setEnabled(true);
    controller_->startSweep(s, o);
}

void SweepDialog::cancelSweep() {
    controller_->cancel(JobKind::Sweep);
    status_->setText(tr("Cancelling…"));
}

void SweepDialog::onFinished(const SweepOutcome& o) {
    runButton_->setEnabled(true);
    cancelButton_->setEnabled(false);
    size_t points = 0;
    QStringList failures;
    for (const auto& [law, r] : o.results) {
        points += r.points.size();
        if (r.status == RunStatus::Failed) failures << QString::fromStdString(r.message);
    }
    if (!failures.isEmpty()) status_->setText(tr("Failed: %1").arg(failures.join("; ")));
    else if (o.cancelled()) status_->setText(tr("Cancelled after %1 values (%2).").arg(points).arg(seconds(o.elapsed_ms)));
    else {
        progress_->setValue(1000);
        status_->setText(tr("Done: %1 values in %2.").arg(points).arg(seconds(o.elapsed_ms)));
    }
}

MapDialog::MapDialog(SimulationController* controller, SettingsSource current, QWidget* parent)
    : QDialog(parent), controller_(controller), current_(std::move(current)) {
    setWindowTitle(tr("Periodicity map"));
    setObjectName("mapDialog");
    auto* form = new QFormLayout;
    key1_ = keyBox(this, "A");
    from1_ = valueBox(this, 0.1);
    to1_ = valueBox(this, 3.0);
    steps1_ = intBox(this, 1, 2000, 20);
    key2_ = keyBox(this, "f");
    from2_ = valueBox(this, 3.0);
    to2_ = valueBox(this, 10.0);
    steps2_ = intBox(this, 1, 2000, 15);
    settle_ = intBox(this, 0, 1000000, 50);
    sample_ = intBox(this, 1, 1000000, 64);
    form->addRow(tr("x parameter"), key1_);
    form->addRow(tr("x from"), from1_);
    form->addRow(tr("x to"), to1_);
    form->addRow(tr("x values"), steps1_);
    form->addRow(tr("y parameter"), key2_);
    form->addRow(tr("y from"), from2_);
    form->addRow(tr("y to"), to2_);
    form->addRow(tr("y values"), steps2_);
    form->addRow(tr("Settle cycles per cell"), settle_);
    form->addRow(tr("Sampled cycles per cell"), sample_);
    const RunControls rc =
        addRunControls(this, form, tr("Every cell starts from rest; cells run in parallel."), tr("Cancel map"));
    progress_ = rc.progress;
    status_ = rc.status;
    runButton_ = rc.run;
    cancelButton_ = rc.cancel;
    connect(runButton_, &QPushButton::clicked, this, &MapDialog::start);
    connect(cancelButton_, &QPushButton::clicked, this, &MapDialog::cancelMap);
    connect(controller_, &SimulationController::mapProgress, this,
            [this](double f) { progress_->setValue(static_cast<int>(f * 1000.0)); });
    connect(controller_, &SimulationController::mapFinished, this, &MapDialog::onFinished);
}

MapOptions MapDialog::options() const {
    MapOptions o;
    o.key1 = key1_->currentData().toString().toStdString();
    o.key2 = key2_->currentData().toString().toStdString();
    o.from1 = from1_->value() / scaleOf(key1_);
    o.to1 = to1_->value() / scaleOf(key1_);
    o.steps1 = steps1_->value();
    o.from2 = from2_->value() / scaleOf(key2_);
    o.to2 = to2_->value() / scaleOf(key2_);
    o.steps2 = steps2_->value();
    o.settleCycles = settle_->value();
    o.sampleCycles = sample_->value();
    return o;
}

void MapDialog::start() {
    const ModelSettings s = current_();
    const MapOptions o = options();
    const ParamIssues issues = o.validate(s.params);
    if (!issues.empty()) {
        status_->setText(QString::fromStdString(formatIssues(issues)));
        return;
    }
    progress_->setValue(0);
    status_->setText(tr("Running…"));
    runButton_->setEnabled(false);
    cancelButton_->setEnabled(true);
    controller_->startMap(s, o);
}

void MapDialog::cancelMap() {
    controller_->cancel(JobKind::Map);
    status_->setText(tr("Cancelling…"));
}

void MapDialog::onFinished(const MapOutcome& o) {
    runButton_->setEnabled(true);
    cancelButton_->setEnabled(false);
    size_t done = 0;
    for (auto d : o.map.done) done += d ? 1 : 0;
    if (o.map.status == RunStatus::Failed) status_->setText(tr("Failed: %1").arg(QString::fromStdString(o.map.message)));
    else if (o.map.status == RunStatus::Cancelled)
        status_->setText(tr("Cancelled: %1 of %2 cells (%3).").arg(done).arg(o.map.done.size()).arg(seconds(o.elapsed_ms)));
    else {
        progress_->setValue(1000);
        status_->setText(tr("Done: %1 cells in %2.").arg(done).arg(seconds(o.elapsed_ms)));
    }
}

}  // namespace stickslip::gui
