// Dialogs that start the long analyses on the controller and follow them: a bifurcation
// sweep (parameter, range, direction up/down/both, cycles) and a 2-D periodicity map, each
// with a progress bar and Cancel. Values are entered in the panel's display units.
#pragma once

#include <QDialog>
#include <functional>

#include "core/analysis/periodicity_map.hpp"
#include "core/analysis/sweep.hpp"
#include "model_settings.hpp"

class QComboBox;
class QDoubleSpinBox;
class QSpinBox;
class QProgressBar;
class QPushButton;
class QLabel;

namespace stickslip::gui {

class SimulationController;
struct SweepOutcome;
struct MapOutcome;

using SettingsSource = std::function<ModelSettings()>;

class SweepDialog : public QDialog {
    Q_OBJECT
public:
    SweepDialog(SimulationController* controller, SettingsSource current, QWidget* parent = nullptr);

    SweepOptions options() const;          // SI values
    void setOptions(const SweepOptions&);  // shows them
    QPushButton* runButton() const { return runButton_; }
    QPushButton* cancelButton() const { return cancelButton_; }
    QProgressBar* progressBar() const { return progress_; }
    QString statusText() const;

public slots:
    void start();
    void cancelSweep();

private:
    void onFinished(const SweepOutcome& o);
    SimulationController* controller_;
    SettingsSource current_;
    QComboBox* key_;
    QDoubleSpinBox *from_, *to_;
    QSpinBox *steps_, *settle_, *sample_;
    QComboBox* direction_;
    QProgressBar* progress_;
    QPushButton *runButton_, *cancelButton_;
    QLabel* status_;
};

class MapDialog : public QDialog {
    Q_OBJECT
public:
    MapDialog(SimulationController* controller, SettingsSource current, QWidget* parent = nullptr);

    MapOptions options() const;
    QPushButton* runButton() const { return runButton_; }
    QPushButton* cancelButton() const { return cancelButton_; }
    QProgressBar* progressBar() const { return progress_; }

public slots:
    void start();
    void cancelMap();

private:
    void onFinished(const MapOutcome& o);
    SimulationController* controller_;
    SettingsSource current_;
    QComboBox *key1_, *key2_;
    QDoubleSpinBox *from1_, *to1_, *from2_, *to2_;
    QSpinBox *steps1_, *steps2_, *settle_, *sample_;
    QProgressBar* progress_;
    QPushButton *runButton_, *cancelButton_;
    QLabel* status_;
};

}  // namespace stickslip::gui
