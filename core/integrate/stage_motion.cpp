#include "stage_motion.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace stickslip {

StageMotion StageMotion::harmonic(const DriveParams& d) {
    StageMotion m;
    m.A_ = d.amplitude_m;
    m.omega_ = d.omega();
    m.phase_ = d.phase_rad;
    return m;
}

ParamIssues StageMotion::validateTable(const std::vector<double>& t, const std::vector<double>& u) {
    ParamIssues out;
    if (t.size() < 2) out.push_back({"stage table samples", static_cast<double>(t.size()), ">= 2"});
    if (u.size() != t.size())
        out.push_back({"stage table u samples", static_cast<double>(u.size()),
                       "equal to the t samples (" + std::to_string(t.size()) + ")"});
    // Only the first step that does not increase: a bad table usually repeats one fault many times.
    for (size_t i = 1; i < t.size(); ++i)
        if (!(t[i] > t[i - 1])) {
            out.push_back({"stage table t[" + std::to_string(i) + "]", t[i],
                           "> t[" + std::to_string(i - 1) + "] = " + std::to_string(t[i - 1]) + " (time must increase strictly)"});
            break;
        }
    return out;
}

std::optional<StageMotion> StageMotion::tabulated(std::vector<double> t, std::vector<double> u, ParamIssues* issues) {
    ParamIssues bad = validateTable(t, u);
    if (!bad.empty()) {
        if (issues) *issues = std::move(bad);
        return std::nullopt;
    }
    if (issues) issues->clear();
    StageMotion m;
    m.table_t_ = std::move(t);
    m.table_u_ = std::move(u);
    return m;
}

double StageMotion::displacement(double t) const {
    if (table_t_.empty()) return A_ * std::sin(omega_ * t + phase_);
    if (t <= table_t_.front()) return table_u_.front();
    if (t >= table_t_.back()) return table_u_.back();
    const auto it = std::upper_bound(table_t_.begin(), table_t_.end(), t);
    const size_t i = static_cast<size_t>(it - table_t_.begin());
    const double w = (t - table_t_[i - 1]) / (table_t_[i] - table_t_[i - 1]);
    return table_u_[i - 1] + w * (table_u_[i] - table_u_[i - 1]);
}

double StageMotion::velocity(double t) const {
    if (table_t_.empty()) return A_ * omega_ * std::cos(omega_ * t + phase_);
    if (t < table_t_.front() || t > table_t_.back()) return 0.0;
    auto it = std::upper_bound(table_t_.begin(), table_t_.end(), t);
    if (it == table_t_.end()) --it;
    const size_t i = static_cast<size_t>(it - table_t_.begin());
    return (table_u_[i] - table_u_[i - 1]) / (table_t_[i] - table_t_[i - 1]);
}

}  // namespace stickslip
