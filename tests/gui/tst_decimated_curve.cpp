// DecimatedCurve: the drawn polyline keeps every pixel column's extent (monotonic x) and
// every sample within the tolerance (retraced loops).
#include <qwt_scale_map.h>

#include <QtTest>
#include <cmath>
#include <map>

#include "widgets/decimated_curve.hpp"

using namespace stickslip::widgets;

namespace {

// x → [0, width) px, y → [height, 0) px over the data's range.
void maps(const QVector<QPointF>& pts, double width, double height, QwtScaleMap& xm, QwtScaleMap& ym) {
    double x0 = INFINITY, x1 = -INFINITY, y0 = INFINITY, y1 = -INFINITY;
    for (const QPointF& p : pts) {
        x0 = std::min(x0, p.x());
        x1 = std::max(x1, p.x());
        y0 = std::min(y0, p.y());
        y1 = std::max(y1, p.y());
    }
    xm.setScaleInterval(x0, x1);
    xm.setPaintInterval(0, width);
    ym.setScaleInterval(y0, y1);
    ym.setPaintInterval(height, 0);
}

}  // namespace

class TestDecimatedCurve : public QObject {
    Q_OBJECT
private slots:
    void decimationKeepsEveryColumnExtent();
    void decimationOfLoopsStaysWithinTolerance();
};

void TestDecimatedCurve::decimationKeepsEveryColumnExtent() {
    // A noisy fast oscillation, ~27 samples per pixel column, plus a spike in one sample.
    QVector<QPointF> pts;
    const int n = 20000;
    for (int i = 0; i < n; ++i) {
        const double t = i * 1e-4;
        pts.append(QPointF(t, std::sin(2 * M_PI * 37 * t) + 0.3 * std::sin(2 * M_PI * 911 * t) + (i == 12345 ? 5.0 : 0.0)));
    }
    DecimatedCurve c("x");
    c.setMonotonicX(true);
    c.setSamples(pts);
    QCOMPARE(c.dataSize(), size_t(n));   // the curve keeps every sample (export, tests)
    QwtScaleMap xm, ym;
    maps(pts, 733, 300, xm, ym);
    const QPolygonF poly = c.reducedPolyline(xm, ym, 0, n - 1);
    QVERIFY2(poly.size() <= 4 * 734 && poly.size() > 734, qPrintable(QString::number(poly.size())));
    QCOMPARE(poly.front(), QPointF(xm.transform(pts.front().x()), ym.transform(pts.front().y())));
    QCOMPARE(poly.back(), QPointF(xm.transform(pts.back().x()), ym.transform(pts.back().y())));
    // Per pixel column, the drawn points span exactly the full data's vertical extent.
    std::map<int, std::pair<double, double>> full, drawn;
    auto add = [](std::map<int, std::pair<double, double>>& m, double x, double y) {
        const int col = static_cast<int>(std::floor(x));
        auto it = m.find(col);
        if (it == m.end()) m[col] = {y, y};
        else it->second = {std::min(it->second.first, y), std::max(it->second.second, y)};
    };
    for (const QPointF& p : pts) add(full, xm.transform(p.x()), ym.transform(p.y()));
    for (const QPointF& p : poly) add(drawn, p.x(), p.y());
    QCOMPARE(drawn.size(), full.size());
    for (const auto& [col, ext] : full) {
        QCOMPARE(drawn[col].first, ext.first);
        QCOMPARE(drawn[col].second, ext.second);
    }
    // Drawn in order of x (the polyline never goes back).
    for (int i = 1; i < poly.size(); ++i) QVERIFY(poly[i].x() >= poly[i - 1].x());
    // Zoomed in: only the visible columns (plus one sample each side) are drawn.
    QwtScaleMap zx = xm;
    zx.setScaleInterval(0.5, 0.6);
    const QPolygonF zoomed = c.reducedPolyline(zx, ym, 0, n - 1);
    QVERIFY(zoomed.size() <= 4 * 734 + 8);
    QVERIFY(zoomed.front().x() <= 0 && zoomed.front().x() > -733.0 * 1e-4 / 0.1 - 1e-9);
    QVERIFY(zoomed.back().x() >= 733 && zoomed.back().x() < 733 + 733.0 * 1e-4 / 0.1 + 1e-9);
}

void TestDecimatedCurve::decimationOfLoopsStaysWithinTolerance() {
    // Twenty retraced loops (not monotonic in x), dense enough for the weeding to act.
    QVector<QPointF> pts;
    for (int i = 0; i < 200000; ++i) {
        const double th = 2 * M_PI * 20 * i / 200000.0;
        pts.append(QPointF(std::cos(th) * (1 + 0.01 * std::sin(13 * th)), std::sin(2 * th)));
    }
    DecimatedCurve c("loop");
    c.setSamples(pts);
    QwtScaleMap xm, ym;
    maps(pts, 300, 200, xm, ym);
    const QPolygonF poly = c.reducedPolyline(xm, ym, 0, pts.size() - 1);
    QVERIFY2(poly.size() < pts.size() / 2, qPrintable(QString::number(poly.size())));
    // Every sample lies within the tolerance (per axis) of the last vertex drawn before it,
    // vertices are samples in order, and the first and last samples are drawn.
    int v = 0;
    for (const QPointF& p : pts) {
        const QPointF d(xm.transform(p.x()), ym.transform(p.y()));
        if (v + 1 < poly.size() && poly[v + 1] == d) ++v;
        QVERIFY(std::abs(d.x() - poly[v].x()) <= DecimatedCurve::tolerance_px + 1e-12);
        QVERIFY(std::abs(d.y() - poly[v].y()) <= DecimatedCurve::tolerance_px + 1e-12);
    }
    QCOMPARE(v, poly.size() - 1);
}

QTEST_MAIN(TestDecimatedCurve)
#include "tst_decimated_curve.moc"
