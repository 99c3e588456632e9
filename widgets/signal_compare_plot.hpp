// One measured signal before and after cleaning (issue 5): the raw samples in grey, the
// cleaned signal in blue on top, and the fit window (the samples kept after trimming)
// shaded. Values are given in SI and shown times a display factor (e.g. 1e3 for mm).
#pragma once

#include <vector>

#include "plot_widget.hpp"

class QwtPlotZoneItem;

namespace stickslip::widgets {

struct SignalComparison {
    QString signalTitle;            // y axis title, e.g. "friction force F [N]"
    double displayFactor = 1.0;     // value shown = SI value * factor
    std::vector<double> rawTime_s, raw;          // raw signal (may be empty: derived signal)
    std::vector<double> cleanTime_s, clean;      // cleaned signal
    double windowBegin_s = 0.0, windowEnd_s = 0.0;  // fit window; begin >= end: none
};

class SignalComparePlot : public PlotWidget {
    Q_OBJECT
public:
    explicit SignalComparePlot(QWidget* parent = nullptr);

    // Curves "raw" and "cleaned" (a missing one is not attached), zoom base reset.
    void setComparison(const SignalComparison& c);
    void clearAll() override;
    // Shows [t0, t1] with the y range of the samples inside it, as the zoom base.
    void showTimeRange(double t0_s, double t1_s);
    const SignalComparison& comparison() const { return data_; }
    bool hasWindow() const;

private:
    SignalComparison data_;
    QwtPlotZoneItem* window_ = nullptr;
};

}  // namespace stickslip::widgets
