// Power spectral density on a logarithmic y axis (paper Figs 2, 4, 5, 12, 22).
#pragma once

#include <vector>

#include "plot_widget.hpp"

namespace stickslip::widgets {

class SpectrumPlot : public PlotWidget {
    Q_OBJECT
public:
    explicit SpectrumPlot(QWidget* parent = nullptr);
    // y title, e.g. "PSD of x [m²/Hz]" (values are plotted as given; zeros are clamped to
    // the smallest positive value for the log scale).
    void setValueTitle(const QString& title);
    // Curve "<model>: PSD"; frequencies in Hz.
    void setSpectrum(const std::vector<double>& freq_Hz, const std::vector<double>& psd,
                     LawKind law = LawKind::RateState);
};

}  // namespace stickslip::widgets
