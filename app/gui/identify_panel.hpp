// The Identify panel (issues 5 and 6): load measured runs, see how their columns were mapped,
// fit the rate-state and/or Coulomb law (free parameters, robust loss, validation), run the
// residual -> missing effect -> extended model loop, look at measured versus predicted,
// residuals and diagnostics, and export the reports. It only builds requests and shows
// outcomes: the computing happens on IdentifyWorker's thread.
//
// The panel is a thin container: the Data, Fit and Identify tabs and the plots are classes of
// their own; the panel owns the worker and the last outcomes and wires the tabs to them.
#pragma once

#include <QStringList>
#include <QWidget>

#include "identify_tables.hpp"
#include "identify_worker.hpp"

class QLabel;
class QPushButton;
class QTabWidget;
class QTableWidget;
class SelfTestView;

namespace stickslip::widgets {
class SeriesPlot;
}

namespace stickslip::gui {

class IdentifyDataTab;
class IdentifyFitTab;
class IdentifyLoopTab;
class IdentifyPlots;

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
    QTableWidget* fitParameterTable() const;
    QTableWidget* fitRunTable() const;
    QTableWidget* beforeAfterTable() const;
    QTableWidget* effectsTable() const;
    QTableWidget* candidateTable() const;
    QTableWidget* timelineTable() const;  // the loop's stages: time and fits
    SelfTestView* selfTestView() const;
    QLabel* unexplainedLabel() const;
    QLabel* baselineBoundsLabel() const;
    QTabWidget* controlTabs() const { return controls_; }
    QTabWidget* plotTabs() const;
    widgets::SeriesPlot* overlayPlot() const;
    IdentifyPlots* plots() const { return plots_; }
    QPushButton* fitRunButton() const;
    QPushButton* fitCancelButton() const;
    QPushButton* identifyRunButton() const;
    QPushButton* identifyCancelButton() const;

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
    void buildTabs();
    void connectTabs();
    void updateRunButtons();
    void setBusy(bool busy, bool fitJob);
    void onProgress(double fraction, const QString& stage);
    void onFitFinished(const FitOutcome& o);
    void onIdentifyFinished(const IdentifyOutcome& o);
    void exportDialog();

    IdentifyWorker* worker_ = nullptr;
    FitOutcome lastFit_;
    IdentifyOutcome lastIdentify_;
    bool fitJob_ = true;

    QTabWidget* controls_ = nullptr;
    IdentifyDataTab* data_ = nullptr;
    IdentifyFitTab* fit_ = nullptr;
    IdentifyLoopTab* loop_ = nullptr;
    IdentifyPlots* plots_ = nullptr;
};

}  // namespace stickslip::gui
