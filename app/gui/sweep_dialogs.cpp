#include "sweep_dialogs.hpp"

#include <QCheckBox>
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

}  // namespace

RunDialog::RunDialog(SimulationController* controller, SettingsSource current, QWidget* parent)
    : QDialog(parent), controller_(controller), current_(std::move(current)) {}

void RunDialog::addRunControls(QFormLayout* form, const QString& statusText, const QString& cancelText) {
    progress_ = new QProgressBar(this);
    progress_->setRange(0, 1000);
    progress_->setValue(0);
    status_ = new QLabel(statusText, this);
    status_->setWordWrap(true);
    runButton_ = new QPushButton(tr("Run"), this);
    cancelButton_ = new QPushButton(cancelText, this);
    cancelButton_->setEnabled(false);
    auto* close = new QPushButton(tr("Close"), this);
    auto* buttons = new QHBoxLayout;
    buttons->addStretch(1);
    buttons->addWidget(runButton_);
    buttons->addWidget(cancelButton_);
    buttons->addWidget(close);
    auto* top = new QVBoxLayout(this);
    top->addLayout(form);
    top->addWidget(progress_);
    top->addWidget(status_);
    top->addLayout(buttons);
    connect(close, &QPushButton::clicked, this, &QDialog::hide);
    connect(runButton_, &QPushButton::clicked, this, &RunDialog::start);
    connect(cancelButton_, &QPushButton::clicked, this, &RunDialog::cancelRun);
}

void RunDialog::showProgress(double fraction) { progress_->setValue(static_cast<int>(fraction * 1000.0)); }

QString RunDialog::statusText() const { return status_->text(); }

bool RunDialog::beginRun(const ParamIssues& issues) {
    if (!issues.empty()) {
        status_->setText(QString::fromStdString(formatIssues(issues)));
        return false;
    }
    progress_->setValue(0);
    status_->setText(tr("Running…"));
    runButton_->setEnabled(false);
    cancelButton_->setEnabled(true);
    return true;
}

void RunDialog::requestCancel(JobKind kind) {
    controller_->cancel(kind);
    status_->setText(tr("Cancelling…"));
}

void RunDialog::endRun(const QString& failure, bool cancelled, const QString& cancelledText, const QString& doneText) {
    runButton_->setEnabled(true);
    cancelButton_->setEnabled(false);
    if (!failure.isEmpty()) status_->setText(tr("Failed: %1").arg(failure));
    else if (cancelled) status_->setText(cancelledText);
    else {
        progress_->setValue(1000);
        status_->setText(doneText);
    }
}

SweepDialog::SweepDialog(SimulationController* controller, SettingsSource current, QWidget* parent)
    : RunDialog(controller, std::move(current), parent) {
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
    concurrent_ = new QCheckBox(tr("Run both branches at once (down starts from rest at the top value)"), this);
    concurrent_->setToolTip(tr("About halves the wall time on two cores. Each branch still carries its state from value "
                               "to value, so hysteresis shows; only the down branch's starting state differs."));
    settle_ = intBox(this, 0, 1000000, 50);
    sample_ = intBox(this, 1, 1000000, 50);
    form->addRow(tr("Parameter"), key_);
    form->addRow(tr("From (display unit)"), from_);
    form->addRow(tr("To"), to_);
    form->addRow(tr("Values"), steps_);
    form->addRow(tr("Direction"), direction_);
    form->addRow(QString(), concurrent_);
    connect(direction_, qOverload<int>(&QComboBox::currentIndexChanged), this, [this] {
        concurrent_->setEnabled(static_cast<SweepDirection>(direction_->currentData().toInt()) == SweepDirection::Both);
    });
    form->addRow(tr("Settle cycles per value"), settle_);
    form->addRow(tr("Sampled cycles per value"), sample_);
    addRunControls(form, tr("The state is carried from one value to the next (continuation)."), tr("Cancel sweep"));
    connect(controller_, &SimulationController::sweepProgress, this, &SweepDialog::showProgress);
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
    o.concurrentBranches = o.direction == SweepDirection::Both && concurrent_->isChecked();
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
    concurrent_->setChecked(o.concurrentBranches);
    settle_->setValue(static_cast<int>(o.settleCycles));
    sample_->setValue(static_cast<int>(o.sampleCycles));
}

void SweepDialog::start() {
    const ModelSettings s = current_();
    const SweepOptions o = options();
    if (beginRun(o.validate(s.paramsFor(s.primaryLaw())))) controller_->startSweep(s, o);
}

void SweepDialog::cancelRun() { requestCancel(JobKind::Sweep); }

void SweepDialog::onFinished(const SweepOutcome& o) {
    size_t points = 0;
    QStringList failures;
    for (const auto& [law, r] : o.results) {
        points += r.points.size();
        if (r.status == RunStatus::Failed) failures << QString::fromStdString(r.message);
    }
    endRun(failures.join("; "), o.cancelled(), tr("Cancelled after %1 values (%2).").arg(points).arg(seconds(o.elapsed_ms)),
           tr("Done: %1 values in %2.").arg(points).arg(seconds(o.elapsed_ms)));
}

MapDialog::MapDialog(SimulationController* controller, SettingsSource current, QWidget* parent)
    : RunDialog(controller, std::move(current), parent) {
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
    addRunControls(form, tr("Every cell starts from rest; cells run in parallel."), tr("Cancel map"));
    connect(controller_, &SimulationController::mapProgress, this, &MapDialog::showProgress);
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
    if (beginRun(o.validate(s.paramsFor(s.primaryLaw())))) controller_->startMap(s, o);
}

void MapDialog::cancelRun() { requestCancel(JobKind::Map); }

void MapDialog::onFinished(const MapOutcome& o) {
    size_t done = 0;
    for (auto d : o.map.done) done += d ? 1 : 0;
    const QString failure = o.map.status == RunStatus::Failed ? QString::fromStdString(o.map.message) : QString();
    endRun(failure, o.map.status == RunStatus::Cancelled,
           tr("Cancelled: %1 of %2 cells (%3).").arg(done).arg(o.map.done.size()).arg(seconds(o.elapsed_ms)),
           tr("Done: %1 cells in %2.").arg(done).arg(seconds(o.elapsed_ms)));
}

}  // namespace stickslip::gui
