#include "dataset.hpp"

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "../params.hpp"
#include "channel_ranges.hpp"
#include "csv_table.hpp"
#include "units.hpp"

namespace stickslip::io {

namespace {

struct SignalInfo {
    Signal s;
    const char* key;
    const char* column;
    const char* unit;
    Dimension dim;
    Channel range;  // its physical range (channel_ranges.hpp)
};

const std::array<SignalInfo, kSignalCount>& signalTable() {
    static const std::array<SignalInfo, kSignalCount> t{{
        {Signal::Time, "time", "time_s", "s", {0, 0, 1}, Channel::Time},
        {Signal::StageDisp, "stage_disp", "stage_disp_m", "m", {1, 0, 0}, Channel::Displacement},
        {Signal::SliderDisp, "slider_disp", "slider_disp_m", "m", {1, 0, 0}, Channel::Displacement},
        {Signal::Slip, "slip", "slip_m", "m", {1, 0, 0}, Channel::Displacement},
        {Signal::RelVel, "rel_vel", "rel_vel_mps", "m/s", {1, 0, -1}, Channel::Velocity},
        {Signal::StageVel, "stage_vel", "stage_vel_mps", "m/s", {1, 0, -1}, Channel::Velocity},
        {Signal::SliderVel, "slider_vel", "slider_vel_mps", "m/s", {1, 0, -1}, Channel::Velocity},
        {Signal::Friction, "friction", "friction_force_N", "N", {1, 1, -2}, Channel::Force},
        {Signal::Normal, "normal", "normal_force_N", "N", {1, 1, -2}, Channel::NormalForce},
        {Signal::Tension, "tension", "band_tension_N", "N", {1, 1, -2}, Channel::Force},
        {Signal::SliderAccel, "slider_accel", "slider_accel_mps2", "m/s^2", {1, 0, -2}, Channel::Acceleration},
    }};
    return t;
}

const SignalInfo& info(Signal s) { return signalTable()[static_cast<size_t>(s)]; }

std::vector<std::string> splitList(const std::string& s, char sep) {
    std::vector<std::string> out;
    std::string cur;
    std::istringstream in(s);
    while (std::getline(in, cur, sep)) {
        const auto b = cur.find_first_not_of(" \t");
        const auto e = cur.find_last_not_of(" \t");
        if (b != std::string::npos) out.push_back(cur.substr(b, e - b + 1));
    }
    return out;
}

bool splitPair(const std::string& item, std::string& k, std::string& v) {
    const auto eq = item.find('=');
    if (eq == std::string::npos || eq == 0 || eq + 1 >= item.size()) return false;
    k = item.substr(0, eq);
    v = item.substr(eq + 1);
    return true;
}

std::string baseName(const std::string& path) {
    const auto slash = path.find_last_of('/');
    return slash == std::string::npos ? path : path.substr(slash + 1);
}

}  // namespace

const char* signalKey(Signal s) { return info(s).key; }
const char* defaultColumn(Signal s) { return info(s).column; }
const char* signalUnit(Signal s) { return info(s).unit; }

bool parseSignal(const std::string& key, Signal& out) {
    for (const SignalInfo& i : signalTable())
        if (key == i.key) {
            out = i.s;
            return true;
        }
    return false;
}

static std::string knownSignals() {
    std::string s;
    for (const SignalInfo& i : signalTable()) s += (s.empty() ? "" : ", ") + std::string(i.key);
    return s;
}

bool ColumnMapping::addColumns(const std::string& spec, std::string* error) {
    for (const std::string& item : splitList(spec, ',')) {
        std::string k, v;
        Signal s;
        if (!splitPair(item, k, v)) {
            if (error) *error = "--columns '" + item + "': expected SIGNAL=COLUMN, e.g. friction=Fx";
            return false;
        }
        if (!parseSignal(k, s)) {
            if (error) *error = "--columns '" + item + "': unknown signal '" + k + "' (known: " + knownSignals() + ")";
            return false;
        }
        if (s == Signal::Time && v == kNotMapped) {
            if (error) *error = "--columns '" + item + "': the time signal must be read from a column";
            return false;
        }
        columns[s] = v;
    }
    return true;
}

bool ColumnMapping::addUnits(const std::string& spec, std::string* error) {
    for (const std::string& item : splitList(spec, ',')) {
        std::string k, v;
        Signal s;
        if (!splitPair(item, k, v)) {
            if (error) *error = "--units '" + item + "': expected SIGNAL=UNIT, e.g. stage_disp=mm";
            return false;
        }
        if (!parseSignal(k, s)) {
            if (error) *error = "--units '" + item + "': unknown signal '" + k + "' (known: " + knownSignals() + ")";
            return false;
        }
        Quantity q;
        std::string why;
        const Dimension dim = info(s).dim;
        if (!parseQuantity("1 " + v, q, &why, &dim) || !q.hasUnit || !(q.dimension == dim)) {
            if (error)
                *error = "--units '" + item + "': " + (why.empty() ? "unit of the wrong dimension" : why) + " (" + k + " expects " +
                         dimensionString(dim) + ")";
            return false;
        }
        scaleToSI[s] = q.valueSI;
        unitText[s] = v;
    }
    return true;
}

std::string DatasetError::what() const {
    std::ostringstream o;
    o << file;
    if (line > 0) {
        o << ':' << line;
        if (column > 0) o << ':' << column;
    }
    o << ": " << message;
    return o.str();
}

bool Run::setting(const std::string& key, double& value) const {
    const auto it = settings.find(key);
    if (it == settings.end()) return false;
    value = it->second;
    return true;
}

std::string Run::name() const { return baseName(file); }

bool loadRun(const std::string& path, const ColumnMapping& mapping, Run& out, DatasetError& err) {
    CsvTable table;
    CsvError cerr;
    if (!readCsvTable(path, table, cerr)) {
        err = DatasetError{cerr.file.empty() ? path : cerr.file, cerr.line, cerr.column, cerr.message};
        return false;
    }
    // The header is the first non-comment line (blank lines are rare in these files).
    const long headerLine = static_cast<long>(table.comments.size()) + 1;
    Run run;
    run.file = path;
    run.comments = table.comments;
    for (const SignalInfo& si : signalTable()) {
        const auto m = mapping.columns.find(si.s);
        if (m != mapping.columns.end() && (m->second.empty() || m->second == kNotMapped)) {
            if (si.s != Signal::Time) continue;  // deliberately not read
            err = DatasetError{path, 0, 0, "the time signal must be read from a column (it cannot be unmapped)"};
            return false;
        }
        const std::string col = m != mapping.columns.end() ? m->second : si.column;
        const int j = table.column(col);
        if (j < 0) {
            if (m != mapping.columns.end() || si.s == Signal::Time) {
                std::string have;
                for (const auto& h : table.header) have += (have.empty() ? "" : ", ") + h;
                err = DatasetError{path, headerLine, 0,
                                   std::string("no column '") + col + "' for signal " + si.key + " (columns: " + have + ")"};
                return false;
            }
            continue;
        }
        std::vector<double> v = table.columns[static_cast<size_t>(j)];
        const auto sc = mapping.scaleToSI.find(si.s);
        if (sc != mapping.scaleToSI.end())
            for (double& x : v) x *= sc->second;
        run.channels[static_cast<size_t>(si.s)] = std::move(v);
        run.sourceColumn[si.s] = col;
    }
    const std::vector<double>& t = run[Signal::Time];
    if (t.size() < 8) {
        err = DatasetError{path, headerLine, 0, "too few data rows (" + std::to_string(t.size()) + "); need at least 8"};
        return false;
    }
    // Every channel read, in SI, against the one table of physical ranges; time also
    // strictly increasing. The message shows the value as the file has it (its unit).
    for (const SignalInfo& si : signalTable()) {
        if (!run.has(si.s)) continue;
        const std::string& col = run.sourceColumn[si.s];
        const auto sc = mapping.scaleToSI.find(si.s);
        const auto ut = mapping.unitText.find(si.s);
        ValueProblem bad;
        if (!checkChannel(si.range, col, run[si.s], bad, sc != mapping.scaleToSI.end() ? sc->second : 1.0,
                          ut != mapping.unitText.end() ? ut->second : std::string())) {
            const auto j = static_cast<size_t>(table.column(col));
            err = DatasetError{path, table.rowLines[bad.row], table.cellColumn(bad.row, j), bad.message};
            return false;
        }
    }
    out = std::move(run);
    return true;
}

bool readManifest(const std::string& path, Manifest& out, DatasetError& err) {
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        err = DatasetError{path, 0, 0, "cannot open manifest"};
        return false;
    }
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    return parseManifest(text, path, out, err);
}

bool parseManifest(const std::string& text, const std::string& path, Manifest& out, DatasetError& err) {
    nlohmann::json j;
    try {
        j = nlohmann::json::parse(text);
    } catch (const nlohmann::json::parse_error& e) {
        // nlohmann reports a byte offset; turn it into line and column.
        long line = 1, col = 1;
        for (size_t i = 0; i + 1 < e.byte && i < text.size(); ++i) {
            if (text[i] == '\n') { ++line; col = 1; } else ++col;
        }
        err = DatasetError{path, line, col, std::string("invalid JSON: ") + e.what()};
        return false;
    } catch (const nlohmann::json::exception& e) {
        // A number beyond the double range ("1e999") is out_of_range, without a byte offset.
        err = DatasetError{path, 0, 0, std::string("invalid JSON: ") + e.what()};
        return false;
    }
    Manifest m;
    m.path = path;
    static const std::pair<const char*, const char*> keys[] = {
        {"k_N_per_m", "k"}, {"A_m", "A"}, {"f_Hz", "f"}, {"tN_N", "tN"}, {"m_kg", "m"}, {"c_Ns_per_m", "c"}, {"phase_rad", "phase"}};
    if (j.contains("nominal_mass_kg") && j["nominal_mass_kg"].is_number()) m.common["m"] = j["nominal_mass_kg"].get<double>();
    if (!j.contains("runs") || !j["runs"].is_array()) {
        err = DatasetError{path, 0, 0, "manifest has no \"runs\" array"};
        return false;
    }
    size_t idx = 0;
    for (const auto& r : j["runs"]) {
        if (!r.is_object() || !r.contains("file") || !r["file"].is_string()) {
            err = DatasetError{path, 0, 0, "manifest run #" + std::to_string(idx + 1) + " has no \"file\" name"};
            return false;
        }
        std::map<std::string, double> s;
        for (const auto& [jk, pk] : keys)
            if (r.contains(jk)) {
                if (!r[jk].is_number()) {
                    err = DatasetError{path, 0, 0, "manifest run " + r["file"].get<std::string>() + ": \"" + jk + "\" is not a number"};
                    return false;
                }
                const double v = r[jk].get<double>();
                // The amplitude and the normal load are channels of the range table; the other
                // settings are checked by the parameters' own validation once used.
                const std::string key = pk;
                ValueProblem bad;
                bool ok = std::isfinite(v);
                if (!ok) bad.message = std::string("\"") + jk + "\" is not finite";
                else if (key == "A") ok = checkChannel(Channel::Displacement, jk, {v}, bad);
                else if (key == "tN") ok = checkChannel(Channel::NormalForce, jk, {v}, bad);
                if (!ok) {
                    err = DatasetError{path, 0, 0, "manifest run " + r["file"].get<std::string>() + ": " + bad.message};
                    return false;
                }
                s[pk] = v;
            }
        m.runs[baseName(r["file"].get<std::string>())] = s;
        ++idx;
    }
    out = std::move(m);
    return true;
}

static double mean(const std::vector<double>& v) {
    double s = 0;
    for (double x : v) s += x;
    return v.empty() ? 0.0 : s / static_cast<double>(v.size());
}

bool applyRunSet(Dataset& ds, const std::string& spec, std::string* error) {
    const auto colon = spec.rfind(':', spec.find('='));
    std::string key, value;
    if (colon == std::string::npos || !splitPair(spec.substr(colon + 1), key, value)) {
        if (error) *error = "--run-set '" + spec + "': expected FILE:KEY=VALUE, e.g. run_01.csv:tN=6.2";
        return false;
    }
    const std::string file = spec.substr(0, colon);
    double v = 0;
    std::string why;
    if (!parseParamValue(key, value, v, &why)) {
        if (error) *error = "--run-set '" + spec + "': " + why;
        return false;
    }
    bool hit = false;
    for (Run& r : ds.runs)
        if (r.file == file || r.name() == file || r.name() == baseName(file)) {
            r.settings[key] = v;
            r.settingSource[key] = "run-set";
            hit = true;
        }
    if (!hit) {
        if (error) *error = "--run-set '" + spec + "': no loaded run is called '" + file + "'";
        return false;
    }
    return true;
}

bool loadDataset(const std::vector<std::string>& files, const DatasetOptions& options, Dataset& out, DatasetError& err) {
    if (files.empty()) {
        err = DatasetError{"", 0, 0, "no data files given"};
        return false;
    }
    Dataset ds;
    Manifest man;
    if (!options.manifestPath.empty()) {
        if (!readManifest(options.manifestPath, man, err)) return false;
        ds.manifestPath = options.manifestPath;
    }
    for (const std::string& f : files) {
        Run r;
        if (!loadRun(f, options.mapping, r, err)) return false;
        if (!man.path.empty()) {
            for (const auto& [k, v] : man.common) { r.settings[k] = v; r.settingSource[k] = "manifest"; }
            const auto it = man.runs.find(r.name());
            if (it == man.runs.end()) {
                err = DatasetError{man.path, 0, 0, "manifest lists no run for data file '" + r.name() + "'"};
                return false;
            }
            for (const auto& [k, v] : it->second) { r.settings[k] = v; r.settingSource[k] = "manifest"; }
        }
        if (r.has(Signal::Normal)) {
            r.settings["tN"] = mean(r[Signal::Normal]);
            r.settingSource["tN"] = "column " + r.sourceColumn[Signal::Normal] + " (mean)";
        } else if (r.has(Signal::Tension) && !r.settings.count("tN")) {
            r.settings["tN"] = mean(r[Signal::Tension]);
            r.settingSource["tN"] = "column " + r.sourceColumn[Signal::Tension] + " (mean; reference load)";
        }
        ds.runs.push_back(std::move(r));
    }
    for (const std::string& spec : options.runSets) {
        std::string why;
        if (!applyRunSet(ds, spec, &why)) {
            err = DatasetError{"--run-set", 0, 0, why};
            return false;
        }
    }
    out = std::move(ds);
    return true;
}

}  // namespace stickslip::io
