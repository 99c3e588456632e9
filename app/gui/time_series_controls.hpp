// A strip above the time series: which channels to show (u, x, F/t_N, V, α) and the cycle
// range [from, to) (to = 0 shows every cycle). It only forwards choices to the plot.
#pragma once

#include <QWidget>

class QDoubleSpinBox;

namespace stickslip::widgets {
class TimeSeriesPlot;
}

namespace stickslip::gui {

class TimeSeriesControls : public QWidget {
    Q_OBJECT
public:
    TimeSeriesControls(widgets::TimeSeriesPlot* plot, QWidget* parent = nullptr);
    QDoubleSpinBox* firstCycleBox() const { return first_; }
    QDoubleSpinBox* lastCycleBox() const { return last_; }

private:
    widgets::TimeSeriesPlot* plot_;
    QDoubleSpinBox* first_;
    QDoubleSpinBox* last_;
};

}  // namespace stickslip::gui
