// The physical ranges of measured and prescribed signals: one table that every reader of
// a user's data (run files, prescribed-slip histories, measured datasets) checks against,
// so that an absurd value is rejected at the file with its position, not deep inside a
// solver. Ranges are in SI, applied after unit conversion.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace stickslip::io {

enum class Channel { Time, Displacement, Velocity, Acceleration, Force, NormalForce };

struct ChannelRange {
    Channel channel;
    const char* key;    // "time", "displacement", ...
    const char* unit;   // SI unit as printed
    double min;         // allowed values: finite, min <= v <= max
    double max;
    const char* doc;    // one line: what the channel covers and why this range
    bool allows(double valueSI) const;
    std::string rangeText() const;  // "[-10, 10] m"
};

// Every channel, in Channel order.
const std::vector<ChannelRange>& channelRanges();
const ChannelRange& channelRange(Channel c);

// Where an offending value sits, as the caller knows it.
struct ValueProblem {
    size_t row = 0;        // 0-based data row
    std::string message;   // "rel_disp_m = 1e+300 m is outside the allowed range [-10, 10] m (...)"
};

// Checks one column of values (SI) of channel `c`. `column` names it in the message;
// `scaleToSI` and `unitAsWritten` show the offending value as the file has it ("= 1e+300 mm
// (1e+297 m)"). NaN/Inf are always rejected. For Channel::Time the values must also increase
// strictly (no duplicates): "time does not increase (0.003000 s then 0.002000 s)". Returns
// false and fills `problem` for the first bad row.
bool checkChannel(Channel c, const std::string& column, const std::vector<double>& valuesSI, ValueProblem& problem,
                  double scaleToSI = 1.0, const std::string& unitAsWritten = {});

// Shortest text that reads back to the same double ("1e+300", "0.001").
std::string shortestNumber(double v);

}  // namespace stickslip::io
