// The one table of parameters: for every key of SimParams its struct field, SI unit,
// physical bounds, fit range and scale, display unit and slider range, group and one-line
// doc. setParam/getParam, validate(), the fit's defaults, the units parser, the GUI's sliders
// and the CLI's --set help all read it. Defaults are the struct initialisers (params.hpp and
// each law's file), read through the field accessor, so they are written once.
// The drive, rig and integration rows are in param_table.cpp; each friction law contributes
// its own rows from its file (core/friction/*.cpp); a key shared by several laws (μ, ε_T,
// D_c) is one row that writes every law having it.
#pragma once

#include <limits>
#include <string>
#include <vector>

namespace stickslip {

// One violated constraint: which field, what value it had, what is allowed. The one issue
// type of every validate() in core (parameters, options, settings, slip histories).
struct ParamIssue {
    ParamIssue() = default;
    ParamIssue(std::string f, double v, std::string a, std::string d = {})
        : field(std::move(f)), value(v), allowed(std::move(a)), detail(std::move(d)) {}
    std::string field;    // e.g. "tN"
    double value = 0.0;   // offending value
    std::string allowed;  // e.g. "> 0"
    std::string detail;   // a problem that is not a value out of range ("time does not increase at …")
    std::string message() const;  // detail if given, else "tN = -1 is out of range: must be > 0"
    static ParamIssue note(std::string field, std::string detail) { return {std::move(field), 0.0, {}, std::move(detail)}; }
};

using ParamIssues = std::vector<ParamIssue>;

// "tN = -1 is out of range: must be > 0; k = ..." — one line per issue.
std::string formatIssues(const ParamIssues&);

struct SimParams;

enum class ParamGroup { Drive, Rig, FrictionLaw, Integration };
const char* toString(ParamGroup);

// A fit range; `log` fits log(value). Empty (upper ≤ lower): not a fit parameter.
struct FitRange {
    double lower = 0.0, upper = 0.0;
    bool log = false;
    bool valid() const { return upper > lower; }
};

inline constexpr double kUnbounded = std::numeric_limits<double>::infinity();

struct ParamDef {
    const char* key = "";         // CLI, session and run-file key, e.g. "Dc"
    const char* label = "";       // shown name (UTF-8), e.g. "D_c"
    const char* unit = "";        // SI unit, "" when dimensionless
    const char* quantity = "";    // what the unit measures, for messages: "a length"
    const char* doc = "";         // one line, with the paper's equation where it has one
    ParamGroup group = ParamGroup::Drive;
    // Physical bounds (SI): lower < v (lowerOpen) or lower ≤ v, and v ≤ upper.
    double lower = -kUnbounded, upper = kUnbounded;
    bool lowerOpen = false;
    FitRange fit;            // the fit's default range; invalid → the key is not fitted
    FitRange fitPrescribed;  // the prescribed set-up's (coefficients per unit reference load); invalid → fit
    // Display: value shown = SI × displayScale in displayUnit; slider range in display units.
    const char* displayUnit = "";
    double displayScale = 1.0;
    double sliderMin = 0.0, sliderMax = 1.0;
    bool logSlider = false;
    int decimals = 3;
    double* (*field)(SimParams&) = nullptr;

    // Issues of v against the physical bounds, named by the key ("Dc = -1 is out of range: must be > 0").
    void check(double v, ParamIssues& out) const;
};

// Every row, in display order: drive, rig, each law's own keys (registration order), integration.
const std::vector<ParamDef>& paramTable();
// The row of a key, or nullptr.
const ParamDef* findParam(const std::string& key);
// Issues of `v` for `key` against the table's bounds (none for an unknown key).
void checkParam(const char* key, double v, ParamIssues& out);
// The keys with a fit range in the table's order, space-separated: "tN k m c mu eta Dc …" (for help
// and messages).
std::string fitParamKeys();
// The default of a key (a default-constructed SimParams read through the row's field); NaN if unknown.
double paramDefault(const std::string& key);

}  // namespace stickslip
