#include "phase_portrait_plot.hpp"

#include <qwt_plot.h>
#include <qwt_plot_curve.h>

#include "plot_style.hpp"

namespace stickslip::widgets {

PhasePortraitPlot::PhasePortraitPlot(QWidget* parent) : PlotWidget(parent) {
    plot_->setTitle(QStringLiteral("Phase portrait"));
    setAxisTitles(QStringLiteral("slider displacement x [mm]"), QStringLiteral("relative velocity V [m/s]"));
    setFactors(1.0e3, 1.0);
}

void PhasePortraitPlot::setRun(const RunResult& run, LawKind law) {
    QVector<QPointF> pts;
    pts.reserve(static_cast<int>(run.samples.size()));
    for (const Sample& s : run.samples) pts.append(QPointF(s.slider_m * xFactor_, s.relVel_mps * yFactor_));
    auto* c = reuseCurve(modelLabel(law) + QStringLiteral(": trajectory"),
                         QPen(style::modelColor(law), 0.8, style::modelPenStyle(law)));
    c->setSamples(pts);
    rescale();
}

}  // namespace stickslip::widgets
