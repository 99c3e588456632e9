// The signals the import dialog maps, in the order its grid shows them, with their names in the
// paper's terms. Plain data (no Qt) so the validators can name signals as the pages do.
#pragma once

#include <array>
#include <string>

#include "core/io/dataset.hpp"

namespace stickslip::gui {

struct SignalInfo {
    io::Signal signal;
    const char* label;   // in the paper's terms (UTF-8)
    const char* symbol;
};

// Rows of the mapping grid, in a reading order (measured kinematics, forces, derived).
const std::array<SignalInfo, io::kSignalCount>& signalRows();
const SignalInfo& rowOf(io::Signal s);
// The label in lower case, as messages use it mid-sentence (labels are ASCII).
std::string lowerLabel(io::Signal s);

inline size_t idx(io::Signal s) { return static_cast<size_t>(s); }

}  // namespace stickslip::gui
