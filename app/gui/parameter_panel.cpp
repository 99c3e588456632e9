#include "parameter_panel.hpp"

#include "core/friction/friction_law.hpp"

#include <QComboBox>
#include <QDoubleSpinBox>
#include <QFormLayout>
#include <QGridLayout>
#include <QGroupBox>
#include <QHBoxLayout>
#include <QLabel>
#include <QPushButton>
#include <QSignalBlocker>
#include <QSlider>
#include <QVBoxLayout>

#include "core/presets.hpp"
#include "param_specs.hpp"

namespace stickslip::gui {

namespace {
const char* kInvalidStyle = "QDoubleSpinBox { background: #ffd0d0; }";
}

ParameterPanel::ParameterPanel(QWidget* parent) : QWidget(parent) {
    auto* top = new QVBoxLayout(this);
    top->setContentsMargins(4, 4, 4, 4);

    auto* form = new QFormLayout;
    presetBox_ = new QComboBox(this);
    presetBox_->setObjectName("presetBox");
    for (const auto& p : builtinPresets()) {
        presetBox_->addItem(QString::fromStdString(p.name), QString::fromStdString(p.name));
        presetBox_->setItemData(presetBox_->count() - 1, QString::fromStdString(p.description), Qt::ToolTipRole);
    }
    resetButton_ = new QPushButton(tr("Reset"), this);
    resetButton_->setToolTip(tr("Reset every value to the selected preset"));
    auto* presetRow = new QHBoxLayout;
    presetRow->addWidget(presetBox_, 1);
    presetRow->addWidget(resetButton_);
    form->addRow(tr("Preset"), presetRow);

    modelBox_ = new QComboBox(this);
    modelBox_->setObjectName("modelBox");
    for (ModelChoice m : modelChoices()) {
        const QString name = m == ModelChoice::Both ? tr("Both overlaid")
                             : m == ModelChoice::RateState
                                 ? tr("Rate-state")
                                 : QString::fromUtf8(lawInfo(static_cast<LawKind>(static_cast<int>(m))).label);
        modelBox_->addItem(name, int(m));
    }
    form->addRow(tr("Model"), modelBox_);

    setupBox_ = new QComboBox(this);
    setupBox_->setObjectName("setupBox");
    setupBox_->addItem(tr("Dynamics (spring-mass rig)"), int(SetupKind::Dynamics));
    setupBox_->addItem(tr("Prescribed slip (block)"), int(SetupKind::Prescribed));
    form->addRow(tr("Set-up"), setupBox_);
    top->addLayout(form);

    buildRows();

    issuesLabel_ = new QLabel(this);
    issuesLabel_->setObjectName("issuesLabel");
    issuesLabel_->setWordWrap(true);
    issuesLabel_->setStyleSheet("QLabel { color: #b00000; }");
    top->addWidget(issuesLabel_);
    top->addStretch(1);

    connect(modelBox_, qOverload<int>(&QComboBox::currentIndexChanged), this, &ParameterPanel::onModel);
    connect(setupBox_, qOverload<int>(&QComboBox::currentIndexChanged), this, &ParameterPanel::onSetup);
    connect(presetBox_, qOverload<int>(&QComboBox::activated), this, &ParameterPanel::onPreset);
    connect(resetButton_, &QPushButton::clicked, this, &ParameterPanel::resetToPreset);

    Preset p;
    findPreset("fig20", p);
    settings_.params = p.params;
    settings_.preset = "fig20";
    showValues();
    showIssues();
}

void ParameterPanel::buildRows() {
    auto* top = static_cast<QVBoxLayout*>(layout());
    for (ParamGroup g : {ParamGroup::Drive, ParamGroup::Rig, ParamGroup::FrictionLaw, ParamGroup::Integration}) {
        auto* box = new QGroupBox(groupTitle(g), this);
        auto* grid = new QGridLayout(box);
        grid->setContentsMargins(4, 2, 4, 2);
        grid->setVerticalSpacing(1);
        grid->setColumnStretch(1, 1);
        int r = 0;
        for (const auto& s : parameterSpecs()) {
            if (s.group != g) continue;
            Row row;
            row.label = new QLabel(s.label, box);
            row.label->setToolTip(s.tooltip);
            row.slider = new QSlider(Qt::Horizontal, box);
            row.slider->setObjectName("slider_" + s.key);
            row.slider->setRange(0, kSliderSteps);
            row.slider->setToolTip(s.tooltip + (s.logScale ? tr(" (logarithmic slider)") : QString()));
            row.spin = new QDoubleSpinBox(box);
            row.spin->setObjectName("spin_" + s.key);
            row.spin->setDecimals(s.decimals);
            row.spin->setRange(s.min, s.max);
            row.spin->setStepType(QAbstractSpinBox::AdaptiveDecimalStepType);
            row.spin->setKeyboardTracking(false);
            row.spin->setToolTip(s.tooltip);
            row.spin->setMinimumWidth(90);
            auto* unit = new QLabel(s.unit, box);
            unit->setMinimumWidth(36);
            grid->addWidget(row.label, r, 0);
            grid->addWidget(row.slider, r, 1);
            grid->addWidget(row.spin, r, 2);
            grid->addWidget(unit, r, 3);
            const QString key = s.key;
            connect(row.slider, &QSlider::valueChanged, this, [this, key](int v) { onSlider(key, v); });
            connect(row.spin, qOverload<double>(&QDoubleSpinBox::valueChanged), this,
                    [this, key](double v) { onSpin(key, v); });
            rows_.insert(s.key, row);
            ++r;
        }
        if (g == ParamGroup::Integration) addSteppingRow(box, grid, r);
        top->addWidget(box);
    }
}

QString ParameterPanel::steppingLabel(double tolerance) {
    return tr("error-controlled, TOL %1").arg(tolerance, 0, 'g', 3);
}

void ParameterPanel::addSteppingRow(QWidget* box, QGridLayout* grid, int row) {
    steppingBox_ = new QComboBox(box);
    steppingBox_->setObjectName("steppingBox");
    steppingBox_->addItem(tr("fixed dt (the paper's algorithm)"), 0.0);
    for (double tol : {1e-3, 1e-4, 1e-5})
        steppingBox_->addItem(steppingLabel(tol), tol);
    steppingBox_->setToolTip(
        tr("Dynamics runs: the paper's scheme with the fixed step dt, or the error-controlled integrator "
           "(step doubling, stick-slip switches located, samples and Poincare points from its dense output at "
           "the exact times) with TOL the relative error target on the displacement; dt is then not used. "
           "The prescribed set-up always steps the given slip history."));
    auto* label = new QLabel(tr("steps"), box);
    label->setToolTip(steppingBox_->toolTip());
    grid->addWidget(label, row, 0);
    grid->addWidget(steppingBox_, row, 1, 1, 3);
    connect(steppingBox_, qOverload<int>(&QComboBox::activated), this, &ParameterPanel::onStepping);
}

void ParameterPanel::onStepping(int index) {
    if (updating_) return;
    settings_.tolerance = steppingBox_->itemData(index).toDouble();
    showValues();
    changed();
}

QSlider* ParameterPanel::slider(const QString& key) const {
    auto it = rows_.find(key);
    return it == rows_.end() ? nullptr : it->slider;
}
QDoubleSpinBox* ParameterPanel::spinBox(const QString& key) const {
    auto it = rows_.find(key);
    return it == rows_.end() ? nullptr : it->spin;
}

void ParameterPanel::onSlider(const QString& key, int position) {
    if (updating_) return;
    const ParamSpec* s = findSpec(key);
    const double display = sliderValue(*s, position);
    {
        const QSignalBlocker b(rows_[key].spin);
        rows_[key].spin->setValue(display);
    }
    // The spin box rounds to its decimals; use its value so both show the same number.
    setParam(settings_.params, key.toStdString(), rows_[key].spin->value() / s->scale);
    changed();
}

void ParameterPanel::onSpin(const QString& key, double display) {
    if (updating_) return;
    const ParamSpec* s = findSpec(key);
    {
        const QSignalBlocker b(rows_[key].slider);
        rows_[key].slider->setValue(sliderPosition(*s, display));
    }
    setParam(settings_.params, key.toStdString(), display / s->scale);
    changed();
}

void ParameterPanel::onModel(int index) {
    if (updating_) return;
    settings_.model = static_cast<ModelChoice>(modelBox_->itemData(index).toInt());
    settings_.params.law = settings_.primaryLaw();
    showValues();
    changed();
}

void ParameterPanel::onSetup(int index) {
    if (updating_) return;
    settings_.params.setup = static_cast<SetupKind>(setupBox_->itemData(index).toInt());
    showValues();
    changed();
}

void ParameterPanel::onPreset(int index) { loadPreset(presetBox_->itemData(index).toString()); }

void ParameterPanel::resetToPreset() { loadPreset(presetBox_->currentData().toString()); }

bool ParameterPanel::loadPreset(const QString& name) {
    Preset p;
    if (!findPreset(name.toStdString(), p)) return false;
    ModelSettings s = settings_;
    s.params = p.params;
    s.params.law = s.primaryLaw();
    s.preset = name;
    setSettings(s);
    return true;
}

void ParameterPanel::setSettings(const ModelSettings& s) {
    settings_ = s;
    settings_.params.law = settings_.primaryLaw();
    showValues();
    changed();
}

void ParameterPanel::showValues() {
    updating_ = true;
    const bool dynamics = settings_.params.setup == SetupKind::Dynamics;
    const bool adaptive = dynamics && settings_.tolerance > 0.0;
    for (auto it = rows_.begin(); it != rows_.end(); ++it) {
        const ParamSpec* s = findSpec(it.key());
        double v = 0.0;
        getParam(settings_.params, it.key().toStdString(), v);  // a shared key: the primary law's value
        it->spin->setValue(v * s->scale);
        it->slider->setValue(sliderPosition(*s, v * s->scale));
        // A law's key is enabled for the laws that have it (greyed out, not hidden, so that
        // switching the model does not move the panel's rows).
        bool used = !s->lawKey;
        for (LawKind law : settings_.laws()) used = used || lawHasParam(law, it.key().toStdString());
        if (it.key() == "dt" && adaptive) used = false;  // the error-controlled integrator picks its steps
        it->spin->setEnabled(used);
        it->slider->setEnabled(used);
        it->label->setEnabled(used);
    }
    modelBox_->setCurrentIndex(modelBox_->findData(int(settings_.model)));
    setupBox_->setCurrentIndex(setupBox_->findData(int(settings_.params.setup)));
    int si = steppingBox_->findData(settings_.tolerance);
    if (si < 0) {  // a tolerance from a session that the list does not offer: add it
        steppingBox_->addItem(steppingLabel(settings_.tolerance), settings_.tolerance);
        si = steppingBox_->count() - 1;
    }
    steppingBox_->setCurrentIndex(si);
    steppingBox_->setEnabled(dynamics);
    const int pi = presetBox_->findData(settings_.preset);
    if (pi >= 0) presetBox_->setCurrentIndex(pi);
    updating_ = false;
}

QString ParameterPanel::issuesText() const { return issuesLabel_->text(); }

void ParameterPanel::showIssues() {
    // Validate every law that will run, so "both" flags the Coulomb values too.
    ParamIssues issues;
    for (LawKind law : settings_.laws()) {
        for (const auto& i : settings_.paramsFor(law).validate()) {
            bool dup = false;
            for (const auto& j : issues) dup = dup || (j.field == i.field);
            if (!dup) issues.push_back(i);
        }
    }
    for (auto it = rows_.begin(); it != rows_.end(); ++it) {
        QString reason;
        for (const auto& i : issues)
            if (QString::fromStdString(i.field) == it.key()) reason = QString::fromStdString(i.message());
        it->spin->setStyleSheet(reason.isEmpty() ? QString() : QString(kInvalidStyle));
        const ParamSpec* s = findSpec(it.key());
        it->spin->setToolTip(reason.isEmpty() ? s->tooltip : s->tooltip + "\n" + reason);
    }
    issuesLabel_->setText(QString::fromStdString(formatIssues(issues)));
    issuesLabel_->setVisible(!issues.empty());
}

void ParameterPanel::changed() {
    showIssues();
    emit paramsChanged(settings_);
}

}  // namespace stickslip::gui
