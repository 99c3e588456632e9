// Fuzz target: unit-suffixed values (core/io/units: parseQuantity, parseParamValue), e.g.
// "0.4mm", "1e6N/m", "0.6 s/m". Input "KEY\nVALUE" parses VALUE for the SimParams key KEY;
// anything else is parsed as a free quantity. Accepted values are finite, and printing the
// SI value with the key's SI unit parses back to the same number (round trip).
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>

#include "core/io/units.hpp"
#include "fuzz_check.hpp"

namespace {

std::string printed(double v, const std::string& unit) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.17g", v);
    return unit.empty() ? std::string(buf) : std::string(buf) + " " + unit;
}

void checkQuantity(const std::string& text) {
    using namespace stickslip::io;
    Quantity q;
    std::string why;
    if (!parseQuantity(text, q, &why)) {
        FUZZ_CHECK(!why.empty(), "rejected '%s' without a message", text.c_str());
        return;
    }
    FUZZ_CHECK(std::isfinite(q.valueSI), "'%s' accepted as a non-finite value", text.c_str());
    Quantity back;
    FUZZ_CHECK(parseQuantity(printed(q.valueSI, ""), back, &why), "SI value of '%s' does not parse: %s", text.c_str(),
               why.c_str());
    FUZZ_CHECK(back.valueSI == q.valueSI, "'%s': %.17g printed and read as %.17g", text.c_str(), q.valueSI, back.valueSI);
    (void)dimensionString(q.dimension);
}

void checkParam(const std::string& key, const std::string& text) {
    using namespace stickslip::io;
    double v = 0;
    std::string why;
    std::string unit;
    const bool known = paramUnit(key, unit);
    if (!parseParamValue(key, text, v, &why)) {
        FUZZ_CHECK(!why.empty(), "rejected %s = '%s' without a message", key.c_str(), text.c_str());
        return;
    }
    FUZZ_CHECK(known, "value accepted for unknown key '%s'", key.c_str());
    FUZZ_CHECK(std::isfinite(v), "%s = '%s' accepted as a non-finite value", key.c_str(), text.c_str());
    double back = 0;
    const std::string again = printed(v, unit);
    FUZZ_CHECK(parseParamValue(key, again, back, &why), "%s = '%s' (from '%s') does not parse: %s", key.c_str(),
               again.c_str(), text.c_str(), why.c_str());
    FUZZ_CHECK(back == v, "%s: '%s' read as %.17g, not %.17g", key.c_str(), again.c_str(), back, v);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string in(reinterpret_cast<const char*>(data), size);
    const auto nl = in.find('\n');
    if (nl == std::string::npos)
        checkQuantity(in);
    else
        checkParam(in.substr(0, nl), in.substr(nl + 1));
    return 0;
}
