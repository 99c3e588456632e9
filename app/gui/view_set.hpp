// The app's views (H4a's plot widgets and the rig view) and how outcomes are shown on them.
// Owns no threads and computes nothing: it hands value types to the widgets.
#pragma once

#include <QObject>
#include <QString>
#include <QVector>
#include <memory>

#include "job_results.hpp"

class QWidget;

namespace stickslip::io {
struct CsvTable;
}

namespace stickslip::widgets {
class PlotWidget;
class TimeSeriesPlot;
class FrictionLoopPlot;
class PhasePortraitPlot;
class PoincarePlot;
class BifurcationPlot;
class SpectrumPlot;
class AutocorrelationPlot;
class PeriodicityMapPlot;
class RigView;
}  // namespace stickslip::widgets

namespace stickslip::gui {

class ViewSet : public QObject {
    Q_OBJECT
public:
    struct View {
        QString id;       // "timeseries", used in sessions and object names
        QString title;    // dock title
        QWidget* widget;  // the view
        widgets::PlotWidget* plot;  // nullptr for the rig view
    };

    explicit ViewSet(QWidget* parentForWidgets);

    const QVector<View>& views() const { return views_; }
    const View* find(const QString& id) const;

    widgets::TimeSeriesPlot* timeSeries() const { return timeSeries_; }
    widgets::FrictionLoopPlot* frictionLoop() const { return loop_; }
    widgets::PhasePortraitPlot* phasePortrait() const { return phase_; }
    widgets::PoincarePlot* poincare() const { return poincare_; }
    widgets::BifurcationPlot* bifurcation() const { return bifurcation_; }
    widgets::SpectrumPlot* spectrum() const { return spectrum_; }
    widgets::AutocorrelationPlot* autocorrelation() const { return acf_; }
    widgets::PeriodicityMapPlot* periodicityMap() const { return map_; }
    widgets::RigView* rig() const { return rig_; }

    // Overlays the measured columns of `table` (by the CLI's column names: time_s with
    // slider_m / stage_m / stage_disp_m / ratio / friction_force_N / relVel_mps ...) on the
    // time series and, where both exist, the friction loop. Returns the number of series
    // overlaid; a message in `error` when none fits.
    int overlayMeasured(const io::CsvTable& table, double normalForce_N, QString* error);
    void clearMeasured();

    // The last run outcome shown (nullptr before the first).
    std::shared_ptr<const RunOutcome> lastRun() const { return lastRun_; }
    // A view's dock became visible (e.g. its tab was brought to the front): a plot kept off
    // screen draws the newest result it was handed.
    void viewBroughtToFront(const QString& id);

public slots:
    void showRun(const stickslip::gui::RunOutcome& outcome);
    void showPoincare(const stickslip::gui::PoincareOutcome& outcome);
    void showSweep(const stickslip::gui::SweepOutcome& outcome);
    void showMap(const stickslip::gui::MapOutcome& outcome);

private:
    void showShared(const std::shared_ptr<const RunOutcome>& outcome);
    QVector<View> views_;
    std::shared_ptr<const RunOutcome> lastRun_;   // re-shown after clearing measured overlays
    widgets::TimeSeriesPlot* timeSeries_ = nullptr;
    widgets::FrictionLoopPlot* loop_ = nullptr;
    widgets::PhasePortraitPlot* phase_ = nullptr;
    widgets::PoincarePlot* poincare_ = nullptr;
    widgets::BifurcationPlot* bifurcation_ = nullptr;
    widgets::SpectrumPlot* spectrum_ = nullptr;
    widgets::AutocorrelationPlot* acf_ = nullptr;
    widgets::PeriodicityMapPlot* map_ = nullptr;
    widgets::RigView* rig_ = nullptr;
};

}  // namespace stickslip::gui
