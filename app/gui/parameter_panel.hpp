// The parameter panel: for every control and law parameter a slider (logarithmic where the
// range spans decades), a spin box and the unit, grouped as drive, rig, friction law and
// integration; a model selector (rate-state, Coulomb, both overlaid), a set-up selector
// (dynamics, prescribed slip), a preset selector with "reset to preset", and in the
// integration group the stepping (the paper's fixed dt or error-controlled at a tolerance). Invalid
// combinations (SimParams::validate()) are flagged on the field and listed in words.
// Emits ONE value, paramsChanged(ModelSettings), for every change. It never computes.
#pragma once

#include <QHash>
#include <QWidget>

#include "model_settings.hpp"

class QComboBox;
class QGridLayout;
class QDoubleSpinBox;
class QLabel;
class QSlider;
class QPushButton;

namespace stickslip::gui {

class ParameterPanel : public QWidget {
    Q_OBJECT
public:
    explicit ParameterPanel(QWidget* parent = nullptr);

    const ModelSettings& settings() const { return settings_; }
    // Shows `s` (exact values are kept even where the spin box rounds them) and emits once.
    void setSettings(const ModelSettings& s);
    // Loads a built-in preset (keeps the model choice); false for an unknown name.
    bool loadPreset(const QString& name);

    // The controls of one key (nullptr for an unknown key), for tests and benchmarks.
    QSlider* slider(const QString& key) const;
    QDoubleSpinBox* spinBox(const QString& key) const;
    QComboBox* modelBox() const { return modelBox_; }
    QComboBox* setupBox() const { return setupBox_; }
    QComboBox* presetBox() const { return presetBox_; }
    // Stepping of dynamics runs: the paper's fixed dt, or error-controlled at a tolerance.
    QComboBox* steppingBox() const { return steppingBox_; }
    // The current validation issues in words ("" when valid).
    QString issuesText() const;

public slots:
    void resetToPreset();

signals:
    void paramsChanged(const stickslip::gui::ModelSettings& settings);

private:
    struct Row {
        QSlider* slider = nullptr;
        QDoubleSpinBox* spin = nullptr;
        QLabel* label = nullptr;
    };
    void buildRows();
    static QString steppingLabel(double tolerance);  // the stepping row's text for an error-controlled TOL
    void addSteppingRow(QWidget* box, QGridLayout* grid, int row);
    void onSlider(const QString& key, int position);
    void onSpin(const QString& key, double displayValue);
    void onModel(int index);
    void onSetup(int index);
    void onPreset(int index);
    void onStepping(int index);
    void showValues();      // settings_ → widgets, without signals
    void showIssues();      // validate and flag
    void changed();         // showIssues + emit

    ModelSettings settings_;
    QHash<QString, Row> rows_;
    QComboBox* presetBox_ = nullptr;
    QComboBox* modelBox_ = nullptr;
    QComboBox* setupBox_ = nullptr;
    QComboBox* steppingBox_ = nullptr;
    QPushButton* resetButton_ = nullptr;
    QLabel* issuesLabel_ = nullptr;
    bool updating_ = false;
};

}  // namespace stickslip::gui
