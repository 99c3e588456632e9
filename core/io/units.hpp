// Physical values with optional unit suffixes ("0.4mm", "20um", "6.2N", "1e6N/m", "0.6s/m")
// converted to SI, with a check that the unit's dimension fits the parameter it is for.
#pragma once

#include <string>

namespace stickslip::io {

// Exponents of the SI base units a quantity carries: m^length kg^mass s^time.
struct Dimension {
    int length = 0;
    int mass = 0;
    int time = 0;
    bool operator==(const Dimension&) const = default;
};

// Parses "<number>[ ]<unit>" and converts to SI. Units are products and one quotient of
// atoms with optional SI prefix (G M k c m u µ n p) and integer exponent ("m^2", "s^-1"):
// m, g, s, N, Hz, rad, deg, %, in, ft, lb (pound-force; pound-mass where a mass is
// expected), lbf, lbm; e.g. "mm/s", "kN/m", "N s/m", "Ns/m", "kg/s". The number alone means
// SI (dimension left unspecified, `hasUnit` false). Returns false with a message on error.
struct Quantity {
    double valueSI = 0.0;
    Dimension dimension;
    bool hasUnit = false;
};
bool parseQuantity(const std::string& text, Quantity& out, std::string* error,
                   const Dimension* expected = nullptr);

// The SI unit of a SimParams key as printed ("m", "Hz", "N/m", "N s/m", "s/m", "m/s", "kg",
// "N", "s", "rad", "" for dimensionless). False for an unknown key.
bool paramUnit(const std::string& key, std::string& unit);
// The dimension of a SimParams key. False for an unknown key.
bool paramDimension(const std::string& key, Dimension& dim);

// Parses a value for a SimParams key: SI number or number with a unit of the key's
// dimension. Error messages name the key, the text and the expected unit, e.g.
// "A = 3Hz: unit 'Hz' is a frequency [1/s], but A expects a length [m]".
bool parseParamValue(const std::string& key, const std::string& text, double& valueSI, std::string* error);

// "m", "kg/s", "1/s", ... for a dimension; "1" when dimensionless.
std::string dimensionString(const Dimension& d);

}  // namespace stickslip::io
