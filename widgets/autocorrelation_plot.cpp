#include "autocorrelation_plot.hpp"

#include <qwt_plot.h>
#include <qwt_plot_curve.h>
#include <qwt_plot_marker.h>

#include <algorithm>

#include "decimated_curve.hpp"
#include "plot_style.hpp"

namespace stickslip::widgets {

AutocorrelationPlot::AutocorrelationPlot(QWidget* parent) : PlotWidget(parent) {
    plot_->setTitle(QStringLiteral("Autocorrelation"));
    setAxisTitles(QStringLiteral("lag τ [s]"), QStringLiteral("autocorrelation R(τ)/R(0) [-]"));
    setFactors(1.0, 1.0);
    auto* zero = new QwtPlotMarker;
    zero->setLineStyle(QwtPlotMarker::HLine);
    zero->setLinePen(QPen(QColor(150, 150, 150), 0.8));
    zero->setYValue(0.0);
    zero->attach(plot_);
}

void AutocorrelationPlot::setAutocorrelation(const std::vector<double>& lag_s, const std::vector<double>& r,
                                             LawKind law) {
    QVector<QPointF> pts;
    const size_t n = std::min(lag_s.size(), r.size());
    pts.reserve(static_cast<int>(n));
    for (size_t i = 0; i < n; ++i) pts.append(QPointF(lag_s[i], r[i]));
    auto* c = static_cast<DecimatedCurve*>(
        reuseCurve(modelLabel(law) + QStringLiteral(": autocorrelation"), law, style::modelColor(law)));
    c->setMonotonicX(std::is_sorted(lag_s.begin(), lag_s.begin() + static_cast<std::ptrdiff_t>(n)));
    c->setSamples(pts);
    rescale();
}

}  // namespace stickslip::widgets
