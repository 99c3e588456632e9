// The parameter panel's rows as Qt values, made from the core's parameter table
// (core/param_table.hpp): label, display unit and scale from SI, slider range, whether the
// slider is logarithmic (ranges spanning decades: η, D_c, v_c, ε_T, k, dt). Kept apart from
// the widget so it can be tested.
#pragma once

#include <QString>
#include <vector>

#include "core/params.hpp"

namespace stickslip::gui {

using stickslip::ParamGroup;
QString groupTitle(ParamGroup g);

struct ParamSpec {
    QString key;            // SimParams key (setParam/getParam), e.g. "Dc"
    QString label;          // shown name, e.g. "D_c"
    QString unit;           // display unit, e.g. "µm"
    double scale = 1.0;     // display value = SI value × scale
    double min = 0.0;       // display range (spin box and slider)
    double max = 1.0;
    bool logScale = false;  // slider position ∝ log(value)
    int decimals = 3;       // spin box decimals
    ParamGroup group = ParamGroup::Drive;
    bool lawKey = false;    // a friction-law parameter: shown for the laws that have it
    QString tooltip;
};

const std::vector<ParamSpec>& parameterSpecs();
const ParamSpec* findSpec(const QString& key);

// Slider position (0..sliderSteps) for a display value and back; clamps to the range.
constexpr int kSliderSteps = 1000;
int sliderPosition(const ParamSpec& s, double displayValue);
double sliderValue(const ParamSpec& s, int position);

}  // namespace stickslip::gui

namespace stickslip::gui {
// Axis title with the display unit ("A [mm]") and the factor from SI for a key; the key
// itself and factor 1 for keys the panel does not know.
struct ParamSpecScale {
    QString title;
    double factor = 1.0;
};
ParamSpecScale paramScale(const QString& key);
}  // namespace stickslip::gui
