#include "channel_ranges.hpp"

#include <charconv>
#include <cmath>

namespace stickslip::io {

namespace {

// Generous bounds: any bench rig, lab press or shaker table lies well inside them, while a
// value beyond them is a unit mix-up or a corrupted file that would otherwise overflow the
// return map (F = ε_T g with g = 1e300 m) or stall the integrator.
const std::vector<ChannelRange> kRanges = {
    {Channel::Time, "time", "s", -1e9, 1e9,
     "sample time: finite, strictly increasing, within about 30 years of the origin"},
    {Channel::Displacement, "displacement", "m", -10.0, 10.0,
     "stage/slider displacement and slip: up to metres"},
    {Channel::Velocity, "velocity", "m/s", -1e3, 1e3, "stage/slider/relative velocity: up to 1 km/s"},
    {Channel::Acceleration, "acceleration", "m/s^2", -1e6, 1e6, "slider acceleration: up to 1e6 m/s^2"},
    {Channel::Force, "force", "N", -1e6, 1e6, "friction force and band tension: up to 1 MN"},
    {Channel::NormalForce, "normal_force", "N", 0.0, 1e6,
     "normal load: compressive (non-negative), up to 1 MN"},
};

}  // namespace

std::string shortestNumber(double v) {
    char buf[64];
    const auto res = std::to_chars(buf, buf + sizeof buf, v);
    return std::string(buf, res.ptr);
}

bool ChannelRange::allows(double v) const { return std::isfinite(v) && v >= min && v <= max; }

std::string ChannelRange::rangeText() const {
    std::string s(1, '[');  // appended, not "[" + string: GCC 12 warns falsely (-Wrestrict) on that
    s += shortestNumber(min) + ", " + shortestNumber(max) + "] " + unit;
    return s;
}

const std::vector<ChannelRange>& channelRanges() { return kRanges; }

const ChannelRange& channelRange(Channel c) { return kRanges[static_cast<size_t>(c)]; }

bool checkChannel(Channel c, const std::string& column, const std::vector<double>& valuesSI, ValueProblem& problem,
                  double scaleToSI, const std::string& unitAsWritten) {
    const ChannelRange& r = channelRange(c);
    const bool converted = !unitAsWritten.empty() && unitAsWritten != r.unit;
    auto asWritten = [&](double si) {
        const double raw = converted && scaleToSI != 0.0 ? si / scaleToSI : si;
        std::string s = shortestNumber(raw) + " " + (converted ? unitAsWritten : std::string(r.unit));
        if (converted) s += " (" + shortestNumber(si) + " " + r.unit + ")";
        return s;
    };
    for (size_t i = 0; i < valuesSI.size(); ++i) {
        const double v = valuesSI[i];
        if (!r.allows(v)) {
            problem = ValueProblem{i, column + " = " + asWritten(v) + " is outside the allowed range " + r.rangeText() +
                                          " (" + r.doc + ")"};
            return false;
        }
        // Worded as the GUI import dialog's own check of a time column (it shows the same text).
        if (c == Channel::Time && i > 0 && !(v > valuesSI[i - 1])) {
            problem = ValueProblem{i, "time does not increase (" + std::to_string(valuesSI[i - 1]) + " s then " +
                                          std::to_string(v) + " s)"};
            return false;
        }
    }
    return true;
}

}  // namespace stickslip::io
