// Measured runs of a friction rig: CSV columns mapped by name to signals, units converted to
// SI, per-run known settings (k, A, f, t_N, m) from columns, a manifest or the command line.
// A dataset is one or more runs fitted jointly with shared law parameters (issue 5).
#pragma once

#include <array>
#include <map>
#include <string>
#include <vector>

namespace stickslip::io {

// The signals a run can carry. Keys (for --columns / --units) and default column names:
enum class Signal {
    Time,         // "time"         time_s             [s]
    StageDisp,    // "stage_disp"   stage_disp_m       u [m]
    SliderDisp,   // "slider_disp"  slider_disp_m      x [m]
    Slip,         // "slip"         slip_m             g = u − x [m]
    RelVel,       // "rel_vel"      rel_vel_mps        V = u̇ − ẋ [m/s]
    StageVel,     // "stage_vel"    stage_vel_mps      u̇ [m/s]
    SliderVel,    // "slider_vel"   slider_vel_mps     ẋ [m/s]
    Friction,     // "friction"     friction_force_N   F [N]
    Normal,       // "normal"       normal_force_N     t_N [N]
    Tension,      // "tension"      band_tension_N     pre-tension that sets the normal load [N]
    SliderAccel,  // "slider_accel" slider_accel_mps2  ẍ [m/s²]
};
constexpr size_t kSignalCount = 11;

const char* signalKey(Signal s);
const char* defaultColumn(Signal s);
const char* signalUnit(Signal s);  // SI unit as text: "s", "m", "m/s", "N", "m/s^2"
bool parseSignal(const std::string& key, Signal& out);

// Which column holds which signal and in which unit. Signals not in `columns` use their
// default column name (if the file has it); a signal mapped to "-" (kNotMapped) or "" is not
// read at all, even when the file has its default column (time cannot be unmapped). Units
// default to SI.
inline constexpr const char* kNotMapped = "-";
struct ColumnMapping {
    std::map<Signal, std::string> columns;  // signal -> column name, or "-" / "" = not read
    std::map<Signal, double> scaleToSI;     // signal -> factor (e.g. mm: 1e-3)
    std::map<Signal, std::string> unitText; // as given, for reports

    // "friction=Fx" (several may be comma-separated: "friction=Fx,time=t"); "friction=-"
    // means "do not read friction".
    bool addColumns(const std::string& spec, std::string* error);
    // "stage_disp=mm" (comma-separated allowed); the unit must have the signal's dimension.
    bool addUnits(const std::string& spec, std::string* error);
};

// A bad input, located in a file (line/column 1-based; 0 when not applicable).
struct DatasetError {
    std::string file;
    long line = 0;
    long column = 0;
    std::string message;
    std::string what() const;  // "file:line:column: message"
};

// One measured run.
struct Run {
    std::string file;                                // path as given
    std::vector<std::string> comments;               // '#' lines of the file
    std::array<std::vector<double>, kSignalCount> channels;  // SI; empty when absent
    std::map<Signal, std::string> sourceColumn;      // which column each signal came from
    // Known settings, SI, keyed like SimParams keys: k, A, f, tN, m, c, … and where each came
    // from ("column", "manifest", "run-set").
    std::map<std::string, double> settings;
    std::map<std::string, std::string> settingSource;

    bool has(Signal s) const { return !channels[static_cast<size_t>(s)].empty(); }
    const std::vector<double>& operator[](Signal s) const { return channels[static_cast<size_t>(s)]; }
    std::vector<double>& operator[](Signal s) { return channels[static_cast<size_t>(s)]; }
    size_t size() const { return channels[0].size(); }
    bool setting(const std::string& key, double& value) const;  // false if unknown
    std::string name() const;                                   // file name without folders
};

// Dataset manifest (format of shared/data/synthetic/*/manifest.json):
// {"nominal_mass_kg": 0.53, "runs": [{"file": "run_01.csv", "k_N_per_m": .., "A_m": ..,
//  "f_Hz": .., "tN_N": .., "m_kg"?: .., "c_Ns_per_m"?: ..}, ...]}.
struct Manifest {
    std::string path;
    std::map<std::string, std::map<std::string, double>> runs;  // file name -> settings (SimParams keys)
    std::map<std::string, double> common;                       // e.g. {"m": nominal mass}
};
bool readManifest(const std::string& path, Manifest& out, DatasetError& err);
// The same from the manifest's text; `path` is the name used in errors and Manifest::path.
bool parseManifest(const std::string& text, const std::string& path, Manifest& out, DatasetError& err);

struct Dataset {
    std::vector<Run> runs;
    std::string manifestPath;
};

struct DatasetOptions {
    ColumnMapping mapping;
    std::string manifestPath;           // optional
    std::vector<std::string> runSets;   // "FILE:KEY=VALUE" (VALUE may carry a unit: "6.2N")
};

// Reads one CSV into a Run: time column required, every mapped column must exist, time
// strictly increasing. On error returns false and leaves `out` untouched.
bool loadRun(const std::string& path, const ColumnMapping& mapping, Run& out, DatasetError& err);

// Reads all files, then settings in rising priority: manifest, columns (t_N = mean of the
// normal force column; else of the tension column), --run-set. Nothing is half-loaded: on
// any error `out` is untouched.
bool loadDataset(const std::vector<std::string>& files, const DatasetOptions& options, Dataset& out, DatasetError& err);

// Applies one "FILE:KEY=VALUE" to the run whose path or file name is FILE.
bool applyRunSet(Dataset& ds, const std::string& spec, std::string* error);

}  // namespace stickslip::io
