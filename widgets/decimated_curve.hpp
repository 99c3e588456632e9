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

#include <QPair>
#include <QPolygonF>
#include <QVector>

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

    mutable int lastDrawn_ = 0;

private:
    bool monotonicX_ = false;
};

// A DecimatedCurve drawn as separate polylines over chosen index ranges (pieces): many
// friction-loop excursions in one plot item instead of one curve each. The curve keeps all
// its samples (export, picking, bounding box); only the pieces are drawn, each reduced as a
// DecimatedCurve reduces a curve. Without pieces set, the whole curve is drawn.
class PiecewiseCurve : public DecimatedCurve {
public:
    explicit PiecewiseCurve(const QString& title = QString()) : DecimatedCurve(title) {}

    // Closed index ranges [first, last] into the samples, drawn each as one polyline.
    void setPieces(QVector<QPair<int, int>> pieces);
    void clearPieces();   // draw the whole curve again
    bool hasPieces() const { return piecewise_; }
    const QVector<QPair<int, int>>& pieces() const { return pieces_; }
    // The samples of piece k.
    QVector<QPointF> pieceSamples(int k) const;

protected:
    void drawLines(QPainter* painter, const QwtScaleMap& xMap, const QwtScaleMap& yMap, const QRectF& canvasRect,
                   int from, int to) const override;

private:
    QVector<QPair<int, int>> pieces_;
    bool piecewise_ = false;
};

}  // namespace stickslip::widgets
