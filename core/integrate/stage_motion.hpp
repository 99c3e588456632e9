// Stage displacement u(t): harmonic (the paper's drive) or tabulated (measured runs).
#pragma once

#include <optional>
#include <vector>

#include "../params.hpp"

namespace stickslip {

class StageMotion {
public:
    // u(t) = A sin(ω t + φ)
    static StageMotion harmonic(const DriveParams& d);
    // u(t) linearly interpolated in (t, u); t strictly increasing, at least two samples.
    // Outside the table u is held at the end values. A table that breaks those rules gives
    // no motion (nullopt) and, when `issues` is given, every rule it breaks (field, value,
    // allowed range; formatIssues for a message): tables come from measured runs on worker
    // threads, where an exception would end the worker instead of reporting the run.
    static std::optional<StageMotion> tabulated(std::vector<double> t_s, std::vector<double> u_m,
                                                ParamIssues* issues = nullptr);
    // The rules of tabulated(): empty when the table is fine. Names the first offending time.
    static ParamIssues validateTable(const std::vector<double>& t_s, const std::vector<double>& u_m);

    double displacement(double t) const;
    double velocity(double t) const;
    bool isHarmonic() const { return table_t_.empty(); }
    double amplitude() const { return A_; }   // harmonic only [m]
    double omega() const { return omega_; }    // harmonic only [rad/s]
    double phase() const { return phase_; }    // harmonic only [rad]

private:
    double A_ = 0, omega_ = 0, phase_ = 0;
    std::vector<double> table_t_, table_u_;
};

}  // namespace stickslip
