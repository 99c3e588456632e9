#include "poincare_plot.hpp"

#include <cmath>

#include <qwt_plot.h>
#include <qwt_plot_curve.h>
#include <qwt_symbol.h>

#include "plot_style.hpp"

namespace stickslip::widgets {

PoincarePlot::PoincarePlot(QWidget* parent) : PlotWidget(parent) {
    plot_->setTitle(QStringLiteral("Poincaré section"));
    setAxisTitles(QStringLiteral("slider displacement x [mm]"), QStringLiteral("relative velocity V [m/s]"));
    setFactors(1.0e3, 1.0);
}

void PoincarePlot::setOrbitExtent(double slider_m, double relVel_mps) {
    constexpr double kVisibleFraction = 1e-2;  // a few pixels of a dock-sized axis: about one dot
    setMinimumSpans(kVisibleFraction * std::abs(slider_m) * xFactor_, kVisibleFraction * std::abs(relVel_mps) * yFactor_);
}

void PoincarePlot::setSection(const std::vector<double>& slider_m, const std::vector<double>& relVel_mps, LawKind law) {
    removeCurvesWithPrefix(modelLabel(law) + QLatin1Char(':'));
    QVector<QPointF> pts;
    const size_t n = std::min(slider_m.size(), relVel_mps.size());
    pts.reserve(static_cast<int>(n));
    for (size_t i = 0; i < n; ++i) pts.append(QPointF(slider_m[i] * xFactor_, relVel_mps[i] * yFactor_));
    auto* c = addCurve(modelLabel(law) + QStringLiteral(": section"), law, style::modelColor(law));
    c->setStyle(QwtPlotCurve::NoCurve);
    const QColor col = style::modelColor(law);
    c->setSymbol(new QwtSymbol(style::slot(law) % 3 == 1 ? QwtSymbol::Cross : style::slot(law) % 3 == 2 ? QwtSymbol::Triangle : QwtSymbol::Ellipse, QBrush(col), QPen(col),
                               n > 2000 ? QSize(2, 2) : QSize(4, 4)));
    c->setSamples(pts);
    rescale();
}

}  // namespace stickslip::widgets
