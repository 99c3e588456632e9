// Base of every plot view: a QWidget wrapping one QwtPlot with a consistent look, zoom
// (QwtPlotZoomer: drag a rectangle; right click zooms out), pan (middle button drag) and a
// crosshair read-out (QwtPlotPicker). Up to two models are overlaid (rate-state solid,
// Coulomb dashed) plus measured series. Widgets only display value types handed to them.
#pragma once

#include <QList>
#include <QPointF>
#include <QString>
#include <QVector>
#include <QWidget>
#include <functional>
#include <vector>

#include "core/params.hpp"

class QwtPlot;
class QwtPlotCurve;
class QwtPlotZoomer;
class QwtPlotPanner;
class QwtPlotPicker;
class QwtPlotGrid;

namespace stickslip::io {
struct CsvTable;
}

namespace stickslip::widgets {

// A measured series to overlay, in SI units (the plot scales it like its own axes).
struct MeasuredSeries {
    QString label;             // legend text, e.g. "measured: x_m"
    std::vector<double> x;     // SI
    std::vector<double> y;     // SI
};

// Picks columns `xColumn` and `yColumn` (names as in the CSV header, as the CLI reads them)
// from a table. Returns false and a message naming the missing column and file.
bool measuredFromTable(const io::CsvTable& table, const std::string& xColumn, const std::string& yColumn,
                       MeasuredSeries& out, QString* error = nullptr);

// "rate-state" / "Coulomb": the legend prefix used for curves of each model.
QString modelLabel(LawKind law);
// Per-law storage in the plots is indexed by the law's slot (its registry index).
inline constexpr int kMaxLawSlots = 8;

class PlotWidget : public QWidget {
    Q_OBJECT
public:
    explicit PlotWidget(QWidget* parent = nullptr);
    ~PlotWidget() override;

    QwtPlot* plot() const { return plot_; }
    QwtPlotZoomer* zoomer() const { return zoomer_; }
    QwtPlotPanner* panner() const { return panner_; }
    QwtPlotPicker* picker() const { return picker_; }

    // Measured overlays (black markers), on the primary axes (xBottom, yLeft).
    void addMeasured(const MeasuredSeries& series);
    void clearMeasured();

    // Removes the curves of one model / everything.
    virtual void clearModel(LawKind law);
    virtual void clearAll();

    // All curves currently attached, and the one with this exact title (nullptr if none).
    QList<QwtPlotCurve*> curves() const;
    QwtPlotCurve* curve(const QString& title) const;

    // Export by extension: .png .svg .pdf (the plot) or .csv (its data); atomic write.
    // A pending update (below) is applied first, so the file shows the newest data.
    bool exportTo(const QString& path, QString* error = nullptr);

    // Views off the screen need not redraw on every result: runs `update` now when the widget
    // is on screen (isOnScreen), else keeps it (a newer one replaces an older one) and runs it
    // when the widget is shown, exported or applyPendingUpdate() is called (the owner of a
    // tabified dock calls it when the dock's tab is brought to the front).
    void updateWhenVisible(std::function<void()> update);
    // Visible and not entirely outside its window: a dock tabified behind another one is
    // visible but moved out of the window by Qt, so it is not on screen.
    bool isOnScreen() const;
    bool hasPendingUpdate() const { return static_cast<bool>(pending_); }
    void applyPendingUpdate();

    // Display scale of the primary axes: value shown = SI value * factor (e.g. 1e3 for mm).
    double xFactor() const { return xFactor_; }
    double yFactor() const { return yFactor_; }

public slots:
    // Autoscale to the data and make that the zoom base.
    void rescale();

    // Most major intervals on the bottom axis: as many as labels like "-0.000" fit side by
    // side in the plot's width (at most Qwt's 8; 4 on a widened single-value axis), so the
    // labels of a narrow dock do not run into each other.
    int xMajorTicks() const;

protected:
    void showEvent(QShowEvent* e) override;
    void resizeEvent(QResizeEvent* e) override;
    // A curve of `law` (pen style by model) in `color`, attached on axis `yAxis`.
    QwtPlotCurve* addCurve(const QString& title, LawKind law, const QColor& color, int yAxis = 2 /*yLeft*/);
    QwtPlotCurve* addCurve(const QString& title, const QPen& pen, int yAxis = 2 /*yLeft*/);
    // The curve titled `title`, refilled by the caller: an existing one gets `pen` and
    // `yAxis`, else one is added. Results reuse their curves because attaching or removing a
    // curve re-lays out the legend (milliseconds per result).
    QwtPlotCurve* reuseCurve(const QString& title, const QPen& pen, int yAxis = 2 /*yLeft*/);
    QwtPlotCurve* reuseCurve(const QString& title, LawKind law, const QColor& color, int yAxis = 2 /*yLeft*/);
    void setAxisTitles(const QString& xTitle, const QString& yTitle);
    void setFactors(double xFactor, double yFactor) {
        xFactor_ = xFactor;
        yFactor_ = yFactor;
    }
    void removeCurvesWithPrefix(const QString& prefix);
    void applyFonts();
    // Autoscaled x (bottom) and y (left) ranges narrower than these spans [shown units] are
    // widened to them, centred on the data (0: only numerically single values are widened).
    void setMinimumSpans(double x, double y) {
        minSpan_[0] = x;
        minSpan_[1] = y;
    }
    void widenDegenerateAxes();

    QwtPlot* plot_ = nullptr;
    QwtPlotZoomer* zoomer_ = nullptr;
    QwtPlotPanner* panner_ = nullptr;
    QwtPlotPicker* picker_ = nullptr;
    QwtPlotGrid* grid_ = nullptr;
    double xFactor_ = 1.0;
    double yFactor_ = 1.0;
    double minSpan_[2] = {0.0, 0.0};

private:
    bool setXMajorTicks();  // true when the bottom axis's interval count changed
    std::function<void()> pending_;
    bool degenerateX_ = false;  // the bottom axis was widened around a single value
};

}  // namespace stickslip::widgets
