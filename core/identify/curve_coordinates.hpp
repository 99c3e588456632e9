// The steady-state-curve coordinates of the rate-state fit (DatasetFitSettings::curveCoordinates).
//
// Eq. 5, μ_ss(V) = μ + C1 (e^{−V/v_c} − 1) + η V, expanded at V = 0 is μ + s V + κ V²/2 − …
// with slope s = η − C1/v_c and curvature κ = C1/v_c². Measured runs fix s and κ well and v_c
// poorly, so in (C1, η, v_c) the cost has a long curved valley; in (κ, s, v_c) it is straight.
// The solver moves in (κ, s, v_c); everything the user sees is in C1, η, v_c.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "fit.hpp"

namespace stickslip::identify {

class CurveCoordinates {
public:
    static constexpr const char* kCurvature = "C1/vc^2";  // κ, s²/m², log scale in [1e-6, 1e9]
    static constexpr const char* kSlope = "eta-C1/vc";    // s, s/m, linear in [−50, 50]
    static constexpr double kCurvatureLower = 1e-6, kCurvatureUpper = 1e9, kSlopeLower = -50.0, kSlopeUpper = 50.0;

    // When C1, η and v_c are all free in `params` and no scan names C1 or η: rewrites the C1
    // and η entries as κ and s (starting values mapped, clamped to their bounds), remembers the
    // physical bounds of C1 and η, and returns an active object. Else an inactive one.
    static CurveCoordinates install(std::vector<FitParameter>& params, const std::vector<ParameterScan>& scans);
    bool active() const { return active_; }
    // Whether a fit can start from `params` in these coordinates: C1, η and v_c free, C1 and η
    // strictly inside their own bounds (on a bound the valley ends there, and a bound of C1 or
    // η is not a bound of κ, s), and κ, s strictly inside theirs, so that install() keeps the
    // start where it is instead of clamping it (a start moved to a bound is another start).
    static bool startInside(const std::vector<FitParameter>& params);
    // Whether `name` is one of the two coordinates install() writes (κ or s).
    static bool isCoordinate(const std::string& name) { return name == kCurvature || name == kSlope; }

    // C1 = κ v_c², η = s + κ v_c from `vals` (problem order) into `values`, replacing κ and s.
    void toLaw(const std::vector<double>& vals, std::map<std::string, double>& values) const;
    // C1 and η (as toLaw wrote them) within the physical bounds of their original entries.
    bool withinLawBounds(const std::map<std::string, double>& values) const;
    // The fit result back in C1, η, v_c: names, values, and the covariance by the delta method
    // Cov = G Cov_int Gᵀ, G = ∂(C1, η, v_c)/∂(κ, s, v_c), hence standard errors and
    // correlations (NaN standard errors stay NaN). Notes the coordinates in solverSummary.
    void restore(FitResult& fit) const;

private:
    bool active_ = false;
    size_t iC1_ = 0, iEta_ = 0, iVc_ = 0;
    FitParameter c1_, eta_;  // the physical entries (bounds)
};

}  // namespace stickslip::identify
