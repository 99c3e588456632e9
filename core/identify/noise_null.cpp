#include "noise_null.hpp"
#include "diagnostics.hpp"

#include <algorithm>
#include <cmath>
#include <random>

namespace stickslip::identify {

void fitAr1(const std::vector<double>& r, const std::vector<char>& used, double& phi, double& sigma) {
    double ss = 0, n = 0, c0 = 0, c1 = 0;
    for (size_t i = 0; i < r.size(); ++i) {
        if (!used[i]) continue;
        ss += r[i] * r[i];
        n += 1;
        if (i > 0 && used[i - 1]) {
            c0 += r[i - 1] * r[i - 1];
            c1 += r[i - 1] * r[i];
        }
    }
    sigma = n > 0 ? std::sqrt(ss / n) : 0.0;
    phi = c0 > 0 ? std::clamp(c1 / c0, -0.99, 0.99) : 0.0;
}

std::vector<double> noiseReplica(const std::vector<NoiseBlock>& blocks, size_t total, uint64_t seed) {
    std::vector<double> e(total, 0.0);
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> normal(0.0, 1.0);
    for (const NoiseBlock& b : blocks) {
        if (b.offset + b.length > total || b.used.size() != b.length) continue;
        const double innov = b.sigma * std::sqrt(std::max(0.0, 1.0 - b.phi * b.phi));
        double x = b.sigma * normal(rng);  // stationary start
        for (size_t k = 0; k < b.length; ++k) {
            if (k > 0) x = b.phi * x + innov * normal(rng);
            if (b.used[k]) e[b.offset + k] = x;
        }
    }
    return e;
}

double NullGains::quantile(double p) const {
    if (gains.empty()) return 0.0;
    const double q = std::ceil(std::clamp(p, 0.0, 1.0) * static_cast<double>(gains.size()));
    const size_t k = static_cast<size_t>(std::clamp(q, 1.0, static_cast<double>(gains.size()))) - 1;
    return gains[k];
}

ProjectionBases projectionBases(const Eigen::MatrixXd& J0, const Eigen::MatrixXd& Jc) {
    ProjectionBases out;
    const Eigen::Index n = Jc.rows();
    if (n == 0 || Jc.cols() == 0 || (J0.cols() > 0 && J0.rows() != n)) return out;
    // Orthonormal basis of span(J_0), then of the part of span(J_c) orthogonal to it.
    Eigen::MatrixXd R = Jc;
    if (J0.cols() > 0) {
        Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr0(J0);
        qr0.setThreshold(1e-9);
        const Eigen::Index r0 = qr0.rank();
        out.Q0 = (qr0.householderQ() * Eigen::MatrixXd::Identity(n, r0));
        R -= out.Q0 * (out.Q0.transpose() * Jc);
    } else {
        out.Q0.resize(n, 0);
    }
    // Dependence measured against the columns' own size before the projection.
    Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qrc(R);
    const double scale = std::max(Jc.norm(), 1e-300);
    qrc.setThreshold(1e-9 * scale / std::max(R.norm(), 1e-300));
    const Eigen::Index rc = qrc.rank();
    out.Qc = rc > 0 ? Eigen::MatrixXd(qrc.householderQ() * Eigen::MatrixXd::Identity(n, rc)) : Eigen::MatrixXd(n, 0);
    out.valid = true;
    return out;
}

NullGains projectionGainNull(const Eigen::MatrixXd& J0, const Eigen::MatrixXd& Jc, const std::vector<NoiseBlock>& blocks,
                             int replicas, uint64_t seed) {
    const ProjectionBases pb = projectionBases(J0, Jc);
    if (!pb.valid) return {};
    return projectionGainNull(pb, blocks, static_cast<size_t>(Jc.rows()), replicas, seed);
}

NullGains projectionGainNull(const ProjectionBases& pb, const std::vector<NoiseBlock>& blocks, size_t rows, int replicas,
                             uint64_t seed, const std::vector<double>* offset) {
    NullGains out;
    if (!pb.valid || (offset && offset->size() != rows)) return out;
    const Eigen::Index n = static_cast<Eigen::Index>(rows), rc = pb.Qc.cols();
    out.rankExtra = static_cast<int>(rc);
    if (rc == 0) {
        out.gains.assign(static_cast<size_t>(std::max(replicas, 0)), 0.0);
        return out;
    }
    Eigen::VectorXd qd = Eigen::VectorXd::Zero(rc);
    if (offset) {
        qd = pb.Qc.transpose() * Eigen::Map<const Eigen::VectorXd>(offset->data(), n);
        out.offsetGain = qd.squaredNorm();
    }
    for (int b = 0; b < replicas; ++b) {
        const std::vector<double> e = noiseReplica(blocks, static_cast<size_t>(n), seed + static_cast<uint64_t>(b));
        const Eigen::Map<const Eigen::VectorXd> ev(e.data(), n);
        out.gains.push_back((pb.Qc.transpose() * ev + qd).squaredNorm());
    }
    std::sort(out.gains.begin(), out.gains.end());
    return out;
}

double momentMatchedGammaQuantile(const std::vector<double>& gains, double p) {
    double mean = 0, var = 0, largest = 0;
    const double n = static_cast<double>(gains.size());
    for (double g : gains) {
        mean += std::max(g, 0.0) / n;
        largest = std::max(largest, g);
    }
    for (double g : gains) var += (std::max(g, 0.0) - mean) * (std::max(g, 0.0) - mean) / std::max(n - 1.0, 1.0);
    if (gains.size() < 2 || !(var > 0.0) || !(mean > 0.0)) return largest;
    return gammaQuantile(p, mean * mean / var, var / mean);
}

}  // namespace stickslip::identify
