#include "param_table.hpp"

#include <cmath>
#include <sstream>

#include "friction/friction_law.hpp"
#include "params.hpp"

namespace stickslip {

std::string ParamIssue::message() const {
    if (!detail.empty()) return detail;
    std::ostringstream s;
    s.precision(6);
    s << field << " = " << value << " is out of range: must be " << allowed;
    return s.str();
}

std::string formatIssues(const ParamIssues& issues) {
    std::string out;
    for (const auto& i : issues) {
        if (!out.empty()) out += '\n';
        out += i.message();
    }
    return out;
}

const char* toString(ParamGroup g) {
    switch (g) {
    case ParamGroup::Drive: return "Drive";
    case ParamGroup::Rig: return "Rig";
    case ParamGroup::FrictionLaw: return "Friction law";
    case ParamGroup::Integration: return "Integration";
    }
    return "";
}

namespace {

std::string number(double v) {
    std::ostringstream s;
    s.precision(6);
    s << v;
    return s.str();
}

// Ranges cover the paper's (MODEL.md) with margin; display units are those the paper quotes.
std::vector<ParamDef> driveAndRigRows() {
    using G = ParamGroup;
    return {
        {.key = "A", .label = "A", .unit = "m", .quantity = "a length", .doc = "Stage amplitude, zero to peak",
         .group = G::Drive, .lower = 0, .upper = 1.0, .displayUnit = "mm", .displayScale = 1e3, .sliderMin = 0.0,
         .sliderMax = 10.0, .decimals = 4, .field = [](SimParams& p) { return &p.drive.amplitude_m; }},
        {.key = "f", .label = "f", .unit = "Hz", .quantity = "a frequency", .doc = "Forcing frequency", .group = G::Drive,
         .lower = 0, .lowerOpen = true, .displayUnit = "Hz", .sliderMin = 0.5, .sliderMax = 20.0, .decimals = 3,
         .field = [](SimParams& p) { return &p.drive.frequency_Hz; }},
        {.key = "phase", .label = "phase", .unit = "rad", .quantity = "an angle", .doc = "Initial stage phase",
         .group = G::Drive, .displayUnit = "rad", .sliderMin = -3.1416, .sliderMax = 3.1416, .decimals = 3,
         .field = [](SimParams& p) { return &p.drive.phase_rad; }},
        {.key = "tN", .label = "t_N", .unit = "N", .quantity = "a force", .doc = "Normal force", .group = G::Rig,
         .lower = 0, .lowerOpen = true, .fit = {1e-3, 1e5, true}, .displayUnit = "N", .sliderMin = 0.1,
         .sliderMax = 50.0, .decimals = 3, .field = [](SimParams& p) { return &p.rig.normalForce_N; }},
        {.key = "k", .label = "k", .unit = "N/m", .quantity = "a stiffness", .doc = "Beam stiffness", .group = G::Rig,
         .lower = 0, .fit = {1.0, 1e7, true}, .displayUnit = "N/m", .sliderMin = 100.0, .sliderMax = 50000.0,
         .logSlider = true, .decimals = 1, .field = [](SimParams& p) { return &p.rig.stiffness_N_per_m; }},
        {.key = "m", .label = "m*", .unit = "kg", .quantity = "a mass", .doc = "Effective mass (Eq. 9)", .group = G::Rig,
         .lower = 0, .lowerOpen = true, .fit = {0.05, 5.0, true}, .displayUnit = "kg", .sliderMin = 0.01,
         .sliderMax = 5.0, .decimals = 3, .field = [](SimParams& p) { return &p.rig.mass_kg; }},
        {.key = "c", .label = "c", .unit = "N s/m", .quantity = "a damping coefficient", .doc = "Viscous damping",
         .group = G::Rig, .lower = 0, .fit = {1e-6, 1e4, true}, .displayUnit = "N s/m", .sliderMin = 0.0,
         .sliderMax = 20.0, .decimals = 4, .field = [](SimParams& p) { return &p.rig.damping_Ns_per_m; }},
    };
}

std::vector<ParamDef> integrationRows() {
    using G = ParamGroup;
    return {
        {.key = "dt", .label = "dt", .unit = "s", .quantity = "a time", .doc = "Time step", .group = G::Integration,
         .lower = 0, .lowerOpen = true, .displayUnit = "µs", .displayScale = 1e6, .sliderMin = 0.5, .sliderMax = 2000.0,
         .logSlider = true, .decimals = 3, .field = [](SimParams& p) { return &p.integration.dt_s; }},
        {.key = "output_every", .label = "output", .unit = "s", .quantity = "a time", .doc = "Output sample spacing",
         .group = G::Integration, .lower = 0, .lowerOpen = true, .displayUnit = "ms", .displayScale = 1e3,
         .sliderMin = 0.01, .sliderMax = 100.0, .logSlider = true, .decimals = 3,
         .field = [](SimParams& p) { return &p.integration.outputInterval_s; }},
        {.key = "cycles", .label = "cycles", .quantity = "dimensionless", .doc = "Recorded forcing cycles",
         .group = G::Integration, .lower = 0, .lowerOpen = true, .sliderMin = 1.0, .sliderMax = 2000.0,
         .logSlider = true, .decimals = 0, .field = [](SimParams& p) { return &p.cycles; }},
        {.key = "transient", .label = "transient", .quantity = "dimensionless",
         .doc = "Forcing cycles simulated and discarded first", .group = G::Integration, .lower = 0, .sliderMin = 0.0,
         .sliderMax = 2000.0, .decimals = 0, .field = [](SimParams& p) { return &p.transientCycles; }},
    };
}

std::vector<ParamDef> buildTable() {
    std::vector<ParamDef> t = driveAndRigRows();
    // Each law's rows; a key already present (shared by an earlier law) keeps its first row.
    for (const LawInfo& law : lawRegistry())
        for (const ParamDef& row : law.paramRows) {
            bool known = false;
            for (const ParamDef& d : t) known = known || std::string(d.key) == row.key;
            if (!known) t.push_back(row);
        }
    for (ParamDef& d : integrationRows()) t.push_back(d);
    for (ParamDef& d : t)
        if (!*d.displayUnit) d.displayUnit = d.unit;
    return t;
}

}  // namespace

void ParamDef::check(double v, ParamIssues& out) const {
    if (std::isfinite(lower)) {
        if (lowerOpen && !(std::isfinite(v) && v > lower)) return out.push_back({key, v, "> " + number(lower)});
        if (!lowerOpen && !(std::isfinite(v) && v >= lower)) return out.push_back({key, v, ">= " + number(lower)});
    } else if (!std::isfinite(v)) {
        return out.push_back({key, v, "finite"});
    }
    if (v > upper) out.push_back({key, v, "<= " + number(upper) + (*unit ? std::string(" ") + unit : std::string())});
}

const std::vector<ParamDef>& paramTable() {
    static const std::vector<ParamDef> table = buildTable();
    return table;
}

const ParamDef* findParam(const std::string& key) {
    for (const ParamDef& d : paramTable())
        if (key == d.key) return &d;
    return nullptr;
}

void checkParam(const char* key, double v, ParamIssues& out) {
    if (const ParamDef* d = findParam(key)) d->check(v, out);
}

std::string fitParamKeys() {
    std::string out;
    for (const ParamDef& d : paramTable())
        if (d.fit.valid()) out += std::string(out.empty() ? "" : " ") + d.key;
    return out;
}

double paramDefault(const std::string& key) {
    static const SimParams defaults;
    double v = std::nan("");
    getParam(defaults, key, v);
    return v;
}

}  // namespace stickslip
