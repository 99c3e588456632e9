// Model settings the GUI tests start from.
#pragma once

#include "core/presets.hpp"
#include "model_settings.hpp"

namespace stickslip::gui::test {

// The app's default: the paper's Fig. 20 preset.
inline ModelSettings fig20() {
    Preset p;
    findPreset("fig20", p);
    ModelSettings s;
    s.params = p.params;
    s.preset = "fig20";
    return s;
}

}  // namespace stickslip::gui::test
