// The import dialog's "Cleaning" page: the preprocessing settings and a raw-versus-cleaned plot
// of one signal of the selected run. The cleaning runs off the GUI thread; bursts of edits
// become one job (a short single-shot timer) and results of stale settings are dropped.
#pragma once

#include <QFutureWatcher>
#include <QWidget>
#include <functional>

#include "cleaning_preview.hpp"

class QCheckBox;
class QComboBox;
class QDoubleSpinBox;
class QLabel;
class QSpinBox;
class QTimer;

namespace stickslip::widgets {
class SignalComparePlot;
}

namespace stickslip::gui {

class ImportCleaningPage : public QWidget {
    Q_OBJECT
public:
    // What the job needs from the rest of the dialog, asked for when it starts (not when it is
    // scheduled), so it sees the latest mapping.
    struct Source {
        bool haveFile = false;   // a file is selected and read
        bool ready = false;      // ... readable, and the mapping is valid
        QString file;
        io::DatasetOptions options;
    };

    explicit ImportCleaningPage(QWidget* parent = nullptr);
    ~ImportCleaningPage() override;   // waits for the job

    identify::PreprocessSettings settings() const;
    void setSettings(const identify::PreprocessSettings& s);   // without settingsChanged
    void updateEnabledStates();

    void setSource(std::function<Source()> source) { source_ = std::move(source); }
    void schedule();
    bool isBusy() const;
    const CleaningPreview& preview() const { return cleaning_; }
    widgets::SignalComparePlot* plot() const { return plot_; }
    void setPlotSignal(io::Signal s);

signals:
    void settingsChanged();
    void cleaningUpdated();   // the plot shows a new result

private:
    QWidget* buildSettings();
    QWidget* buildBandBox();
    QWidget* buildLowPassBox();
    QWidget* buildDerivativeBox();
    QWidget* buildTrimBox();
    QWidget* buildPlotBox();
    void start();
    void onFinished();
    void fillSignalChoices();
    void showCleaning();
    void showStatus(double windowBegin_s, double windowEnd_s);

    QCheckBox *bandStop_ = nullptr, *lowPass_ = nullptr, *steadyTrim_ = nullptr, *resample_ = nullptr, *fuseAccel_ = nullptr;
    QDoubleSpinBox *bandCenter_ = nullptr, *bandWidth_ = nullptr, *lowPassHz_ = nullptr;
    QSpinBox *bandOrder_ = nullptr, *lowPassOrder_ = nullptr, *sgHalf_ = nullptr, *sgOrder_ = nullptr,
             *stageHarmonics_ = nullptr;
    QDoubleSpinBox *trimStart_ = nullptr, *trimEnd_ = nullptr, *trimFraction_ = nullptr;
    QComboBox* plotSignal_ = nullptr;
    QCheckBox* detail_ = nullptr;
    QLabel* status_ = nullptr;
    widgets::SignalComparePlot* plot_ = nullptr;

    std::function<Source()> source_;
    QTimer* timer_ = nullptr;
    QFutureWatcher<CleaningPreview> watcher_;
    quint64 generation_ = 0;
    bool running_ = false;
    bool pending_ = false;
    bool populating_ = false;
    CleaningPreview cleaning_;
};

}  // namespace stickslip::gui
