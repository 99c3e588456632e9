// See curve_coordinates.hpp.
#include "curve_coordinates.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace stickslip::identify {

CurveCoordinates CurveCoordinates::install(std::vector<FitParameter>& params, const std::vector<ParameterScan>& scans) {
    CurveCoordinates cc;
    for (const ParameterScan& sc : scans)
        if (sc.name == "C1" || sc.name == "eta") return cc;
    long iC1 = -1, iEta = -1, iVc = -1;
    for (size_t i = 0; i < params.size(); ++i) {
        if (!params[i].free) continue;
        if (params[i].name == "C1") iC1 = static_cast<long>(i);
        if (params[i].name == "eta") iEta = static_cast<long>(i);
        if (params[i].name == "vc") iVc = static_cast<long>(i);
    }
    if (iC1 < 0 || iEta < 0 || iVc < 0) return cc;
    cc.iC1_ = static_cast<size_t>(iC1);
    cc.iEta_ = static_cast<size_t>(iEta);
    cc.iVc_ = static_cast<size_t>(iVc);
    cc.c1_ = params[cc.iC1_];
    cc.eta_ = params[cc.iEta_];
    const double vc = params[cc.iVc_].value, C1 = cc.c1_.value, eta = cc.eta_.value;
    FitParameter kappa{kCurvature, 0.0, kCurvatureLower, kCurvatureUpper, true, ParamScale::Log};
    FitParameter slope{kSlope, 0.0, kSlopeLower, kSlopeUpper, true, ParamScale::Linear};
    kappa.value = std::clamp(C1 / (vc * vc), kappa.lower, kappa.upper);
    slope.value = std::clamp(eta - C1 / vc, slope.lower, slope.upper);
    params[cc.iC1_] = kappa;
    params[cc.iEta_] = slope;
    cc.active_ = true;
    return cc;
}

bool CurveCoordinates::startInside(const std::vector<FitParameter>& params) {
    const FitParameter *c1 = nullptr, *eta = nullptr, *vc = nullptr;
    for (const FitParameter& p : params) {
        if (!p.free) continue;
        if (p.name == "C1") c1 = &p;
        if (p.name == "eta") eta = &p;
        if (p.name == "vc") vc = &p;
    }
    if (!c1 || !eta || !vc || !(vc->value > 0)) return false;
    for (const FitParameter* q : {c1, eta}) {  // by 1e-6 of the range: fit.cpp's "on a bound"
        const double tol = 1e-6 * (q->upper - q->lower);
        if (!(q->value > q->lower + tol && q->value < q->upper - tol)) return false;
    }
    const double kappa = c1->value / (vc->value * vc->value), s = eta->value - c1->value / vc->value;
    return kappa > kCurvatureLower && kappa < kCurvatureUpper && s > kSlopeLower && s < kSlopeUpper;
}

void CurveCoordinates::toLaw(const std::vector<double>& vals, std::map<std::string, double>& values) const {
    const double kappa = vals[iC1_], s = vals[iEta_], vc = vals[iVc_];
    values.erase(kCurvature);
    values.erase(kSlope);
    values["C1"] = kappa * vc * vc;
    values["eta"] = s + kappa * vc;
}
bool CurveCoordinates::withinLawBounds(const std::map<std::string, double>& values) const {
    const double C1 = values.at("C1"), eta = values.at("eta");
    return C1 >= c1_.lower && C1 <= c1_.upper && eta >= eta_.lower && eta <= eta_.upper;
}

void CurveCoordinates::restore(FitResult& fit) const {
    const double kappa = fit.values[iC1_], s = fit.values[iEta_], vc = fit.values[iVc_];
    fit.names[iC1_] = "C1";
    fit.names[iEta_] = "eta";
    fit.values[iC1_] = kappa * vc * vc;
    fit.values[iEta_] = s + kappa * vc;
    const size_t p = fit.freeNames.size();
    auto freePos = [&](const char* n) {
        return static_cast<size_t>(std::find(fit.freeNames.begin(), fit.freeNames.end(), n) - fit.freeNames.begin());
    };
    const size_t fK = freePos(kCurvature), fS = freePos(kSlope), fV = freePos("vc");
    if (fK >= p || fS >= p || fV >= p) return;
    fit.freeNames[fK] = "C1";
    fit.freeNames[fS] = "eta";
    if (fit.correlation.size() != p * p) return;
    // Free standard errors in freeNames order (fit.stderrs is in problem order).
    std::vector<double> se(p);
    for (size_t a = 0; a < p; ++a) {
        const auto it = std::find(fit.names.begin(), fit.names.end(), fit.freeNames[a]);
        se[a] = fit.stderrs[static_cast<size_t>(it - fit.names.begin())];
    }
    if (!std::all_of(se.begin(), se.end(), [](double v) { return std::isfinite(v); })) {
        fit.stderrs[iC1_] = fit.stderrs[iEta_] = std::numeric_limits<double>::quiet_NaN();
        return;  // not identifiable: no standard errors to transform
    }
    std::vector<double> cov(p * p), G(p * p, 0.0), out(p * p, 0.0);
    for (size_t a = 0; a < p; ++a)
        for (size_t b = 0; b < p; ++b) cov[a * p + b] = fit.correlation[a * p + b] * se[a] * se[b];
    for (size_t a = 0; a < p; ++a) G[a * p + a] = 1.0;
    G[fK * p + fK] = vc * vc;          // ∂C1/∂κ
    G[fK * p + fV] = 2.0 * kappa * vc; // ∂C1/∂v_c
    G[fS * p + fS] = 1.0;              // ∂η/∂s
    G[fS * p + fK] = vc;               // ∂η/∂κ
    G[fS * p + fV] = kappa;            // ∂η/∂v_c
    for (size_t a = 0; a < p; ++a)
        for (size_t b = 0; b < p; ++b) {
            double acc = 0;
            for (size_t i = 0; i < p; ++i)
                for (size_t j = 0; j < p; ++j) acc += G[a * p + i] * cov[i * p + j] * G[b * p + j];
            out[a * p + b] = acc;
        }
    for (size_t a = 0; a < p; ++a) {
        const auto it = std::find(fit.names.begin(), fit.names.end(), fit.freeNames[a]);
        fit.stderrs[static_cast<size_t>(it - fit.names.begin())] = std::sqrt(std::max(0.0, out[a * p + a]));
    }
    for (size_t a = 0; a < p; ++a)
        for (size_t b = 0; b < p; ++b) {
            const double d = std::sqrt(out[a * p + a] * out[b * p + b]);
            fit.correlation[a * p + b] = d > 0 ? out[a * p + b] / d : (a == b ? 1.0 : 0.0);
        }
    fit.solverSummary = "solver coordinates: " + std::string(kCurvature) + ", " + kSlope + ", vc (steady-state curve)\n" +
                        fit.solverSummary;
}

}  // namespace stickslip::identify
