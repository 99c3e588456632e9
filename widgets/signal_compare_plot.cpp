#include "signal_compare_plot.hpp"

#include <qwt_plot.h>
#include <qwt_plot_curve.h>
#include <qwt_graphic.h>
#include <qwt_plot_zoneitem.h>
#include <qwt_plot_zoomer.h>

#include <QPainter>

#include <algorithm>
#include <cmath>

#include "plot_style.hpp"

namespace stickslip::widgets {

namespace {

// A zone item with a legend swatch of its own brush and pen.
class WindowZone : public QwtPlotZoneItem {
public:
    QwtGraphic legendIcon(int, const QSizeF& size) const override {
        QwtGraphic icon;
        icon.setDefaultSize(size);
        if (size.isEmpty()) return icon;
        QPainter painter(&icon);
        painter.setPen(pen());
        painter.setBrush(brush());
        painter.drawRect(QRectF(QPointF(0, 0), size).adjusted(0.5, 0.5, -0.5, -0.5));
        return icon;
    }
};

}  // namespace

SignalComparePlot::SignalComparePlot(QWidget* parent) : PlotWidget(parent) {
    setAxisTitles(QStringLiteral("time t [s]"), QString());
    window_ = new WindowZone;
    window_->setTitle(QStringLiteral("fit window"));
    window_->setOrientation(Qt::Vertical);
    window_->setBrush(QColor(44, 160, 44, 28));
    window_->setPen(QPen(QColor(44, 160, 44, 110), 1, Qt::DashLine));
    window_->setItemAttribute(QwtPlotItem::Legend, true);
    window_->setLegendIconSize(QSize(14, 8));
    window_->setZ(1);
    window_->attach(plot_);
    window_->setVisible(false);
    applyFonts();
}

void SignalComparePlot::showTimeRange(double t0_s, double t1_s) {
    if (!(t1_s > t0_s)) return;
    double lo = 0.0, hi = 0.0;
    bool any = false;
    auto scan = [&](const std::vector<double>& t, const std::vector<double>& y) {
        for (size_t i = 0; i < std::min(t.size(), y.size()); ++i) {
            if (t[i] < t0_s || t[i] > t1_s) continue;
            const double v = y[i] * data_.displayFactor;
            lo = any ? std::min(lo, v) : v;
            hi = any ? std::max(hi, v) : v;
            any = true;
        }
    };
    scan(data_.rawTime_s, data_.raw);
    scan(data_.cleanTime_s, data_.clean);
    if (!any) return;
    const double pad = hi > lo ? 0.05 * (hi - lo) : std::max(1e-12, 1e-3 * std::abs(hi));
    plot_->setAxisScale(QwtPlot::xBottom, t0_s, t1_s);
    plot_->setAxisScale(QwtPlot::yLeft, lo - pad, hi + pad);
    plot_->replot();
    zoomer_->setZoomBase(false);
}

bool SignalComparePlot::hasWindow() const { return window_->isVisible(); }

void SignalComparePlot::clearAll() {
    data_ = SignalComparison{};
    window_->setVisible(false);
    PlotWidget::clearAll();
}

void SignalComparePlot::setComparison(const SignalComparison& c) {
    plot_->detachItems(QwtPlotItem::Rtti_PlotCurve, true);
    data_ = c;
    setFactors(1.0, c.displayFactor);
    setAxisTitles(QStringLiteral("time t [s]"), c.signalTitle);
    auto samples = [&](const std::vector<double>& t, const std::vector<double>& y) {
        QVector<QPointF> pts;
        const size_t n = std::min(t.size(), y.size());
        pts.reserve(static_cast<int>(n));
        for (size_t i = 0; i < n; ++i) pts.append(QPointF(t[i], y[i] * c.displayFactor));
        return pts;
    };
    if (!c.raw.empty()) {
        auto* raw = addCurve(QStringLiteral("raw"), QPen(QColor(150, 150, 150), 1.0));
        raw->setSamples(samples(c.rawTime_s, c.raw));
        raw->setZ(10);
    }
    if (!c.clean.empty()) {
        auto* clean = addCurve(QStringLiteral("cleaned"), QPen(style::rateState(), 1.6));
        clean->setSamples(samples(c.cleanTime_s, c.clean));
        clean->setZ(20);
    }
    const bool hasWindow = c.windowEnd_s > c.windowBegin_s;
    if (hasWindow) window_->setInterval(c.windowBegin_s, c.windowEnd_s);
    window_->setVisible(hasWindow);
    rescale();
}

}  // namespace stickslip::widgets
