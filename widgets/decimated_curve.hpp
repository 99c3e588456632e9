// A QwtPlotCurve that draws only what the screen can show (internal to the widgets).
// The curve keeps every sample (export, picking and tests see the full data); only the
// polyline handed to the painter is reduced, at paint time, for the current axes and size:
//  - x non-decreasing (time series): per pixel column the first, lowest, highest and last
//    sample in index order ("M4"), so every vertical extent and every column-to-column join
//    of the full polyline is kept; points outside the visible x range are skipped;
//  - any other curve (loops, trajectories): a sample is skipped while it stays within
//    `tolerance_px` of the last one drawn, so the drawn line is never further than that from
//    any sample.
// Time series with fewer than two samples per pixel column, and curves of a few points, are
// drawn exactly as QwtPlotCurve draws them.
#pragma once

#include <qwt_plot_curve.h>

#include <QPolygonF>

class QwtScaleMap;

namespace stickslip::widgets {

class DecimatedCurve : public QwtPlotCurve {
public:
    explicit DecimatedCurve(const QString& title = QString()) : QwtPlotCurve(title) {}

    // The caller vouches that x never decreases with the index (checked in debug builds).
    void setMonotonicX(bool on) { monotonicX_ = on; }
    bool monotonicX() const { return monotonicX_; }

    // Points drawn by the last paint (diagnostics and tests).
    int lastDrawnPoints() const { return lastDrawn_; }

    // The reduced polyline in device coordinates for samples [from, to] (pure: no painting).
    QPolygonF reducedPolyline(const QwtScaleMap& xMap, const QwtScaleMap& yMap, int from, int to) const;

    static constexpr double tolerance_px = 0.25;

protected:
    void drawLines(QPainter* painter, const QwtScaleMap& xMap, const QwtScaleMap& yMap, const QRectF& canvasRect,
                   int from, int to) const override;

private:
    bool monotonicX_ = false;
    mutable int lastDrawn_ = 0;
};

}  // namespace stickslip::widgets
