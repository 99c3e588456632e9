// The Identify panel (issues 5 and 6): load measured runs, see how their columns were mapped,
// fit the rate-state and/or Coulomb law (free parameters, robust loss, validation), run the
// residual -> missing effect -> extended model loop, look at measured versus predicted,
// residuals and diagnostics, and export the reports. It only builds requests and shows
// outcomes: the computing happens on IdentifyWorker's thread.
#pragma once

#include <QStringList>
#include <QWidget>
#include <map>

#include "identify_worker.hpp"

class QCheckBox;
class SelfTestView;
class QComboBox;
class QDoubleSpinBox;
class QLabel;
class QListWidget;
class QProgressBar;
class QPushButton;
class QSpinBox;
class QTabWidget;
class QTableWidget;
class QTextBrowser;

namespace stickslip::widgets {
class SeriesPlot;
}

namespace stickslip::gui {

// "0.3012 ± 0.0021" (4 significant digits; "± n/a" when the standard error is not finite,
// no "±" when it is 0, i.e. the parameter was fixed).
QString formatEstimate(double value, double stderr_);
// A dimensionless error as shown in the tables ("0.1608"; "–" when not finite).
QString formatNrmse(double v);

class IdentifyPanel : public QWidget {
    Q_OBJECT
public:
    explicit IdentifyPanel(QWidget* parent = nullptr);
    ~IdentifyPanel() override;

    // Loads CSV files with the default column mapping; a manifest.json next to the first
    // file is used when `manifest` is empty. Replaces the loaded runs.
    bool loadRuns(const QStringList& files, const QString& manifest = {}, QString* error = nullptr);
    // Shows the import dialog for these files (or a file chooser when empty).
    void openImport(const QStringList& files = {});
    void setDataset(const io::Dataset& data);
    int runCount() const;
    void setValidationRun(int row, bool validation);
    SetupKind setup() const;

    // Requests built from the current controls (what Run would start).
    FitRequest fitRequest() const;
    IdentifyRequest identifyRequest() const;

    // Control setters (the same widgets the user edits).
    void setModel(const QString& model);            // "rate-state", "coulomb" or "both"
    void setFreeParameters(const QStringList& names);
    void setMultistarts(int n);
    void setMaxIterations(int n);
    void setTimeSplit(double fraction);              // 0: off
    void setIdentifyFree(const QStringList& names);
    void setCandidates(const QStringList& names);    // empty: all
    void setMaxEffects(int n);

    IdentifyWorker* worker() const { return worker_; }
    const FitOutcome& lastFit() const { return lastFit_; }
    const IdentifyOutcome& lastIdentify() const { return lastIdentify_; }
    bool hasFit() const { return lastFit_.ok; }
    bool hasIdentify() const { return lastIdentify_.ok; }

    // What the panel shows (tests read the same widgets the user sees).
    QString fitStatus() const;
    QString identifyStatus() const;
    QTableWidget* fitParameterTable() const { return fitParams_; }
    QTableWidget* fitRunTable() const { return fitRuns_; }
    QTableWidget* beforeAfterTable() const { return beforeAfter_; }
    QTableWidget* effectsTable() const { return effects_; }
    QTableWidget* candidateTable() const { return candidates_; }
    SelfTestView* selfTestView() const { return selfTest_; }
    QLabel* unexplainedLabel() const { return unexplained_; }
    QTabWidget* controlTabs() const { return controls_; }
    QTabWidget* plotTabs() const { return plots_; }
    widgets::SeriesPlot* overlayPlot() const { return overlayPlot_; }
    QPushButton* fitRunButton() const { return fitRun_; }
    QPushButton* fitCancelButton() const { return fitCancel_; }
    QPushButton* identifyRunButton() const { return idRun_; }
    QPushButton* identifyCancelButton() const { return idCancel_; }

    // Reports, written atomically (QSaveFile).
    bool exportFitReport(const QString& jsonPath, QString* error = nullptr) const;
    bool exportIdentifyReport(const QString& jsonPath, const QString& htmlPath, QString* error = nullptr) const;

public slots:
    void startFit();
    void startIdentify();
    void cancel();

signals:
    void fitShown(const stickslip::gui::FitOutcome& outcome);
    void identifyShown(const stickslip::gui::IdentifyOutcome& outcome);
    void statusMessage(const QString& text);

protected:
    void dragEnterEvent(QDragEnterEvent* e) override;
    void dropEvent(QDropEvent* e) override;

private:
    QWidget* buildDataTab();
    QWidget* buildFitTab();
    QWidget* buildIdentifyTab();
    QWidget* buildPlots();
    void refreshRunTable();
    void showMapping(int row);
    void setBusy(bool busy, bool fitJob);
    void onProgress(double fraction, const QString& stage);
    // Shows a cancelled or failed job in its progress bar and status line; true when it succeeded.
    bool showJobEnd(const QString& what, bool cancelled, bool ok, const QString& message, double elapsed_ms,
                    QProgressBar* bar, QLabel* status);
    void onFitFinished(const FitOutcome& o);
    void onIdentifyFinished(const IdentifyOutcome& o);
    void refreshPlots();
    void exportDialog();
    enum class Shown { Nothing, Fit, Identify };

    IdentifyWorker* worker_ = nullptr;
    MeasuredRuns runs_;
    FitOutcome lastFit_;
    IdentifyOutcome lastIdentify_;
    Shown shown_ = Shown::Nothing;
    bool fitJob_ = true;

    QTabWidget* controls_ = nullptr;
    QTabWidget* plots_ = nullptr;
    // Data
    QTableWidget* runTable_ = nullptr;
    QComboBox* setupBox_ = nullptr;
    QLabel* mapping_ = nullptr;
    QLabel* dataSummary_ = nullptr;
    QCheckBox *bandStop_ = nullptr, *lowPass_ = nullptr, *steadyTrim_ = nullptr;
    QDoubleSpinBox* lowPassHz_ = nullptr;
    // Fit
    QComboBox* model_ = nullptr;
    std::map<std::string, QCheckBox*> fitFree_;
    QComboBox* loss_ = nullptr;
    QDoubleSpinBox* lossScale_ = nullptr;
    QCheckBox* split_ = nullptr;
    QDoubleSpinBox* splitFraction_ = nullptr;
    QSpinBox *multistarts_ = nullptr, *maxIterations_ = nullptr;
    QCheckBox* jackknife_ = nullptr;
    QPushButton *fitRun_ = nullptr, *fitCancel_ = nullptr;
    QProgressBar* fitProgress_ = nullptr;
    QLabel* fitStatus_ = nullptr;
    QLabel* identifiability_ = nullptr;
    QTableWidget* fitParams_ = nullptr;
    QTableWidget* fitRuns_ = nullptr;
    // Identify
    std::map<std::string, QCheckBox*> idFree_;
    QListWidget* candidateList_ = nullptr;
    QSpinBox *maxEffects_ = nullptr, *idMultistarts_ = nullptr;
    QDoubleSpinBox* bicMargin_ = nullptr;
    QPushButton *idRun_ = nullptr, *idCancel_ = nullptr;
    QProgressBar* idProgress_ = nullptr;
    QLabel* idStatus_ = nullptr;
    QTableWidget* beforeAfter_ = nullptr;
    QTableWidget* effects_ = nullptr;
    QTableWidget* candidates_ = nullptr;
    SelfTestView* selfTest_ = nullptr;
    QLabel* unexplained_ = nullptr;
    // Plots
    QComboBox* plotRun_ = nullptr;
    QLabel* plotSource_ = nullptr;
    widgets::SeriesPlot* overlayPlot_ = nullptr;
    widgets::SeriesPlot* residualPlot_ = nullptr;
    widgets::SeriesPlot* spectrumPlot_ = nullptr;
    widgets::SeriesPlot* acfPlot_ = nullptr;
    QTableWidget* correlations_ = nullptr;
};

}  // namespace stickslip::gui
