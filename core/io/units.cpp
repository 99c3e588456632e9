#include "units.hpp"

#include "../param_table.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <numbers>
#include <optional>
#include <vector>

namespace stickslip::io {

namespace {

struct Atom {
    const char* name;
    double factor;   // SI value of one unit
    Dimension dim;
    bool prefixable;
};

constexpr int kMaxExponent = 9;                    // |exponent| of one unit atom
constexpr double kInch = 0.0254;                    // m
constexpr double kFoot = 0.3048;                    // m
constexpr double kPoundMass = 0.45359237;           // kg
constexpr double kPoundForce = 0.45359237 * 9.80665;  // N

// Base unit atoms. "g" is 1e-3 kg so that "kg" comes out as prefix k + g.
const Atom kAtoms[] = {
    {"m", 1.0, {1, 0, 0}, true},
    {"g", 1.0e-3, {0, 1, 0}, true},
    {"s", 1.0, {0, 0, 1}, true},
    {"N", 1.0, {1, 1, -2}, true},
    {"Hz", 1.0, {0, 0, -1}, true},
    {"rad", 1.0, {0, 0, 0}, true},
    {"deg", std::numbers::pi / 180.0, {0, 0, 0}, false},
    {"%", 0.01, {0, 0, 0}, false},
    {"in", kInch, {1, 0, 0}, false},
    {"ft", kFoot, {1, 0, 0}, false},
    {"lbf", kPoundForce, {1, 1, -2}, false},
    {"lbm", kPoundMass, {0, 1, 0}, false},
    {"lb", kPoundForce, {1, 1, -2}, false},  // resolved against the expected dimension
};

struct Prefix {
    const char* name;
    double factor;
};
const Prefix kPrefixes[] = {{"G", 1e9}, {"M", 1e6}, {"k", 1e3}, {"c", 1e-2}, {"m", 1e-3},
                            {"u", 1e-6}, {"n", 1e-9}, {"p", 1e-12}};

struct Term {
    double factor = 1.0;
    Dimension dim;
    bool isPound = false;  // "lb": force or mass, decided later
    int exponent = 1;
};

bool matchAtom(std::string_view s, Term& t) {
    for (const Atom& a : kAtoms) {
        if (s == a.name) {
            t.factor = a.factor;
            t.dim = a.dim;
            t.isPound = std::string_view(a.name) == "lb";
            return true;
        }
    }
    for (const Prefix& p : kPrefixes) {
        const std::string_view pn(p.name);
        if (s.size() <= pn.size() || s.substr(0, pn.size()) != pn) continue;
        for (const Atom& a : kAtoms) {
            if (a.prefixable && s.substr(pn.size()) == a.name) {
                t.factor = p.factor * a.factor;
                t.dim = a.dim;
                return true;
            }
        }
    }
    return false;
}

// A run of letters is one atom ("mN", "kg", "Hz") or, failing that, a product of atoms
// ("Ns" = N·s). Whole-run matches win, so "ms" is a millisecond, not a metre-second.
// Longest atom spelling with a prefix ("mrad", "klbf" is not prefixable): longer heads never match.
constexpr size_t kMaxAtomLength = 4;

// `failed[i]`: s.substr(i) is known not to split, so each suffix is tried once (linear time;
// trying every split again was exponential in the length of the run).
bool splitLettersFrom(std::string_view s, size_t from, std::vector<char>& failed, std::vector<Term>& out) {
    if (from == s.size()) return true;
    if (failed[from]) return false;
    const std::string_view rest = s.substr(from);
    Term t;
    if (matchAtom(rest, t)) {
        out.push_back(t);
        return true;
    }
    for (size_t n = std::min(rest.size() - 1, kMaxAtomLength); n >= 1; --n) {
        Term head;
        if (!matchAtom(rest.substr(0, n), head)) continue;
        const size_t mark = out.size();
        out.push_back(head);
        if (splitLettersFrom(s, from + n, failed, out)) return true;
        out.resize(mark);
    }
    failed[from] = 1;
    return false;
}

bool splitLetters(std::string_view s, std::vector<Term>& out) {
    std::vector<char> failed(s.size() + 1, 0);
    return splitLettersFrom(s, 0, failed, out);
}

// Normalises the UTF-8 spellings: µ (U+00B5) and μ (U+03BC) -> u, · (U+00B7) -> *.
std::string normalise(const std::string& in) {
    std::string s;
    for (size_t i = 0; i < in.size(); ++i) {
        const unsigned char c = static_cast<unsigned char>(in[i]);
        if (c == 0xC2 && i + 1 < in.size() && static_cast<unsigned char>(in[i + 1]) == 0xB5) {
            s += 'u';
            ++i;
        } else if (c == 0xCE && i + 1 < in.size() && static_cast<unsigned char>(in[i + 1]) == 0xBC) {
            s += 'u';
            ++i;
        } else if (c == 0xC2 && i + 1 < in.size() && static_cast<unsigned char>(in[i + 1]) == 0xB7) {
            s += '*';
            ++i;
        } else {
            s += static_cast<char>(c);
        }
    }
    return s;
}

bool isLetter(char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || c == '%'; }

// Parses the unit part into terms with signed exponents.
bool parseUnit(const std::string& u, std::vector<Term>& terms, std::string& why) {
    bool denominator = false;
    size_t i = 0;
    while (i < u.size()) {
        const char c = u[i];
        if (c == ' ' || c == '*' || c == '.') {
            ++i;
            continue;
        }
        if (c == '/') {
            if (denominator) {
                why = "only one '/' is allowed in a unit";
                return false;
            }
            denominator = true;
            ++i;
            continue;
        }
        if (!isLetter(c)) {
            why = std::string("unexpected character '") + c + "' in unit";
            return false;
        }
        size_t j = i;
        while (j < u.size() && isLetter(u[j])) ++j;
        std::vector<Term> run;
        if (!splitLetters(std::string_view(u).substr(i, j - i), run)) {
            why = "unknown unit '" + u.substr(i, j - i) + "'";
            return false;
        }
        i = j;
        int exponent = 1;
        if (i < u.size() && (u[i] == '^' || u[i] == '-' || (u[i] >= '0' && u[i] <= '9'))) {
            if (u[i] == '^') ++i;
            const char* b = u.data() + i;
            const auto [ptr, ec] = std::from_chars(b, u.data() + u.size(), exponent);
            if (ec == std::errc::invalid_argument) {
                why = "bad exponent in unit";
                return false;
            }
            // No physical unit needs more; a bound keeps the int dimension sums from overflowing.
            if (ec != std::errc() || exponent < -kMaxExponent || exponent > kMaxExponent) {
                why = "exponent " + std::string(b, ptr) + " in unit is out of range: allowed -" +
                      std::to_string(kMaxExponent) + " to " + std::to_string(kMaxExponent);
                return false;
            }
            i += static_cast<size_t>(ptr - b);
        }
        // The exponent applies to the last atom of the run ("Ns^2" would be N·s²).
        for (size_t k = 0; k < run.size(); ++k) {
            Term t = run[k];
            t.exponent = (k + 1 == run.size() ? exponent : 1) * (denominator ? -1 : 1);
            terms.push_back(t);
        }
    }
    if (terms.empty()) {
        why = "missing unit after '/'";
        return false;
    }
    return true;
}

void combine(const std::vector<Term>& terms, bool poundAsMass, double& factor, Dimension& dim) {
    factor = 1.0;
    dim = {};
    for (const Term& t : terms) {
        double f = t.factor;
        Dimension d = t.dim;
        if (t.isPound && poundAsMass) {
            f = kPoundMass;
            d = {0, 1, 0};
        }
        factor *= std::pow(f, t.exponent);
        dim.length += d.length * t.exponent;
        dim.mass += d.mass * t.exponent;
        dim.time += d.time * t.exponent;
    }
}

struct KeyUnit {
    const char* key;
    const char* unit;
    Dimension dim;
    const char* quantity;
};

// The parameter table's keys with the dimension of their SI unit.
const std::vector<KeyUnit>& keyUnits() {
    static const std::vector<KeyUnit> units = [] {
        std::vector<KeyUnit> out;
        for (const ParamDef& d : paramTable()) {
            std::vector<Term> terms;
            std::string why;
            double factor = 1.0;
            Dimension dim;
            if (*d.unit && parseUnit(d.unit, terms, why)) combine(terms, false, factor, dim);
            out.push_back({d.key, d.unit, dim, d.quantity});
        }
        return out;
    }();
    return units;
}

const char* describe(const Dimension& d) {
    for (const KeyUnit& k : keyUnits())
        if (k.dim == d) return k.quantity;
    if (d == Dimension{0, 0, -1}) return "a frequency";
    return nullptr;
}

}  // namespace

std::string dimensionString(const Dimension& d) {
    std::string num, den;
    auto add = [](std::string& s, const char* sym, int e) {
        if (e == 0) return;
        if (!s.empty()) s += ' ';
        s += sym;
        if (std::abs(e) != 1) {
            s += '^';
            s += std::to_string(std::abs(e));
        }
    };
    add(d.mass > 0 ? num : den, "kg", d.mass);
    add(d.length > 0 ? num : den, "m", d.length);
    add(d.time > 0 ? num : den, "s", d.time);
    if (num.empty() && den.empty()) return "1";
    if (den.empty()) return num;
    std::string out = num.empty() ? std::string(1, '1') : num;
    out += '/';
    const bool group = den.find(' ') != std::string::npos;
    if (group) out += '(';
    out += den;
    if (group) out += ')';
    return out;
}

bool parseQuantity(const std::string& textIn, Quantity& out, std::string* error, const Dimension* expected) {
    auto fail = [&](const std::string& why) {
        if (error) *error = why;
        return false;
    };
    const std::string text = normalise(textIn);
    size_t b = 0, e = text.size();
    while (b < e && text[b] == ' ') ++b;
    while (e > b && text[e - 1] == ' ') --e;
    if (b == e) return fail("empty value");
    const char* first = text.data() + b;
    if (*first == '+') ++first;
    double v = 0;
    const auto [ptr, ec] = std::from_chars(first, text.data() + e, v);
    if (ec == std::errc::result_out_of_range) return fail("number out of range '" + textIn + "'");
    if (ec != std::errc()) return fail("'" + textIn + "' does not start with a number");
    if (!std::isfinite(v)) return fail("'" + textIn + "' is not a finite number");
    const std::string unit(ptr, text.data() + e);

    Quantity q;
    if (unit.find_first_not_of(' ') == std::string::npos) {
        q.valueSI = v;
        q.hasUnit = false;
        if (expected) q.dimension = *expected;
        out = q;
        return true;
    }
    std::vector<Term> terms;
    std::string why;
    if (!parseUnit(unit.substr(unit.find_first_not_of(' ')), terms, why)) return fail(why + " in '" + textIn + "'");
    double factor = 1.0;
    Dimension dim;
    combine(terms, false, factor, dim);
    if (expected && !(dim == *expected)) {
        double f2 = 1.0;
        Dimension d2;
        combine(terms, true, f2, d2);  // "lb" as pound-mass
        if (d2 == *expected) {
            factor = f2;
            dim = d2;
        }
    }
    q.valueSI = v * factor;
    q.dimension = dim;
    q.hasUnit = true;
    if (!std::isfinite(q.valueSI)) return fail("'" + textIn + "' overflows in SI units");
    out = q;
    return true;
}

bool paramUnit(const std::string& key, std::string& unit) {
    for (const KeyUnit& k : keyUnits()) {
        if (key == k.key) {
            unit = k.unit;
            return true;
        }
    }
    return false;
}

bool paramDimension(const std::string& key, Dimension& dim) {
    for (const KeyUnit& k : keyUnits()) {
        if (key == k.key) {
            dim = k.dim;
            return true;
        }
    }
    return false;
}

bool parseParamValue(const std::string& key, const std::string& text, double& valueSI, std::string* error) {
    const KeyUnit* ku = nullptr;
    for (const KeyUnit& k : keyUnits())
        if (key == k.key) ku = &k;
    if (!ku) {
        if (error) *error = "unknown parameter '" + key + "'";
        return false;
    }
    const std::string expectedUnit = *ku->unit ? std::string("[") + ku->unit + "]" : std::string("(no unit)");
    Quantity q;
    std::string why;
    if (!parseQuantity(text, q, &why, &ku->dim)) {
        if (error) *error = key + " = " + text + ": " + why + "; " + key + " expects " + ku->quantity + " " + expectedUnit;
        return false;
    }
    if (!(q.dimension == ku->dim)) {
        if (error) {
            const char* what = describe(q.dimension);
            *error = key + " = " + text + ": the unit is " + (what ? std::string(what) + " " : std::string()) + "[" +
                     dimensionString(q.dimension) + "], but " + key + " expects " + ku->quantity + " " + expectedUnit;
        }
        return false;
    }
    valueSI = q.valueSI;
    return true;
}

}  // namespace stickslip::io
