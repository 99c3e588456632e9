#include "series_plot.hpp"

#include <qwt_plot.h>
#include <qwt_plot_curve.h>
#include <qwt_plot_marker.h>
#include <qwt_scale_engine.h>
#include <qwt_symbol.h>

#include <cmath>

namespace stickslip::widgets {

SeriesPlot::SeriesPlot(QWidget* parent) : PlotWidget(parent) { setFactors(1.0, 1.0); }

void SeriesPlot::setTitles(const QString& title, const QString& xTitle, const QString& yTitle) {
    plot_->setTitle(title);
    setAxisTitles(xTitle, yTitle);
    applyFonts();
    plot_->replot();
}

void SeriesPlot::setLogY(bool on) {
    if (on == logY_) return;
    logY_ = on;
    if (on) plot_->setAxisScaleEngine(QwtPlot::yLeft, new QwtLogScaleEngine);
    else plot_->setAxisScaleEngine(QwtPlot::yLeft, new QwtLinearScaleEngine);
    rescale();
}

void SeriesPlot::setSeries(const std::vector<PlotSeries>& series) {
    plot_->detachItems(QwtPlotItem::Rtti_PlotCurve, true);
    for (const PlotSeries& s : series) {
        QPen pen(s.color, s.width, s.dashed ? Qt::DashLine : Qt::SolidLine);
        QwtPlotCurve* c = addCurve(s.label, pen);
        if (s.dots) {
            c->setStyle(QwtPlotCurve::Dots);
            c->setSymbol(new QwtSymbol(QwtSymbol::Ellipse, QBrush(s.color), QPen(s.color), QSize(3, 3)));
        }
        QVector<QPointF> pts;
        const size_t n = std::min(s.x.size(), s.y.size());
        pts.reserve(static_cast<int>(n));
        for (size_t i = 0; i < n; ++i) {
            if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i])) continue;
            if (logY_ && !(s.y[i] > 0)) continue;
            pts.append(QPointF(s.x[i], s.y[i]));
        }
        c->setSamples(pts);
    }
    rescale();
}

void SeriesPlot::clearLines(std::vector<QwtPlotMarker*>& lines) {
    for (QwtPlotMarker* m : lines) {
        m->detach();
        delete m;
    }
    lines.clear();
}

void SeriesPlot::setVerticalLines(const std::vector<double>& x, const QColor& color) {
    clearLines(vlines_);
    for (double v : x) {
        auto* m = new QwtPlotMarker;
        m->setLineStyle(QwtPlotMarker::VLine);
        m->setLinePen(QPen(color, 0.8, Qt::DotLine));
        m->setXValue(v);
        m->setZ(5);
        m->attach(plot_);
        vlines_.push_back(m);
    }
    plot_->replot();
}

void SeriesPlot::setHorizontalLines(const std::vector<double>& y, const QColor& color) {
    clearLines(hlines_);
    for (double v : y) {
        auto* m = new QwtPlotMarker;
        m->setLineStyle(QwtPlotMarker::HLine);
        m->setLinePen(QPen(color, 0.8, Qt::DashLine));
        m->setYValue(v);
        m->setZ(5);
        m->attach(plot_);
        hlines_.push_back(m);
    }
    plot_->replot();
}

void SeriesPlot::clearAll() {
    clearLines(vlines_);
    clearLines(hlines_);
    PlotWidget::clearAll();
}

int SeriesPlot::seriesCount() const { return curves().size(); }

}  // namespace stickslip::widgets
