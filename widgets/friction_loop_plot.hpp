// F/t_N versus relative velocity V (paper Figs 8, 17). The paper's loops are the slip
// excursions (one sign of V between reversals, core frictionLoops): each is drawn coloured by
// its orientation, clockwise (blue) or counter-clockwise (red), over the whole trajectory in
// light grey (stick and elastic reversal segments). The rate-state law only gives clockwise
// loops; measured ones can be counter-clockwise (MODEL.md fact 6).
#pragma once

#include "core/integrate/run_result.hpp"
#include "plot_widget.hpp"

class QwtPlotTextLabel;

namespace stickslip::widgets {

// Orientation of one slip excursion's loop in the (V, F/t_N) plane (x right, y up).
struct LoopMark {
    int index = 0;             // 0-based excursion index within the run
    int sign = 0;              // sign of V during the excursion (+1 / −1)
    double t0_s = 0, t1_s = 0; // the excursion's time span
    double signedArea = 0;     // shoelace area closed by the chord [m/s · 1] (core frictionLoops); > 0 ccw
    int orientation = 0;       // −1 clockwise, +1 counter-clockwise, 0 degenerate (|area| ≤ 1e-3 × bounding box)
};

class FrictionLoopPlot : public PlotWidget {
    Q_OBJECT
public:
    explicit FrictionLoopPlot(QWidget* parent = nullptr);

    // Curves "<model>: trajectory" (grey, every sample; drawn where no loop covers it) and,
    // per orientation, "<model>: loops cw" / "… ccw" / "… flat": the complete slip excursions of
    // that orientation, one piece each (PiecewiseCurve::pieces, in time order; partial
    // first/last excursions are not marked).
    void setRun(const RunResult& run, LawKind law = LawKind::RateState);
    // Same; the forcing period is not needed for the excursion loops (kept for symmetry).
    void setRun(const RunResult& run, double /*period_s*/, LawKind law = LawKind::RateState) { setRun(run, law); }
    const std::vector<LoopMark>& loopMarks(LawKind law) const;

    void clearModel(LawKind law) override;
    void clearAll() override;

private:
    void updateSummary();
    std::vector<LoopMark> marks_[kMaxLawSlots];
    QwtPlotTextLabel* summary_ = nullptr;
};

}  // namespace stickslip::widgets
