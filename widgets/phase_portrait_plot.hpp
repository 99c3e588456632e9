// Phase portrait (paper Figs 21, 22): relative velocity V [m/s] versus slider displacement x [mm].
#pragma once

#include "core/integrate/run_result.hpp"
#include "plot_widget.hpp"

namespace stickslip::widgets {

class PhasePortraitPlot : public PlotWidget {
    Q_OBJECT
public:
    explicit PhasePortraitPlot(QWidget* parent = nullptr);
    // Curve "<model>: trajectory".
    void setRun(const RunResult& run, LawKind law = LawKind::RateState);
};

}  // namespace stickslip::widgets
