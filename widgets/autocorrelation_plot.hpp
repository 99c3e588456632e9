// Normalised autocorrelation versus lag (paper Figs 2, 5, 12, 22).
#pragma once

#include <vector>

#include "plot_widget.hpp"

namespace stickslip::widgets {

class AutocorrelationPlot : public PlotWidget {
    Q_OBJECT
public:
    explicit AutocorrelationPlot(QWidget* parent = nullptr);
    // Curve "<model>: autocorrelation"; lags in s, r in [-1, 1].
    void setAutocorrelation(const std::vector<double>& lag_s, const std::vector<double>& r,
                            LawKind law = LawKind::RateState);
};

}  // namespace stickslip::widgets
