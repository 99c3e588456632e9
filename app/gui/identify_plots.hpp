// The Identify panel's plots: measured versus predicted, residual, residual spectrum and
// autocorrelation, residual-signal correlations for one run of the last fit or identify, and the
// run-to-run structure test behind the "unexplained" verdict (every run, every signal).
// The outcomes belong to the panel (which outlives this child); the view keeps pointers so
// that choosing another run redraws without a copy.
#pragma once

#include <QWidget>
#include <vector>

#include "identify_worker.hpp"

class QComboBox;
class QLabel;
class QTabWidget;
class QTableWidget;

namespace stickslip::widgets {
class SeriesPlot;
struct PlotSeries;
}

namespace stickslip::gui {

class IdentifyPlots : public QWidget {
    Q_OBJECT
public:
    explicit IdentifyPlots(QWidget* parent = nullptr);

    void showFit(const FitOutcome* fit);
    void showIdentify(const IdentifyOutcome* identify);
    QTabWidget* tabs() const { return plots_; }
    QTableWidget* structureRunsTable() const { return structureRuns_; }
    QTableWidget* structureSignalsTable() const { return structureSignals_; }
    QLabel* structureSummary() const { return structureSummary_; }
    widgets::SeriesPlot* overlayPlot() const { return overlay_; }

private:
    void refresh();
    void syncRunChoices();
    using Series = std::vector<widgets::PlotSeries>;
    const identify::Diagnostics* fitSeries(int k, Series& over, Series& res);
    void identifySeries(int k, Series& over, Series& res);
    void showDiagnostics(const identify::Diagnostics* diag, const identify::Diagnostics* after);
    void showCorrelations(const identify::Diagnostics* diag, const identify::Diagnostics* after);
    void showStructure(const identify::Diagnostics* diag, const identify::Diagnostics* after);

    const FitOutcome* fit_ = nullptr;             // what is shown: at most one of the two
    const IdentifyOutcome* identify_ = nullptr;
    QComboBox* run_ = nullptr;
    QLabel* source_ = nullptr;
    QTabWidget* plots_ = nullptr;
    widgets::SeriesPlot* overlay_ = nullptr;
    widgets::SeriesPlot* residual_ = nullptr;
    widgets::SeriesPlot* spectrum_ = nullptr;
    widgets::SeriesPlot* acf_ = nullptr;
    QTableWidget* correlations_ = nullptr;
    QLabel* structureSummary_ = nullptr;
    QTableWidget* structureRuns_ = nullptr;     // per run: d and the feature that predicted it
    QTableWidget* structureSignals_ = nullptr;  // per signal alone: mean d
};

}  // namespace stickslip::gui
