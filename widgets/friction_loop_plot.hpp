// F/t_N versus relative velocity V (paper Figs 8, 17), one closed loop per forcing cycle,
// coloured by its orientation: clockwise (blue) or counter-clockwise (red). The rate-state law
// only gives clockwise loops; measured ones can be counter-clockwise (MODEL.md fact 6).
#pragma once

#include "core/integrate/run_result.hpp"
#include "plot_widget.hpp"

class QwtPlotTextLabel;

namespace stickslip::widgets {

// Orientation of one cycle's loop in the (V, F/t_N) plane (x right, y up).
struct LoopMark {
    int cycle = 0;             // 0-based cycle index within the run
    double t0_s = 0, t1_s = 0; // the cycle's time span
    double signedArea = 0;     // shoelace area [m/s · 1] (core frictionLoopOrientation); > 0 counter-clockwise
    int orientation = 0;       // −1 clockwise, +1 counter-clockwise, 0 degenerate (|area| ≤ 1e-3 × bounding box)
};

class FrictionLoopPlot : public PlotWidget {
    Q_OBJECT
public:
    explicit FrictionLoopPlot(QWidget* parent = nullptr);

    // One curve per complete cycle: "<model>: cycle N cw" / "… ccw" / "… flat"; cycles counted
    // from the first sample (an incomplete last cycle is drawn grey: "<model>: partial").
    // The orientation comes from core frictionLoopOrientation (analysis/loop_orientation.hpp).
    void setRun(const RunResult& run, double period_s, LawKind law = LawKind::RateState);
    const std::vector<LoopMark>& loopMarks(LawKind law) const;

    void clearModel(LawKind law) override;
    void clearAll() override;

private:
    void updateSummary();
    std::vector<LoopMark> marks_[2];
    QwtPlotTextLabel* summary_ = nullptr;
};

}  // namespace stickslip::widgets
