#include "savitzky_golay.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

namespace stickslip::dsp {

std::vector<double> savitzkyGolay(const std::vector<double>& y, double dt, int h, int order, int deriv) {
    const long n = static_cast<long>(y.size());
    std::vector<double> out(y.size(), 0.0);
    if (n == 0) return out;
    h = std::max(0, std::min(h, static_cast<int>((n - 1) / 2)));
    const int w = 2 * h + 1;
    order = std::min(order, w - 1);
    if (deriv > order) return out;  // the polynomial has no such derivative: zero
    // Weights for evaluating derivative `deriv` at position c of the window (c = 0..w−1):
    // the fit coefficients are (AᵀA)⁻¹Aᵀ y with A_jk = (j − c)^k, and the derivative at the
    // evaluation point is deriv! · coefficient[deriv] / dt^deriv.
    double fact = 1.0;
    for (int k = 2; k <= deriv; ++k) fact *= k;
    const double scale = fact / std::pow(dt, deriv);
    std::vector<Eigen::VectorXd> weights(static_cast<size_t>(w));
    for (int c = 0; c < w; ++c) {
        Eigen::MatrixXd A(w, order + 1);
        for (int j = 0; j < w; ++j)
            for (int k = 0; k <= order; ++k) A(j, k) = std::pow(static_cast<double>(j - c), k);
        const Eigen::MatrixXd P = (A.transpose() * A).ldlt().solve(A.transpose());
        weights[static_cast<size_t>(c)] = P.row(deriv).transpose() * scale;
    }
    for (long i = 0; i < n; ++i) {
        const long s = std::clamp(i - h, 0L, n - w);
        const Eigen::VectorXd& wt = weights[static_cast<size_t>(i - s)];
        double acc = 0.0;
        for (int j = 0; j < w; ++j) acc += wt(j) * y[static_cast<size_t>(s + j)];
        out[static_cast<size_t>(i)] = acc;
    }
    return out;
}

}  // namespace stickslip::dsp
