// Uncertainty at the optimum of the fit engine (plain residuals r, m residuals, p free parameters):
//   σ̂² = Σ r² / (m − p − q),  q = nuisance parameters profiled out inside the callback,
//   Cov_z = σ̂² (J_zᵀ J_z)⁻¹,   Cov_v = D Cov_z D,  D = diag(dv/dz).
// Identifiability: with S = diag(JᵀJ)^(−1/2), the scaled matrix A = S JᵀJ S has unit diagonal
// and cond(A) measures how nearly dependent the parameters are, independently of their units.
// cond(A) > conditionLimit (or a zero column: a parameter without effect) → "not identifiable",
// standard errors NaN, and the eigenvector of the smallest eigenvalue names the culprits.
#include <Eigen/Dense>
#include <limits>

#include "fit_internal.hpp"

namespace stickslip::identify {

namespace detail {

namespace {

// The plain Jacobian at the optimum in internal coordinates: the problem's own
// (FitProblem::analyticJacobian) when it has one, else by central differences (one-sided
// against a bound): the 2p displaced points are computed together (in parallel when the
// problem can). False (status set) when a parameter cannot be displaced at all.
bool jacobianAtOptimum(const FitProblem& prob, const Mapping& map, PointEvaluator& evaluator, const std::vector<double>& bestZ,
                       const PointEvaluator::Result& base, FitResult& res, Eigen::MatrixXd& J) {
    const size_t p = map.freeIdx.size();
    const size_t m = prob.residualCount;
    std::vector<double> exact;
    if (analyticJacobianAt(map, bestZ, exact)) {  // the problem's own Jacobian, when it has one
        J = Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
            exact.data(), static_cast<Eigen::Index>(m), static_cast<Eigen::Index>(p));
        return true;
    }
    std::vector<std::vector<double>> displaced;
    std::vector<double> hPlus(p), hMinus(p);
    for (size_t k = 0; k < p; ++k) {
        double h = prob.relativeStep * std::max(std::abs(bestZ[k]), 1e-2);
        // stay inside the box: one-sided when against a bound
        double hp = std::min(h, map.upperZ(k) - bestZ[k]), hm = std::min(h, bestZ[k] - map.lowerZ(k));
        if (hp <= 0 && hm <= 0) { hp = h; hm = 0; }
        hPlus[k] = hp;
        hMinus[k] = hm;
        std::vector<double> zplus = bestZ, zminus = bestZ;
        zplus[k] += hp;
        zminus[k] -= hm;
        displaced.push_back(hp > 0 ? zplus : bestZ);
        displaced.push_back(hm > 0 ? zminus : bestZ);
    }
    const std::vector<PointEvaluator::Ptr> rd = evaluator.evaluate(displaced);
    J.resize(static_cast<Eigen::Index>(m), static_cast<Eigen::Index>(p));
    for (size_t k = 0; k < p; ++k) {
        // A side where the model cannot be evaluated (the edge of a feasible region that is not
        // a box in these coordinates, e.g. curve_coordinates.hpp) is replaced by the optimum:
        // a one-sided difference there.
        const PointEvaluator::Result& rp = rd[2 * k]->ok ? *rd[2 * k] : base;
        const PointEvaluator::Result& rm = rd[2 * k + 1]->ok ? *rd[2 * k + 1] : base;
        const double span = (rd[2 * k]->ok ? hPlus[k] : 0.0) + (rd[2 * k + 1]->ok ? hMinus[k] : 0.0);
        if (!(span > 0.0)) {
            res.status = FitStatus::Failed;
            res.message = "model cannot be evaluated next to the optimum (parameter " + res.freeNames[k] + ")";
            return false;
        }
        for (size_t i = 0; i < m; ++i)
            J(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(k)) = (rp.r[i] - rm.r[i]) / span;
    }
    return true;
}

// Identifiability (cond of the unit-diagonal scaled JᵀJ), and for an identifiable fit the
// standard errors and correlations in physical units (header comment).
void fillCovariance(const FitProblem& prob, const Mapping& map, const std::vector<double>& bestZ, const Eigen::MatrixXd& J,
                    double sigma2, FitResult& res) {
    const size_t p = map.freeIdx.size();
    const Eigen::MatrixXd JtJ = J.transpose() * J;
    Eigen::VectorXd d = JtJ.diagonal();
    std::vector<std::string> dead;
    for (size_t k = 0; k < p; ++k)
        if (!(d(static_cast<Eigen::Index>(k)) > 0.0)) dead.push_back(res.freeNames[k]);
    const Eigen::Index P = static_cast<Eigen::Index>(p);
    res.correlation.assign(p * p, std::numeric_limits<double>::quiet_NaN());
    // JᵀJ scaled to unit diagonal; a parameter without effect keeps a zero row and column
    // (pairCorrelation holds it).
    Eigen::VectorXd sdiag(P);
    for (Eigen::Index k = 0; k < P; ++k) sdiag(k) = d(k) > 0.0 ? 1.0 / std::sqrt(d(k)) : 0.0;
    const Eigen::MatrixXd A = sdiag.asDiagonal() * JtJ * sdiag.asDiagonal();
    res.scaledNormal.resize(p * p);
    Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(res.scaledNormal.data(), P, P) = A;
    res.conditionLimit = prob.conditionLimit;
    if (!dead.empty()) {
        res.identifiable = false;
        res.conditionNumber = std::numeric_limits<double>::infinity();
        res.identifiabilityMessage = "not identifiable: the residuals do not depend on";
        for (const auto& n : dead) res.identifiabilityMessage += " " + n;
    } else {
        Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(A);
        const Eigen::VectorXd ev = es.eigenvalues();  // ascending
        res.conditionNumber = ev(0) > 0 ? ev(P - 1) / ev(0) : std::numeric_limits<double>::infinity();
        if (!(res.conditionNumber <= prob.conditionLimit)) {
            res.identifiable = false;
            const Eigen::VectorXd w = es.eigenvectors().col(0);
            std::string who;
            for (Eigen::Index k = 0; k < P; ++k)
                if (std::abs(w(k)) > 0.3) who += (who.empty() ? "" : ", ") + res.freeNames[static_cast<size_t>(k)];
            res.identifiabilityMessage = "not identifiable: cond(JtJ, unit-diagonal scaled) = " + fmt(res.conditionNumber) +
                                         " > " + fmt(prob.conditionLimit) + "; nearly dependent: " + who;
        } else {
            res.identifiable = true;
            // (JᵀJ)⁻¹ = S A⁻¹ S, A⁻¹ from the eigen-decomposition (well conditioned here).
            const Eigen::MatrixXd Ainv = es.eigenvectors() * ev.cwiseInverse().asDiagonal() * es.eigenvectors().transpose();
            Eigen::MatrixXd covZ = sigma2 * (sdiag.asDiagonal() * Ainv * sdiag.asDiagonal());
            Eigen::VectorXd D(P);
            for (Eigen::Index k = 0; k < P; ++k) D(k) = map.dvdz(static_cast<size_t>(k), bestZ[static_cast<size_t>(k)]);
            const Eigen::MatrixXd cov = D.asDiagonal() * covZ * D.asDiagonal();
            for (Eigen::Index a = 0; a < P; ++a) {
                res.stderrs[map.freeIdx[static_cast<size_t>(a)]] = std::sqrt(std::max(0.0, cov(a, a)));
                for (Eigen::Index b = 0; b < P; ++b)
                    res.correlation[static_cast<size_t>(a * P + b)] = cov(a, b) / std::sqrt(cov(a, a) * cov(b, b));
            }
            std::string atBound;
            for (size_t k = 0; k < p; ++k) {
                const double span = map.upperZ(k) - map.lowerZ(k);
                if (bestZ[k] - map.lowerZ(k) < 1e-6 * span || map.upperZ(k) - bestZ[k] < 1e-6 * span)
                    atBound += (atBound.empty() ? "" : ", ") + res.freeNames[k];
            }
            res.identifiabilityMessage = "identifiable: cond = " + fmt(res.conditionNumber);
            if (!atBound.empty()) res.identifiabilityMessage += "; at a bound (standard error is one-sided): " + atBound;
        }
    }
    if (!res.identifiable)
        for (size_t k = 0; k < p; ++k) res.stderrs[map.freeIdx[k]] = std::numeric_limits<double>::quiet_NaN();
}

}  // namespace

bool fillUncertainty(const FitProblem& prob, const Mapping& map, PointEvaluator& evaluator, const std::vector<double>& bestZ,
                     double bestCost, FitResult& res) {
    const size_t p = map.freeIdx.size();
    const size_t m = prob.residualCount;
    // Plain residuals and Jacobian (no loss) at the optimum, in internal coordinates.
    const PointEvaluator::Ptr base = evaluator.evaluate({bestZ}).front();
    if (!base->ok) {
        res.status = FitStatus::Failed;
        res.message = "model cannot be evaluated at the optimum";
        return false;
    }
    const std::vector<double>& r0 = base->r;
    Eigen::MatrixXd J;
    if (!jacobianAtOptimum(prob, map, evaluator, bestZ, *base, res, J)) return false;
    double ss = 0.0;
    for (double v : r0) ss += v * v;
    res.rms = std::sqrt(ss / static_cast<double>(m));
    res.cost = bestCost;
    // Residual degrees of freedom: the free parameters and any nuisance parameters the callback
    // profiled out (FitProblem::profiledParameters) each take one.
    const size_t used = p + prob.profiledParameters;
    const double sigma2 = ss / static_cast<double>(m > used ? m - used : 1);
    fillCovariance(prob, map, bestZ, J, sigma2, res);
    return true;
}

}  // namespace detail

double pairCorrelation(const FitResult& fit, size_t i, size_t j) {
    constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
    const size_t p = fit.freeNames.size();
    if (i >= p || j >= p) return kNaN;
    if (fit.identifiable && fit.correlation.size() == p * p) return fit.correlation[i * p + j];
    if (fit.scaledNormal.size() != p * p || !(fit.conditionLimit > 0)) return kNaN;
    if (i == j) return 1.0;
    const Eigen::Index P = static_cast<Eigen::Index>(p);
    const Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>> A(fit.scaledNormal.data(), P, P);
    std::vector<Eigen::Index> rest;
    for (Eigen::Index k = 0; k < P; ++k)
        if (k != static_cast<Eigen::Index>(i) && k != static_cast<Eigen::Index>(j)) rest.push_back(k);
    const Eigen::Index pair[2] = {static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)};
    Eigen::Matrix2d S;
    for (int a = 0; a < 2; ++a)
        for (int b = 0; b < 2; ++b) S(a, b) = A(pair[a], pair[b]);
    const Eigen::Index R = static_cast<Eigen::Index>(rest.size());
    if (R > 0) {
        Eigen::MatrixXd Aoo(R, R), Aop(R, 2);
        for (Eigen::Index a = 0; a < R; ++a) {
            for (Eigen::Index b = 0; b < R; ++b) Aoo(a, b) = A(rest[a], rest[b]);
            for (int b = 0; b < 2; ++b) Aop(a, b) = A(rest[a], pair[b]);
        }
        Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(Aoo);
        const Eigen::VectorXd ev = es.eigenvalues();
        const double cut = ev(R - 1) / fit.conditionLimit;
        Eigen::VectorXd inv = Eigen::VectorXd::Zero(R);
        for (Eigen::Index k = 0; k < R; ++k)
            if (ev(k) > cut) inv(k) = 1.0 / ev(k);
        const Eigen::MatrixXd W = es.eigenvectors().transpose() * Aop;
        S -= W.transpose() * inv.asDiagonal() * W;
    }
    // S is the pair's information with the others profiled; its inverse's correlation is
    // −S₁₂/√(S₁₁S₂₂). A diagonal at round-off of the unit diagonal: determined by the others alone.
    const double floor = 1.0 / fit.conditionLimit;
    if (!(S(0, 0) > floor) || !(S(1, 1) > floor)) return kNaN;
    return std::clamp(-S(0, 1) / std::sqrt(S(0, 0) * S(1, 1)), -1.0, 1.0);
}

}  // namespace stickslip::identify
