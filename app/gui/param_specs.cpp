#include "param_specs.hpp"

#include <algorithm>
#include <cmath>

namespace stickslip::gui {

QString groupTitle(ParamGroup g) { return QString::fromUtf8(toString(g)); }

const std::vector<ParamSpec>& parameterSpecs() {
    static const std::vector<ParamSpec> specs = [] {
        std::vector<ParamSpec> out;
        for (const ParamDef& d : paramTable()) {
            ParamSpec s;
            s.key = QString::fromUtf8(d.key);
            s.label = QString::fromUtf8(d.label);
            s.unit = QString::fromUtf8(d.displayUnit);
            s.scale = d.displayScale;
            s.min = d.sliderMin;
            s.max = d.sliderMax;
            s.logScale = d.logSlider;
            s.decimals = d.decimals;
            s.group = d.group;
            s.lawKey = d.group == ParamGroup::FrictionLaw;
            s.tooltip = QString::fromUtf8(d.doc);
            out.push_back(s);
        }
        return out;
    }();
    return specs;
}

const ParamSpec* findSpec(const QString& key) {
    for (const auto& s : parameterSpecs())
        if (s.key == key) return &s;
    return nullptr;
}

int sliderPosition(const ParamSpec& s, double v) {
    v = std::clamp(v, s.min, s.max);
    double f = 0.0;
    if (s.logScale && s.min > 0.0) f = std::log(v / s.min) / std::log(s.max / s.min);
    else if (s.max > s.min) f = (v - s.min) / (s.max - s.min);
    return static_cast<int>(std::lround(std::clamp(f, 0.0, 1.0) * kSliderSteps));
}

double sliderValue(const ParamSpec& s, int position) {
    const double f = std::clamp(position, 0, kSliderSteps) / static_cast<double>(kSliderSteps);
    if (s.logScale && s.min > 0.0) return s.min * std::pow(s.max / s.min, f);
    return s.min + f * (s.max - s.min);
}

}  // namespace stickslip::gui

namespace stickslip::gui {
ParamSpecScale paramScale(const QString& key) {
    const ParamSpec* s = findSpec(key);
    if (!s) return {key, 1.0};
    return {s->unit.isEmpty() ? s->label : QStringLiteral("%1 [%2]").arg(s->label, s->unit), s->scale};
}
}  // namespace stickslip::gui
