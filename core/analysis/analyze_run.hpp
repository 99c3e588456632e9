// The paper's signal analyses of one run table (simulated or measured), found by column name:
// power spectrum peaks, autocorrelation decay time, stage–slider phase lag, friction-loop
// orientation counts and the 0–1 test, as one JSON document (`stickslip-cli analyze`, the
// Python module's analyze()).
//
// Columns used (any missing one only disables the analyses that need it):
//   time_s (required); stage_disp_m; slider_disp_m; rel_vel_mps (else stage_vel_mps − slider
//   velocity, else the central difference of stage − slider); friction_ratio (else
//   friction_force_N / normal_force_N, else friction_force_N / band_tension_N, else
//   friction_force_N alone — the orientation does not depend on a positive scale).
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "../io/csv_table.hpp"

namespace stickslip {

struct AnalyzeSettings {
    double frequency_Hz = 0;           // forcing frequency; 0 = from '# f = ' lines, else the stage spectrum
    double naturalFrequency_rad_s = 0; // ω_n; 0 = √(k/m) from '# k', '# m' lines, else not reported
    double maxLag_s = 2.0;             // autocorrelation lags up to this
};

// The analyses of table `t` (read from `path`, which names it in the JSON and in errors).
// False with *error ("path:line: ...") when the table has no time_s column, fewer than 64
// rows or a time that does not increase. `program` is stored under "program".
bool analyzeRunTable(const io::CsvTable& t, const std::string& path, const AnalyzeSettings& settings,
                     const std::string& program, nlohmann::json& out, std::string* error);

}  // namespace stickslip
