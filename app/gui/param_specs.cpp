#include "param_specs.hpp"

#include <algorithm>
#include <cmath>

namespace stickslip::gui {

QString groupTitle(ParamGroup g) {
    switch (g) {
    case ParamGroup::Drive: return QStringLiteral("Drive");
    case ParamGroup::Rig: return QStringLiteral("Rig");
    case ParamGroup::FrictionLaw: return QStringLiteral("Friction law");
    case ParamGroup::Integration: return QStringLiteral("Integration");
    }
    return {};
}

const std::vector<ParamSpec>& parameterSpecs() {
    using G = ParamGroup;
    // Ranges cover the paper's (MODEL.md) with margin; units are those the paper quotes.
    static const std::vector<ParamSpec> specs = {
        {"A", "A", "mm", 1e3, 0.0, 10.0, false, 4, G::Drive, false, "Stage amplitude, zero to peak"},
        {"f", "f", "Hz", 1.0, 0.5, 20.0, false, 3, G::Drive, false, "Forcing frequency"},
        {"phase", "phase", "rad", 1.0, -3.1416, 3.1416, false, 3, G::Drive, false, "Initial stage phase"},
        {"tN", "t_N", "N", 1.0, 0.1, 50.0, false, 3, G::Rig, false, "Normal force"},
        {"k", "k", "N/m", 1.0, 100.0, 50000.0, true, 1, G::Rig, false, "Beam stiffness"},
        {"m", "m*", "kg", 1.0, 0.01, 5.0, false, 3, G::Rig, false, "Effective mass (Eq. 9)"},
        {"c", "c", "N s/m", 1.0, 0.0, 20.0, false, 4, G::Rig, false, "Viscous damping"},
        {"mu", "μ", "", 1.0, 0.0, 1.0, false, 4, G::FrictionLaw, false, "Static coefficient of friction"},
        {"eta", "η", "s/m", 1.0, 0.01, 10.0, true, 4, G::FrictionLaw, true, "Fluidity (viscosity), Eq. 3"},
        {"Dc", "D_c", "µm", 1e6, 0.5, 1000.0, true, 2, G::FrictionLaw, true, "Critical slip distance, Eq. 4"},
        {"C1", "C1", "", 1.0, 0.0, 1.0, false, 4, G::FrictionLaw, true, "Amplitude of K1(α), Eq. 2"},
        {"r", "r", "", 1.0, 0.05, 10.0, false, 3, G::FrictionLaw, true, "Scale of α in K1(α), Eq. 2"},
        {"vc", "v_c", "m/s", 1.0, 0.001, 1.0, true, 4, G::FrictionLaw, true, "Characteristic velocity 1/C2"},
        {"epsT", "ε_T", "N/m", 1.0, 1.0e3, 1.0e8, true, 0, G::FrictionLaw, false, "Tangential penalty stiffness"},
        {"dt", "dt", "µs", 1e6, 0.5, 2000.0, true, 3, G::Integration, false, "Time step"},
        {"output_every", "output", "ms", 1e3, 0.01, 100.0, true, 3, G::Integration, false, "Output sample spacing"},
        {"cycles", "cycles", "", 1.0, 1.0, 2000.0, true, 0, G::Integration, false, "Recorded forcing cycles"},
        {"transient", "transient", "", 1.0, 0.0, 2000.0, false, 0, G::Integration, false,
         "Forcing cycles simulated and discarded first"},
    };
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
