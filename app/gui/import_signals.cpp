#include "import_signals.hpp"

#include <cctype>

namespace stickslip::gui {

const std::array<SignalInfo, io::kSignalCount>& signalRows() {
    static const std::array<SignalInfo, io::kSignalCount> rows{{
        {io::Signal::Time, "Time", "t"},
        {io::Signal::StageDisp, "Stage displacement", "u"},
        {io::Signal::SliderDisp, "Slider displacement", "x"},
        {io::Signal::Slip, "Relative slip", "g = u \u2212 x"},
        {io::Signal::StageVel, "Stage velocity", "u\u0307"},
        {io::Signal::SliderVel, "Slider velocity", "x\u0307"},
        {io::Signal::RelVel, "Relative velocity", "V = u\u0307 \u2212 x\u0307"},
        {io::Signal::SliderAccel, "Slider acceleration", "x\u0308"},
        {io::Signal::Friction, "Friction force", "F"},
        {io::Signal::Normal, "Normal force", "t_N"},
        {io::Signal::Tension, "Band tension", "sets t_N"},
    }};
    return rows;
}

const SignalInfo& rowOf(io::Signal s) {
    for (const SignalInfo& r : signalRows())
        if (r.signal == s) return r;
    return signalRows()[0];
}

std::string lowerLabel(io::Signal s) {
    std::string out = rowOf(s).label;
    for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return out;
}

}  // namespace stickslip::gui
