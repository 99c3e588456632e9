// Bifurcation diagram (paper Figs 11, 13, 19, 20, 23): the Poincaré samples of one quantity
// versus the swept parameter, up and down branches overlaid in two colours. Columns can be
// appended one parameter value at a time while a sweep streams in.
#pragma once

#include <vector>

#include "core/analysis/sweep.hpp"
#include "plot_widget.hpp"

namespace stickslip::widgets {

enum class SweepBranch { Up, Down };

class BifurcationPlot : public PlotWidget {
    Q_OBJECT
public:
    explicit BifurcationPlot(QWidget* parent = nullptr);

    // Axis titles with units and the display factors (shown = SI * factor). Defaults:
    // "A [mm]" x1e3 and "slider displacement x [mm]" x1e3. Call before appending.
    void setAxes(const QString& paramTitle, double paramFactor, const QString& valueTitle, double valueFactor);

    // Adds the samples kept at one parameter value (SI) to the branch's dot curve
    // "<model>: up" / "<model>: down". Cheap: replots at most every 50 ms.
    void appendColumn(SweepBranch branch, double paramValue, const std::vector<double>& values,
                      LawKind law = LawKind::RateState);
    // One streamed sweep point: its section's slider displacements on its branch.
    void appendPoint(const SweepPoint& point, LawKind law = LawKind::RateState) {
        appendColumn(point.direction < 0 ? SweepBranch::Down : SweepBranch::Up, point.value, point.section.slider_m, law);
    }
    void clearAll() override;
    void clearModel(LawKind law) override;
    int pointCount() const;

private:
    void scheduleReplot();
    bool replotPending_ = false;
};

}  // namespace stickslip::widgets
