#include "spectrum_plot.hpp"

#include <qwt_plot.h>
#include <qwt_plot_curve.h>
#include <qwt_scale_engine.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "plot_style.hpp"

namespace stickslip::widgets {

SpectrumPlot::SpectrumPlot(QWidget* parent) : PlotWidget(parent) {
    plot_->setTitle(QStringLiteral("Power spectral density"));
    setAxisTitles(QStringLiteral("frequency f [Hz]"), QStringLiteral("PSD [unit²/Hz]"));
    plot_->setAxisScaleEngine(QwtPlot::yLeft, new QwtLogScaleEngine);
    setFactors(1.0, 1.0);
}

void SpectrumPlot::setValueTitle(const QString& title) {
    if (plot_->axisTitle(QwtPlot::yLeft).text() == title) return;
    plot_->setAxisTitle(QwtPlot::yLeft, title);
    plot_->replot();
}

void SpectrumPlot::setSpectrum(const std::vector<double>& freq_Hz, const std::vector<double>& psd, LawKind law) {
    const size_t n = std::min(freq_Hz.size(), psd.size());
    // A log axis cannot show zeros: clamp to the smallest positive value (or 1e-300).
    double floor = std::numeric_limits<double>::infinity();
    for (size_t i = 0; i < n; ++i)
        if (psd[i] > 0 && std::isfinite(psd[i])) floor = std::min(floor, psd[i]);
    if (!std::isfinite(floor)) floor = 1e-300;
    QVector<QPointF> pts;
    pts.reserve(static_cast<int>(n));
    for (size_t i = 0; i < n; ++i) pts.append(QPointF(freq_Hz[i], std::max(psd[i], floor)));
    auto* c = reuseCurve(modelLabel(law) + QStringLiteral(": PSD"), law, style::modelColor(law));
    c->setSamples(pts);
    rescale();
}

}  // namespace stickslip::widgets
