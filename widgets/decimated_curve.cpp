#include "decimated_curve.hpp"

#include <qwt_clipper.h>
#include <qwt_painter.h>
#include <qwt_scale_map.h>
#include <qwt_series_data.h>

#include <QPainter>
#include <algorithm>
#include <cmath>

namespace stickslip::widgets {

namespace {

// First index in [from, to + 1) whose x is not below `x` (x non-decreasing).
int lowerBound(const QwtSeriesData<QPointF>& d, int from, int to, double x) {
    int lo = from, hi = to + 1;
    while (lo < hi) {
        const int mid = lo + (hi - lo) / 2;
        if (d.sample(static_cast<size_t>(mid)).x() < x) lo = mid + 1;
        else hi = mid;
    }
    return lo;
}

// First index in [from, to + 1) whose x is above `x`.
int upperBound(const QwtSeriesData<QPointF>& d, int from, int to, double x) {
    int lo = from, hi = to + 1;
    while (lo < hi) {
        const int mid = lo + (hi - lo) / 2;
        if (!(x < d.sample(static_cast<size_t>(mid)).x())) lo = mid + 1;
        else hi = mid;
    }
    return lo;
}

}  // namespace

QPolygonF DecimatedCurve::reducedPolyline(const QwtScaleMap& xMap, const QwtScaleMap& yMap, int from, int to) const {
    QPolygonF out;
    const QwtSeriesData<QPointF>* d = data();
    if (!d || from > to) return out;
    auto device = [&](const QPointF& p) { return QPointF(xMap.transform(p.x()), yMap.transform(p.y())); };
    if (monotonicX_) {
        // Samples in the visible x range plus one on each side (the joins to the border).
        const double lo = std::min(xMap.s1(), xMap.s2()), hi = std::max(xMap.s1(), xMap.s2());
        int first = lowerBound(*d, from, to, lo);
        int last = upperBound(*d, from, to, hi);
        first = std::max(from, first - 1);
        last = std::min(to, last);
        out.reserve(static_cast<int>(4 * std::abs(xMap.p2() - xMap.p1())) + 8);
        int i = first;
        while (i <= last) {
            const QPointF p0 = d->sample(static_cast<size_t>(i));
            const double column = std::floor(xMap.transform(p0.x()));
            int iMin = i, iMax = i, iLast = i;
            double yMin = p0.y(), yMax = p0.y();
            int j = i + 1;
            for (; j <= last; ++j) {
                const QPointF q = d->sample(static_cast<size_t>(j));
                if (!(std::floor(xMap.transform(q.x())) == column)) break;
                if (q.y() < yMin) yMin = q.y(), iMin = j;
                if (q.y() > yMax) yMax = q.y(), iMax = j;
                iLast = j;
            }
            // First, extremes and last of the column, in index order, each once.
            int idx[4] = {i, std::min(iMin, iMax), std::max(iMin, iMax), iLast};
            int prev = -1;
            for (int k : idx) {
                if (k == prev) continue;
                out << device(d->sample(static_cast<size_t>(k)));
                prev = k;
            }
            i = j;
        }
    } else {
        QPointF kept = device(d->sample(static_cast<size_t>(from)));
        out << kept;
        for (int i = from + 1; i < to; ++i) {
            const QPointF p = device(d->sample(static_cast<size_t>(i)));
            if (std::abs(p.x() - kept.x()) > tolerance_px || std::abs(p.y() - kept.y()) > tolerance_px ||
                !std::isfinite(p.x()) || !std::isfinite(p.y())) {
                out << p;
                kept = p;
            }
        }
        if (to > from) out << device(d->sample(static_cast<size_t>(to)));
    }
    return out;
}

void DecimatedCurve::drawLines(QPainter* painter, const QwtScaleMap& xMap, const QwtScaleMap& yMap,
                               const QRectF& canvasRect, int from, int to) const {
    const int n = to - from + 1;
    // Nothing to gain for short or sparse time series; filled or fitted curves keep Qwt's own path.
    const bool sparse = monotonicX_ ? n <= 2 * std::max(1.0, canvasRect.width()) : n <= 8;
    if (sparse || brush().style() != Qt::NoBrush || testCurveAttribute(Fitted)) {
        lastDrawn_ = n;
        QwtPlotCurve::drawLines(painter, xMap, yMap, canvasRect, from, to);
        return;
    }
    QPolygonF poly = reducedPolyline(xMap, yMap, from, to);
    if (QwtPainter::roundingAlignment(painter))
        for (QPointF& p : poly) p = QPointF(std::round(p.x()), std::round(p.y()));
    if (testPaintAttribute(ClipPolygons)) {
        const qreal pw = std::max<qreal>(1.0, painter->pen().widthF());
        poly = QwtClipper::clipPolygonF(canvasRect.adjusted(-pw, -pw, pw, pw), poly, false);
    }
    lastDrawn_ = poly.size();
    QwtPainter::drawPolyline(painter, poly);
}

void PiecewiseCurve::setPieces(QVector<QPair<int, int>> pieces) {
    pieces_ = std::move(pieces);
    piecewise_ = true;
}

void PiecewiseCurve::clearPieces() {
    pieces_.clear();
    piecewise_ = false;
}

QVector<QPointF> PiecewiseCurve::pieceSamples(int k) const {
    QVector<QPointF> out;
    if (k < 0 || k >= pieces_.size()) return out;
    const int n = static_cast<int>(dataSize());
    for (int i = std::max(0, pieces_[k].first); i <= std::min(n - 1, pieces_[k].second); ++i)
        out.append(sample(static_cast<size_t>(i)));
    return out;
}

void PiecewiseCurve::drawLines(QPainter* painter, const QwtScaleMap& xMap, const QwtScaleMap& yMap,
                               const QRectF& canvasRect, int from, int to) const {
    if (!piecewise_) {
        DecimatedCurve::drawLines(painter, xMap, yMap, canvasRect, from, to);
        return;
    }
    int drawn = 0;
    const bool round = QwtPainter::roundingAlignment(painter);
    const qreal pw = std::max<qreal>(1.0, painter->pen().widthF());
    const QRectF clip = canvasRect.adjusted(-pw, -pw, pw, pw);
    for (const auto& [first, last] : pieces_) {
        const int a = std::max(first, from), b = std::min(last, to);
        if (a >= b) continue;   // a single point draws no line
        QPolygonF poly = reducedPolyline(xMap, yMap, a, b);
        if (round)
            for (QPointF& p : poly) p = QPointF(std::round(p.x()), std::round(p.y()));
        if (testPaintAttribute(ClipPolygons)) poly = QwtClipper::clipPolygonF(clip, poly, false);
        drawn += poly.size();
        QwtPainter::drawPolyline(painter, poly);
    }
    lastDrawn_ = drawn;
}

}  // namespace stickslip::widgets
