#include "time_series_plot.hpp"

#include <qwt_plot.h>
#include <qwt_plot_curve.h>
#include <qwt_plot_marker.h>
#include <qwt_plot_picker.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "decimated_curve.hpp"
#include "plot_style.hpp"

namespace stickslip::widgets {

namespace {

constexpr Channel kChannels[] = {Channel::Stage, Channel::Slider, Channel::FrictionRatio, Channel::RelVel,
                                 Channel::Alpha};

int channelIndex(Channel c) {
    for (int i = 0; i < 5; ++i)
        if (kChannels[i] == c) return i;
    return 0;
}

bool onLeftAxis(Channel c) { return c == Channel::Stage || c == Channel::Slider; }

// Display value of a channel: displacements in mm, the rest in SI.
double factor(Channel c) { return onLeftAxis(c) ? 1.0e3 : 1.0; }

double value(const Sample& s, Channel c) {
    switch (c) {
        case Channel::Stage: return s.stage_m;
        case Channel::Slider: return s.slider_m;
        case Channel::FrictionRatio: return s.ratio;
        case Channel::RelVel: return s.relVel_mps;
        case Channel::Alpha: return s.alpha;
    }
    return 0.0;
}

QString unitTitle(Channel c) {
    switch (c) {
        case Channel::Stage: return QStringLiteral("stage u [mm]");
        case Channel::Slider: return QStringLiteral("slider x [mm]");
        case Channel::FrictionRatio: return QStringLiteral("F/t_N [-]");
        case Channel::RelVel: return QStringLiteral("V [m/s]");
        case Channel::Alpha: return QStringLiteral("α [-]");
    }
    return {};
}

}  // namespace

QString channelName(Channel c) {
    switch (c) {
        case Channel::Stage: return QStringLiteral("stage u");
        case Channel::Slider: return QStringLiteral("slider x");
        case Channel::FrictionRatio: return QStringLiteral("F/t_N");
        case Channel::RelVel: return QStringLiteral("V");
        case Channel::Alpha: return QStringLiteral("alpha");
    }
    return {};
}

TimeSeriesPlot::TimeSeriesPlot(QWidget* parent)
    : PlotWidget(parent), cursorTime_s_(std::numeric_limits<double>::quiet_NaN()) {
    plot_->setTitle(QStringLiteral("Time series"));
    setFactors(1.0, 1.0e3);
    cursor_ = new QwtPlotMarker;
    cursor_->setLineStyle(QwtPlotMarker::VLine);
    cursor_->setLinePen(QPen(QColor(0, 0, 0, 160), 1.0, Qt::DashDotLine));
    cursor_->setZ(40);
    cursor_->setVisible(false);
    cursor_->attach(plot_);
    rebuild();
}

void TimeSeriesPlot::setRun(const RunResult& run, double period_s, LawKind law) {
    auto& slot = runs_[style::slot(law)];
    slot.present = true;
    slot.run = run;
    slot.period_s = period_s > 0 ? period_s : 1.0;
    rebuild();
}

void TimeSeriesPlot::setChannels(unsigned channelMask) {
    channels_ = channelMask & kAllChannels;
    rebuild();
}

void TimeSeriesPlot::setCycleRange(double firstCycle, double lastCycle) {
    firstCycle_ = firstCycle;
    lastCycle_ = lastCycle;
    rebuild();
}

void TimeSeriesPlot::addMeasured(Channel channel, const MeasuredSeries& series) {
    measured_.emplace_back(channel, series);
    rebuild();
}

void TimeSeriesPlot::clearModel(LawKind law) {
    runs_[style::slot(law)] = ModelRun{};
    rebuild();
}

void TimeSeriesPlot::clearAll() {
    runs_[0] = runs_[1] = ModelRun{};
    measured_.clear();
    rebuild();
}

void TimeSeriesPlot::setCursorTime(double t_s) {
    // A new run restarts the rig at the same time: nothing to redraw then.
    if (t_s == cursorTime_s_ || (std::isnan(t_s) && std::isnan(cursorTime_s_))) return;
    cursorTime_s_ = t_s;
    cursor_->setVisible(std::isfinite(t_s));
    if (std::isfinite(t_s)) cursor_->setXValue(t_s);
    plot_->replot();
}

void TimeSeriesPlot::rebuild() {
    // The curves already attached are reused by title (setSamples only): detaching and
    // attaching curves re-lays out the legend on every result.
    std::vector<QwtPlotCurve*> old;
    for (auto* c : curves()) old.push_back(c);
    auto curveFor = [&](const QString& title, const QPen& pen, int yAxis) {
        auto it = std::find_if(old.begin(), old.end(), [&](QwtPlotCurve* c) { return c->title().text() == title; });
        QwtPlotCurve* c = nullptr;
        if (it != old.end()) {
            c = *it;
            old.erase(it);
            c->setPen(pen);
            c->setYAxis(yAxis);
        } else {
            c = addCurve(title, pen, yAxis);
        }
        return static_cast<DecimatedCurve*>(c);
    };
    QStringList leftTitles, rightTitles;
    bool anyRight = false;
    for (Channel c : kChannels) {
        if (!(channels_ & channelBit(c))) continue;
        (onLeftAxis(c) ? leftTitles : rightTitles) << unitTitle(c);
        anyRight = anyRight || !onLeftAxis(c);
    }
    const bool anyLeft = !leftTitles.isEmpty();
    plot_->enableAxis(QwtPlot::yRight, anyRight && anyLeft);
    // With only right-axis channels selected, draw them on the left axis.
    const int rightAxis = anyLeft ? QwtPlot::yRight : QwtPlot::yLeft;
    plot_->setAxisTitle(QwtPlot::yLeft, anyLeft ? leftTitles.join(QStringLiteral(", ")) : rightTitles.join(QStringLiteral(", ")));
    plot_->setAxisTitle(QwtPlot::yRight, rightTitles.join(QStringLiteral(", ")));
    plot_->setAxisTitle(QwtPlot::xBottom, QStringLiteral("time t [s]"));
    picker_->setAxis(QwtPlot::xBottom, QwtPlot::yLeft);
    setFactors(1.0, anyLeft ? 1.0e3 : 1.0);

    for (int k = 0; k < kMaxLawSlots; ++k) {
        const LawKind law = static_cast<LawKind>(k);
        const ModelRun& mr = runs_[style::slot(law)];
        if (!mr.present || mr.run.samples.empty()) continue;
        const auto& samples = mr.run.samples;
        const double t0 = samples.front().t_s;
        const bool ranged = lastCycle_ > firstCycle_;
        const double tBegin = t0 + firstCycle_ * mr.period_s;
        const double tEnd = t0 + lastCycle_ * mr.period_s;
        for (Channel c : kChannels) {
            if (!(channels_ & channelBit(c))) continue;
            QVector<QPointF> pts;
            pts.reserve(static_cast<int>(samples.size()));
            for (const Sample& s : samples) {
                if (ranged && (s.t_s < tBegin - 1e-12 || s.t_s >= tEnd - 1e-12)) continue;
                pts.append(QPointF(s.t_s, value(s, c) * factor(c)));
            }
            DecimatedCurve* curve = curveFor(modelLabel(law) + QStringLiteral(": ") + channelName(c),
                                             QPen(style::channelColor(channelIndex(c)), style::kModelLineWidth, style::modelPenStyle(law)),
                                             onLeftAxis(c) ? QwtPlot::yLeft : rightAxis);
            curve->setMonotonicX(true);   // the run's time
            curve->setSamples(pts);
        }
    }
    for (const auto& [c, series] : measured_) {
        if (!(channels_ & channelBit(c))) continue;
        DecimatedCurve* curve =
            curveFor(series.label.isEmpty() ? QStringLiteral("measured: ") + channelName(c) : series.label,
                     QPen(style::measured(), 1.0, Qt::DotLine), onLeftAxis(c) ? QwtPlot::yLeft : rightAxis);
        QVector<QPointF> pts;
        const size_t n = std::min(series.x.size(), series.y.size());
        for (size_t i = 0; i < n; ++i) pts.append(QPointF(series.x[i], series.y[i] * factor(c)));
        curve->setMonotonicX(false);   // measured time is not trusted to be sorted
        curve->setSamples(pts);
        curve->setZ(30);
    }
    for (QwtPlotCurve* c : old) {
        c->detach();
        delete c;
    }
    rescale();
}

}  // namespace stickslip::widgets
