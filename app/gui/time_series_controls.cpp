#include "time_series_controls.hpp"

#include <QCheckBox>
#include <QDoubleSpinBox>
#include <QHBoxLayout>
#include <QLabel>

#include "widgets/time_series_plot.hpp"

namespace stickslip::gui {

using widgets::Channel;
using widgets::channelBit;

TimeSeriesControls::TimeSeriesControls(widgets::TimeSeriesPlot* plot, QWidget* parent)
    : QWidget(parent), plot_(plot) {
    auto* row = new QHBoxLayout(this);
    row->setContentsMargins(4, 0, 4, 0);
    const std::pair<Channel, QString> channels[] = {{Channel::Stage, tr("u")},
                                                    {Channel::Slider, tr("x")},
                                                    {Channel::FrictionRatio, tr("F/t_N")},
                                                    {Channel::RelVel, tr("V")},
                                                    {Channel::Alpha, tr("α")}};
    for (const auto& [ch, name] : channels) {
        auto* box = new QCheckBox(name, this);
        box->setObjectName("channel_" + widgets::channelName(ch));
        box->setChecked(plot_->channels() & channelBit(ch));
        const unsigned bit = channelBit(ch);
        connect(box, &QCheckBox::toggled, this, [this, bit](bool on) {
            plot_->setChannels(on ? (plot_->channels() | bit) : (plot_->channels() & ~bit));
        });
        row->addWidget(box);
    }
    row->addStretch(1);
    row->addWidget(new QLabel(tr("cycles"), this));
    first_ = new QDoubleSpinBox(this);
    last_ = new QDoubleSpinBox(this);
    for (auto* b : {first_, last_}) {
        b->setRange(0, 100000);
        b->setDecimals(1);
        b->setKeyboardTracking(false);
    }
    last_->setSpecialValueText(tr("all"));
    row->addWidget(first_);
    row->addWidget(new QLabel(tr("to"), this));
    row->addWidget(last_);
    auto apply = [this] { plot_->setCycleRange(first_->value(), last_->value()); };
    connect(first_, qOverload<double>(&QDoubleSpinBox::valueChanged), this, apply);
    connect(last_, qOverload<double>(&QDoubleSpinBox::valueChanged), this, apply);
}

}  // namespace stickslip::gui
