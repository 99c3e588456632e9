// Named parameter sets reproducing the paper's figures (../shared/MODEL.md).
#pragma once

#include <string>
#include <vector>

#include "params.hpp"

namespace stickslip {

struct Preset {
    std::string name;         // "fig20"
    std::string description;  // one line: what the figure shows and which values differ
    SimParams params;
};

// All built-in presets: default, fig16, fig17, fig18, fig19, fig20, fig22, fig23.
std::vector<Preset> builtinPresets();
// The preset called `name`; false if there is none.
bool findPreset(const std::string& name, Preset& out);

}  // namespace stickslip
