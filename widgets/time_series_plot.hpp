// Time series of a run (paper Figs 7, 9, 10, 16, 18): stage and slider displacement [mm] on
// the left axis; F/t_N [-], relative velocity V [m/s] and state α [-] on the right axis.
// Channels are selectable, the shown cycle range too; a vertical cursor follows the rig view.
#pragma once

#include "core/integrate/run_result.hpp"
#include "plot_widget.hpp"

class QwtPlotMarker;

namespace stickslip::widgets {

enum class Channel : unsigned {
    Stage = 1u << 0,          // u [mm], left axis
    Slider = 1u << 1,         // x [mm], left axis
    FrictionRatio = 1u << 2,  // F/t_N [-], right axis
    RelVel = 1u << 3,         // V = u̇ − ẋ [m/s], right axis
    Alpha = 1u << 4,          // α [-], right axis
};
constexpr unsigned kAllChannels = 0x1fu;
constexpr unsigned channelBit(Channel c) { return static_cast<unsigned>(c); }

// Short name used in curve titles ("stage u", "slider x", "F/t_N", "V", "alpha").
QString channelName(Channel c);

class TimeSeriesPlot : public PlotWidget {
    Q_OBJECT
public:
    explicit TimeSeriesPlot(QWidget* parent = nullptr);

    // Shows `run` as the curves of model `law`; period_s (1/f) defines cycles for the range.
    // Curve titles: "<model>: <channel>", e.g. "rate-state: slider x".
    void setRun(const RunResult& run, double period_s, LawKind law = LawKind::RateState);

    void setChannels(unsigned channelMask);   // OR of channelBit(...)
    unsigned channels() const { return channels_; }

    // Shows cycles [firstCycle, lastCycle) counted from the run's first sample; lastCycle <=
    // firstCycle shows everything.
    void setCycleRange(double firstCycle, double lastCycle);

    // Measured overlay of one channel (SI values; scaled and put on that channel's axis).
    void addMeasured(Channel channel, const MeasuredSeries& series);

    void clearModel(LawKind law) override;
    void clearAll() override;

    double cursorTime() const { return cursorTime_s_; }

public slots:
    void setCursorTime(double t_s);   // vertical line at t (hidden if NaN)

private:
    struct ModelRun {
        bool present = false;
        RunResult run;
        double period_s = 1.0;
    };
    void rebuild();
    ModelRun runs_[kMaxLawSlots];
    std::vector<std::pair<Channel, MeasuredSeries>> measured_;
    unsigned channels_ = channelBit(Channel::Stage) | channelBit(Channel::Slider) | channelBit(Channel::FrictionRatio);
    double firstCycle_ = 0.0, lastCycle_ = 0.0;
    double cursorTime_s_;
    QwtPlotMarker* cursor_ = nullptr;
};

}  // namespace stickslip::widgets
