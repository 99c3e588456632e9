#include "fourier.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <numbers>

namespace stickslip::dsp {

// Sums in the column order of the normal equations (mean, sin 1, cos 1, sin 2, …), the order in
// which the cleaning's stage fit always evaluated its series: cleaned runs stay bit-identical.
double HarmonicFit::at(double t) const {
    double v = 0;
    v += mean * 1.0;
    for (size_t k = 0; k < cosine.size(); ++k) {
        const double h = static_cast<double>(k + 1);
        v += sine[k] * std::sin(h * omega * t);
        v += cosine[k] * std::cos(h * omega * t);
    }
    return v;
}

double HarmonicFit::amplitude(int harmonic) const {
    if (harmonic < 1 || harmonic > order()) return 0.0;
    const size_t k = static_cast<size_t>(harmonic - 1);
    return std::hypot(cosine[k], sine[k]);
}

HarmonicFit harmonicFit(const std::vector<double>& t, const std::vector<double>& y, double f, int order, size_t b,
                        size_t e) {
    HarmonicFit fit;
    order = std::max(order, 0);
    fit.frequency_Hz = f;
    fit.omega = 2.0 * std::numbers::pi * f;
    const double w = fit.omega;
    const Eigen::Index cols = 1 + 2 * order;
    // Column k: 1 for k = 0, sin(hωt) for odd k, cos(hωt) for even k, h = (k + 1)/2.
    auto basis = [&](double tt, Eigen::Index k) {
        if (k == 0) return 1.0;
        const double h = static_cast<double>((k + 1) / 2);
        return (k % 2) ? std::sin(h * w * tt) : std::cos(h * w * tt);
    };
    // Normal equations accumulated sample by sample: no N × cols design matrix for long records.
    Eigen::MatrixXd AtA = Eigen::MatrixXd::Zero(cols, cols);
    Eigen::VectorXd Aty = Eigen::VectorXd::Zero(cols), row(cols);
    for (size_t i = b; i < e; ++i) {
        for (Eigen::Index k = 0; k < cols; ++k) row(k) = basis(t[i], k);
        AtA.noalias() += row * row.transpose();
        Aty += row * y[i];
    }
    const Eigen::VectorXd c = AtA.ldlt().solve(Aty);
    fit.mean = c(0);
    for (Eigen::Index h = 1; h <= order; ++h) {
        fit.sine.push_back(c(2 * h - 1));
        fit.cosine.push_back(c(2 * h));
    }
    fit.samples = e > b ? e - b : 0;
    double ss = 0;
    for (size_t i = b; i < e; ++i) {
        const double v = fit.at(t[i]);
        ss += (v - y[i]) * (v - y[i]);
    }
    fit.rss = ss;
    return fit;
}

std::vector<double> fourierFit(const std::vector<double>& t, const std::vector<double>& y, double f, int order, size_t b,
                               size_t e, double* rss) {
    const HarmonicFit fit = harmonicFit(t, y, f, order, b, e);
    std::vector<double> out(t.size());
    for (size_t i = 0; i < t.size(); ++i) out[i] = fit.at(t[i]);
    if (rss) *rss = fit.rss;
    return out;
}

double refineFrequency(const std::vector<double>& t, const std::vector<double>& y, double f0, int order, double span) {
    // Only the residual is needed: the fit is not evaluated outside the fitted samples.
    auto cost = [&](double f) { return harmonicFit(t, y, f, order, 0, t.size()).rss; };
    const double g = (std::sqrt(5.0) - 1.0) / 2.0;
    double a = f0 * (1 - span), b = f0 * (1 + span);
    double c = b - g * (b - a), d = a + g * (b - a);
    double fc = cost(c), fd = cost(d);
    for (int it = 0; it < 40 && (b - a) > 1e-9 * f0; ++it) {
        if (fc < fd) { b = d; d = c; fd = fc; c = b - g * (b - a); fc = cost(c); }
        else { a = c; c = d; fc = fd; d = a + g * (b - a); fd = cost(d); }
    }
    return 0.5 * (a + b);
}

}  // namespace stickslip::dsp
