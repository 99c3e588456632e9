// Dialogs that start the long analyses on the controller and follow them: a bifurcation
// sweep (parameter, range, direction up/down/both, cycles) and a 2-D periodicity map, each
// with a progress bar and Cancel. Values are entered in the panel's display units.
#pragma once

#include <QDialog>
#include <functional>

#include "core/analysis/periodicity_map.hpp"
#include "core/analysis/sweep.hpp"
#include "model_settings.hpp"

class QCheckBox;
class QComboBox;
class QFormLayout;
class QDoubleSpinBox;
class QSpinBox;
class QProgressBar;
class QPushButton;
class QLabel;

namespace stickslip::gui {

class SimulationController;
struct SweepOutcome;
struct MapOutcome;
enum class JobKind;

using SettingsSource = std::function<ModelSettings()>;

// What every long-running dialog shares below its form: a progress bar, a status line and
// Run / Cancel / Close (Close hides the dialog; Cancel is enabled only while a run is in flight).
class RunDialog : public QDialog {
    Q_OBJECT
public:
    QPushButton* runButton() const { return runButton_; }
    QPushButton* cancelButton() const { return cancelButton_; }
    QProgressBar* progressBar() const { return progress_; }
    QString statusText() const;

public slots:
    virtual void start() = 0;      // validate the options, then start the job on the controller
    virtual void cancelRun() = 0;  // cancel the job in flight

protected:
    RunDialog(SimulationController* controller, SettingsSource current, QWidget* parent);
    // Lays out `form`, then the progress bar, status line and buttons.
    void addRunControls(QFormLayout* form, const QString& statusText, const QString& cancelText);
    void showProgress(double fraction);  // 0..1
    // Shows the issues and returns false when there are any; else switches to "running".
    bool beginRun(const ParamIssues& issues);
    void requestCancel(JobKind kind);
    // Back to idle: shows the failure if non-empty, else the cancelled or done text.
    void endRun(const QString& failure, bool cancelled, const QString& cancelledText, const QString& doneText);

    SimulationController* controller_;
    SettingsSource current_;

private:
    QProgressBar* progress_ = nullptr;
    QPushButton* runButton_ = nullptr;
    QPushButton* cancelButton_ = nullptr;
    QLabel* status_ = nullptr;
};

class SweepDialog : public RunDialog {
    Q_OBJECT
public:
    SweepDialog(SimulationController* controller, SettingsSource current, QWidget* parent = nullptr);

    SweepOptions options() const;          // SI values
    void setOptions(const SweepOptions&);  // shows them

    void start() override;
    void cancelRun() override;

private:
    void onFinished(const SweepOutcome& o);
    QComboBox* key_;
    QDoubleSpinBox *from_, *to_;
    QSpinBox *steps_, *settle_, *sample_;
    QComboBox* direction_;
    QCheckBox* concurrent_;
};

class MapDialog : public RunDialog {
    Q_OBJECT
public:
    MapDialog(SimulationController* controller, SettingsSource current, QWidget* parent = nullptr);

    MapOptions options() const;

    void start() override;
    void cancelRun() override;

private:
    void onFinished(const MapOutcome& o);
    QComboBox *key1_, *key2_;
    QDoubleSpinBox *from1_, *to1_, *from2_, *to2_;
    QSpinBox *steps1_, *steps2_, *settle_, *sample_;
};

}  // namespace stickslip::gui
