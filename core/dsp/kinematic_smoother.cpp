#include "kinematic_smoother.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>

#include "stats.hpp"

namespace stickslip::dsp {

std::string KinematicSmootherOptions::validate() const {
    if (!(std::isfinite(dispNoise) && dispNoise >= 0.0))
        return "disp_noise = " + std::to_string(dispNoise) + " m: must be finite and >= 0 (0 = estimate)";
    if (!(std::isfinite(accelNoise) && accelNoise >= 0.0))
        return "accel_noise = " + std::to_string(accelNoise) + " m/s^2: must be finite and >= 0 (0 = estimate)";
    return {};
}

namespace {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;

// State (x, v, b) with b the accelerometer's offset; the acceleration linear between samples
// (exact for a piecewise-linear a): x' = x + v dt + (2 a_k + a_k+1 − 3b) dt²/6,
// v' = v + (a_k + a_k+1 − 2b) dt/2, b' = b. Each sample's white noise enters through its
// weight in both (its correlation between neighbouring steps is neglected).
Mat3 transition(double dt) {
    Mat3 F;
    F << 1, dt, -dt * dt / 2, 0, 1, -dt, 0, 0, 1;
    return F;
}

struct Pass {
    std::vector<Vec3> mf, mp;  // filtered and predicted means
    std::vector<Mat3> Pf, Pp;  // their covariances
    double logLik = 0.0;
};

Pass filterPass(const std::vector<double>& x, const std::vector<double>& a, double dt, double sx, double sa, bool keep) {
    const size_t n = x.size();
    const Mat3 F = transition(dt);
    const Vec3 B0(dt * dt / 3, dt / 2, 0), B1(dt * dt / 6, dt / 2, 0);
    const Mat3 Q = sa * sa * (B0 * B0.transpose() + B1 * B1.transpose());
    const double R = sx * sx;
    // A diffuse start: the first two positions fix x and v, the offset is learned over the run.
    double vScale = 0, aScale = 0;
    for (size_t i = 1; i < n; ++i) vScale = std::max(vScale, std::abs(x[i] - x[i - 1]) / dt);
    for (double ai : a) aScale = std::max(aScale, std::abs(ai));
    Vec3 m(x[0], (x[1] - x[0]) / dt, 0.0);
    Mat3 P = Vec3(R + 1e-30, std::pow(10 * vScale + 1e-12, 2), std::pow(aScale + 1e-12, 2)).asDiagonal();
    Pass out;
    if (keep) {
        out.mf.resize(n); out.mp.resize(n); out.Pf.resize(n); out.Pp.resize(n);
    }
    for (size_t k = 0; k < n; ++k) {
        if (k > 0) {
            m = F * m + B0 * a[k - 1] + B1 * a[k];
            P = F * P * F.transpose() + Q;
        }
        if (keep) { out.mp[k] = m; out.Pp[k] = P; }
        const double S = P(0, 0) + R, e = x[k] - m(0);
        if (k >= 8) out.logLik -= 0.5 * (std::log(S) + e * e / S);  // the diffuse start's first steps left out
        const Vec3 K = P.col(0) / S;
        m += K * e;
        P -= K * P.row(0);
        P = 0.5 * (P + P.transpose());
        if (keep) { out.mf[k] = m; out.Pf[k] = P; }
    }
    return out;
}

}  // namespace

KinematicEstimate smoothKinematics(const std::vector<double>& x, const std::vector<double>& a, double dt,
                                   const KinematicSmootherOptions& opt) {
    KinematicEstimate est;
    const size_t n = x.size();
    if (const std::string bad = opt.validate(); !bad.empty()) { est.message = bad; return est; }
    if (a.size() != n || n < 16) { est.message = "position and acceleration need >= 16 samples of equal length"; return est; }
    if (!(std::isfinite(dt) && dt > 0)) { est.message = "dt = " + std::to_string(dt) + " s: must be finite and > 0"; return est; }
    for (size_t i = 0; i < n; ++i)
        if (!std::isfinite(x[i]) || !std::isfinite(a[i])) {
            est.message = std::string(std::isfinite(x[i]) ? "acceleration" : "position") + " sample " + std::to_string(i) + " is not finite";
            return est;
        }
    double xScale = 0, aScale = 0;
    for (size_t i = 0; i < n; ++i) { xScale = std::max(xScale, std::abs(x[i])); aScale = std::max(aScale, std::abs(a[i])); }
    // Floors keep the filter's gains finite on noise-free signals (a smoother that then
    // returns the measured position).
    const double sx = std::max(opt.dispNoise > 0 ? opt.dispNoise : whiteNoiseRms(x, 3), 1e-9 * xScale + 1e-15);
    const double aFloor = 1e-9 * aScale + 1e-12;
    double sa = opt.accelNoise;
    if (!(sa > 0)) {
        // Maximum likelihood of the innovations over log σ_a (golden section), bracketed three
        // decades either side of the second differences' robust estimate.
        const double s0 = std::max(whiteNoiseRms(a, 2), aFloor);
        double lo = std::log(s0) - 3 * std::log(10.0), hi = std::log(s0) + 3 * std::log(10.0);
        const double r = (std::sqrt(5.0) - 1) / 2;
        auto cost = [&](double ls) { return -filterPass(x, a, dt, sx, std::exp(ls), false).logLik; };
        double c = hi - r * (hi - lo), d = lo + r * (hi - lo), fc = cost(c), fd = cost(d);
        for (int it = 0; it < 40 && hi - lo > 1e-3; ++it) {
            if (fc < fd) { hi = d; d = c; fd = fc; c = hi - r * (hi - lo); fc = cost(c); }
            else { lo = c; c = d; fc = fd; d = lo + r * (hi - lo); fd = cost(d); }
        }
        sa = std::exp(0.5 * (lo + hi));
    }
    sa = std::max(sa, aFloor);
    Pass p = filterPass(x, a, dt, sx, sa, true);
    const Mat3 F = transition(dt);
    est.x.resize(n);
    est.v.resize(n);
    Vec3 ms = p.mf[n - 1];
    est.x[n - 1] = ms(0);
    est.v[n - 1] = ms(1);
    est.accelOffset = ms(2);
    for (size_t k = n - 1; k-- > 0;) {
        const Mat3 C = p.Pf[k] * F.transpose() * p.Pp[k + 1].ldlt().solve(Mat3::Identity());
        ms = p.mf[k] + C * (ms - p.mp[k + 1]);
        est.x[k] = ms(0);
        est.v[k] = ms(1);
    }
    for (size_t k = 0; k < n; ++k)
        if (!std::isfinite(est.x[k]) || !std::isfinite(est.v[k])) {
            est.x.clear(); est.v.clear();
            est.message = "the smoother diverged at sample " + std::to_string(k);
            return est;
        }
    est.dispNoise = sx;
    est.accelNoise = sa;
    est.logLikelihood = p.logLik;
    est.ok = true;
    return est;
}

}  // namespace stickslip::dsp
