// The generic least-squares engine on Ceres (all Ceres code of the project lives here).
//
// Internal coordinates z (what Ceres sees), one per FREE parameter:
//   Linear: z = (v − lower)/(upper − lower)  ∈ [0, 1]        dv/dz = upper − lower
//   Log:    z = ln v                          ∈ [ln lo, ln up] dv/dz = v
// so every free coordinate is O(1) and the central-difference step (relativeStep·|z|) is
// meaningful for parameters spanning decades (ε_T ~ 1e6, D_c ~ 1e-5).
//
// Uncertainty at the optimum (plain residuals r, m residuals, p free parameters):
//   σ̂² = Σ r² / (m − p),   Cov_z = σ̂² (J_zᵀ J_z)⁻¹,   Cov_v = D Cov_z D,  D = diag(dv/dz).
// Identifiability: with S = diag(JᵀJ)^(−1/2), the scaled matrix A = S JᵀJ S has unit diagonal
// and cond(A) measures how nearly dependent the parameters are, independently of their units.
// cond(A) > conditionLimit (or a zero column: a parameter without effect) → "not identifiable",
// standard errors NaN, and the eigenvector of the smallest eigenvalue names the culprits.
#include "fit.hpp"

#include <ceres/ceres.h>

#include <Eigen/Dense>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <random>
#include <sstream>

namespace stickslip::identify {

namespace {

struct Mapping {
    std::vector<size_t> freeIdx;  // problem index of each free coordinate
    const FitProblem* prob = nullptr;

    double toPhysical(size_t k, double z) const {
        const FitParameter& p = prob->parameters[freeIdx[k]];
        if (p.scale == ParamScale::Log) return std::exp(z);
        return p.lower + z * (p.upper - p.lower);
    }
    double toInternal(size_t k, double v) const {
        const FitParameter& p = prob->parameters[freeIdx[k]];
        if (p.scale == ParamScale::Log) return std::log(v);
        return (v - p.lower) / (p.upper - p.lower);
    }
    double lowerZ(size_t k) const {
        const FitParameter& p = prob->parameters[freeIdx[k]];
        return p.scale == ParamScale::Log ? std::log(p.lower) : 0.0;
    }
    double upperZ(size_t k) const {
        const FitParameter& p = prob->parameters[freeIdx[k]];
        return p.scale == ParamScale::Log ? std::log(p.upper) : 1.0;
    }
    double dvdz(size_t k, double z) const {
        const FitParameter& p = prob->parameters[freeIdx[k]];
        return p.scale == ParamScale::Log ? std::exp(z) : (p.upper - p.lower);
    }
    std::vector<double> allValues(const double* z) const {
        std::vector<double> v(prob->parameters.size());
        for (size_t i = 0; i < v.size(); ++i) v[i] = prob->parameters[i].value;
        for (size_t k = 0; k < freeIdx.size(); ++k) v[freeIdx[k]] = toPhysical(k, z[k]);
        return v;
    }
};

struct ResidualFunctor {
    const Mapping* map;
    long* evaluations;
    bool operator()(double const* const* z, double* out) const {
        std::vector<double> values = map->allValues(z[0]);
        std::vector<double> r(map->prob->residualCount, 0.0);
        ++*evaluations;
        if (!map->prob->residuals(values, r)) return false;
        if (r.size() != map->prob->residualCount) return false;
        for (size_t i = 0; i < r.size(); ++i) {
            if (!std::isfinite(r[i])) return false;
            out[i] = r[i];
        }
        return true;
    }
};

class ControlCallback : public ceres::IterationCallback {
public:
    ControlCallback(const FitProblem& p, int start, int starts) : p_(p), start_(start), starts_(starts) {}
    ceres::CallbackReturnType operator()(const ceres::IterationSummary& s) override {
        if (p_.cancel && p_.cancel->load(std::memory_order_relaxed)) return ceres::SOLVER_ABORT;
        if (p_.progress) {
            const double within = std::min(1.0, static_cast<double>(s.iteration + 1) / std::max(1, p_.maxIterations));
            p_.progress((start_ + within) / starts_);
        }
        return ceres::SOLVER_CONTINUE;
    }

private:
    const FitProblem& p_;
    int start_, starts_;
};

std::string fmt(double v) {
    std::ostringstream o;
    o.precision(4);
    o << v;
    return o.str();
}

}  // namespace

std::vector<std::string> FitProblem::validate() const {
    std::vector<std::string> issues;
    if (!residuals) issues.push_back("residual callback is missing");
    if (residualCount == 0) issues.push_back("residualCount = 0 is out of range: must be > 0");
    size_t nFree = 0;
    for (const FitParameter& p : parameters) {
        if (!std::isfinite(p.lower) || !std::isfinite(p.upper) || !(p.upper > p.lower))
            issues.push_back(p.name + ": bounds [" + fmt(p.lower) + ", " + fmt(p.upper) + "] must be finite with lower < upper");
        if (p.scale == ParamScale::Log && !(p.lower > 0.0))
            issues.push_back(p.name + ": lower = " + fmt(p.lower) + " is out of range: log scale needs lower > 0");
        if (!(p.value >= p.lower && p.value <= p.upper))
            issues.push_back(p.name + " = " + fmt(p.value) + " is out of range: must be in [" + fmt(p.lower) + ", " +
                             fmt(p.upper) + "]");
        if (p.free) ++nFree;
    }
    if (nFree == 0) issues.push_back("no free parameter");
    if (residualCount > 0 && nFree >= residualCount)
        issues.push_back("residualCount = " + std::to_string(residualCount) + " must exceed the free parameters (" +
                         std::to_string(nFree) + ")");
    if (multistarts < 1) issues.push_back("multistarts = " + std::to_string(multistarts) + " is out of range: must be >= 1");
    if (maxIterations < 1) issues.push_back("maxIterations must be >= 1");
    if (!(relativeStep > 0.0 && relativeStep < 0.1)) issues.push_back("relativeStep = " + fmt(relativeStep) + " must be in (0, 0.1)");
    return issues;
}

double FitResult::value(const std::string& name) const {
    for (size_t i = 0; i < names.size(); ++i)
        if (names[i] == name) return values[i];
    return std::numeric_limits<double>::quiet_NaN();
}

double FitResult::stderrOf(const std::string& name) const {
    for (size_t i = 0; i < names.size(); ++i)
        if (names[i] == name) return stderrs[i];
    return std::numeric_limits<double>::quiet_NaN();
}

FitResult fitLeastSquares(const FitProblem& prob) {
    const auto t0 = std::chrono::steady_clock::now();
    FitResult res;
    for (const FitParameter& p : prob.parameters) {
        res.names.push_back(p.name);
        res.values.push_back(p.value);
        res.free.push_back(p.free);
        res.stderrs.push_back(0.0);
    }
    res.residualCount = prob.residualCount;
    const std::vector<std::string> issues = prob.validate();
    if (!issues.empty()) {
        for (size_t i = 0; i < issues.size(); ++i) res.message += (i ? "; " : "") + issues[i];
        return res;
    }

    Mapping map;
    map.prob = &prob;
    for (size_t i = 0; i < prob.parameters.size(); ++i)
        if (prob.parameters[i].free) {
            map.freeIdx.push_back(i);
            res.freeNames.push_back(prob.parameters[i].name);
        }
    const size_t p = map.freeIdx.size();
    const size_t m = prob.residualCount;

    std::mt19937_64 rng(prob.seed);
    std::uniform_real_distribution<double> uni(0.1, 0.9);  // random starts stay off the bounds

    double bestCost = std::numeric_limits<double>::infinity();
    std::vector<double> bestZ;
    ceres::Solver::Summary bestSummary;
    std::ostringstream perStart;
    bool cancelled = false;
    std::string lastFailure;

    for (int s = 0; s < prob.multistarts && !cancelled; ++s) {
        std::vector<double> z(p);
        for (size_t k = 0; k < p; ++k) {
            if (s == 0) z[k] = map.toInternal(k, prob.parameters[map.freeIdx[k]].value);
            else z[k] = map.lowerZ(k) + uni(rng) * (map.upperZ(k) - map.lowerZ(k));
            z[k] = std::clamp(z[k], map.lowerZ(k), map.upperZ(k));
        }
        ceres::Problem::Options po;
        ceres::Problem problem(po);
        ceres::NumericDiffOptions nd;
        nd.relative_step_size = prob.relativeStep;
        auto* cost = new ceres::DynamicNumericDiffCostFunction<ResidualFunctor, ceres::CENTRAL>(
            new ResidualFunctor{&map, &res.residualEvaluations}, ceres::TAKE_OWNERSHIP, nd);
        cost->AddParameterBlock(static_cast<int>(p));
        cost->SetNumResiduals(static_cast<int>(m));
        ceres::LossFunction* loss = nullptr;
        if (prob.loss == LossKind::Huber) loss = new ceres::HuberLoss(prob.lossScale);
        else if (prob.loss == LossKind::Cauchy) loss = new ceres::CauchyLoss(prob.lossScale);
        problem.AddResidualBlock(cost, loss, z.data());
        for (size_t k = 0; k < p; ++k) {
            problem.SetParameterLowerBound(z.data(), static_cast<int>(k), map.lowerZ(k));
            problem.SetParameterUpperBound(z.data(), static_cast<int>(k), map.upperZ(k));
        }
        ceres::Solver::Options so;
        so.linear_solver_type = ceres::DENSE_QR;
        so.max_num_iterations = prob.maxIterations;
        so.function_tolerance = prob.functionTolerance;
        so.parameter_tolerance = prob.parameterTolerance;
        so.gradient_tolerance = 1e-12;
        so.num_threads = 1;
        so.logging_type = ceres::SILENT;
        so.minimizer_progress_to_stdout = false;
        ControlCallback cb(prob, s, prob.multistarts);
        so.callbacks.push_back(&cb);
        ceres::Solver::Summary summary;
        ceres::Solve(so, &problem, &summary);
        ++res.startsTried;
        if (prob.cancel && prob.cancel->load(std::memory_order_relaxed)) cancelled = true;
        const bool usable = summary.IsSolutionUsable() && std::isfinite(summary.final_cost);
        res.startCosts.push_back(usable ? summary.final_cost : std::numeric_limits<double>::quiet_NaN());
        perStart << "start " << s << ": " << (usable ? "cost " + fmt(summary.final_cost) : "failed: " + summary.message)
                 << ", " << summary.iterations.size() << " iterations, " << ceres::TerminationTypeToString(summary.termination_type)
                 << "\n";
        if (!usable) { lastFailure = summary.message; continue; }
        if (summary.final_cost < bestCost) {
            bestCost = summary.final_cost;
            bestZ = z;
            bestSummary = summary;
            res.bestStart = s;
        }
    }
    res.wallTime_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (bestZ.empty()) {
        res.status = cancelled ? FitStatus::Cancelled : FitStatus::Failed;
        res.message = cancelled ? "cancelled" : "no start gave a usable solution: " + lastFailure;
        res.solverSummary = perStart.str();
        return res;
    }
    res.values = map.allValues(bestZ.data());
    res.converged = bestSummary.termination_type == ceres::CONVERGENCE;
    res.solverSummary = bestSummary.BriefReport() + "\n" + perStart.str();

    // Plain residuals and Jacobian (no loss) at the optimum, in internal coordinates.
    ceres::NumericDiffOptions nd;
    nd.relative_step_size = prob.relativeStep;
    ResidualFunctor f{&map, &res.residualEvaluations};
    std::vector<double> r0(m);
    const double* zp = bestZ.data();
    if (!f(&zp, r0.data())) {
        res.status = FitStatus::Failed;
        res.message = "model cannot be evaluated at the optimum";
        return res;
    }
    Eigen::MatrixXd J(m, p);
    for (size_t k = 0; k < p; ++k) {
        std::vector<double> zplus = bestZ, zminus = bestZ;
        double h = prob.relativeStep * std::max(std::abs(bestZ[k]), 1e-2);
        // stay inside the box: one-sided when against a bound
        double hp = std::min(h, map.upperZ(k) - bestZ[k]), hm = std::min(h, bestZ[k] - map.lowerZ(k));
        if (hp <= 0 && hm <= 0) { hp = h; hm = 0; }
        zplus[k] += hp;
        zminus[k] -= hm;
        std::vector<double> rp(m), rm(m);
        const double* zpp = zplus.data();
        const double* zmp = zminus.data();
        const bool okp = hp > 0 ? f(&zpp, rp.data()) : (rp = r0, true);
        const bool okm = hm > 0 ? f(&zmp, rm.data()) : (rm = r0, true);
        if (!okp || !okm) {
            res.status = FitStatus::Failed;
            res.message = "model cannot be evaluated next to the optimum (parameter " + res.freeNames[k] + ")";
            return res;
        }
        for (size_t i = 0; i < m; ++i) J(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(k)) = (rp[i] - rm[i]) / (hp + hm);
    }
    double ss = 0.0;
    for (double v : r0) ss += v * v;
    res.rms = std::sqrt(ss / static_cast<double>(m));
    res.cost = bestCost;
    const double sigma2 = ss / static_cast<double>(m > p ? m - p : 1);

    const Eigen::MatrixXd JtJ = J.transpose() * J;
    Eigen::VectorXd d = JtJ.diagonal();
    std::vector<std::string> dead;
    for (size_t k = 0; k < p; ++k)
        if (!(d(static_cast<Eigen::Index>(k)) > 0.0)) dead.push_back(res.freeNames[k]);
    const Eigen::Index P = static_cast<Eigen::Index>(p);
    res.correlation.assign(p * p, std::numeric_limits<double>::quiet_NaN());
    if (!dead.empty()) {
        res.identifiable = false;
        res.conditionNumber = std::numeric_limits<double>::infinity();
        res.identifiabilityMessage = "not identifiable: the residuals do not depend on";
        for (const auto& n : dead) res.identifiabilityMessage += " " + n;
    } else {
        const Eigen::VectorXd sdiag = d.cwiseSqrt().cwiseInverse();
        const Eigen::MatrixXd A = sdiag.asDiagonal() * JtJ * sdiag.asDiagonal();
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
    res.status = cancelled ? FitStatus::Cancelled : FitStatus::Ok;
    if (cancelled) res.message = "cancelled (best result so far)";
    res.wallTime_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return res;
}

bool defaultParameter(const std::string& name, SetupKind setup, FitParameter& out) {
    const bool pres = setup == SetupKind::Prescribed;
    // In the prescribed set-up t_N is a reference load (e.g. a band tension), so the
    // coefficients μ, C1 and η are "per unit reference load" and may be far above 1.
    struct Row { const char* n; double v, lo, hi; ParamScale s; };
    const Row rows[] = {
        {"mu", 0.25, pres ? 1e-3 : 0.01, pres ? 1e3 : 2.0, pres ? ParamScale::Log : ParamScale::Linear},
        {"C1", 0.25, pres ? 1e-4 : 0.0, pres ? 1e3 : 2.0, pres ? ParamScale::Log : ParamScale::Linear},
        {"eta", 0.6, 1e-4, pres ? 1e4 : 50.0, ParamScale::Log},
        {"Dc", 20e-6, 1e-8, 1e-2, ParamScale::Log},
        {"vc", 0.1, 1e-4, 10.0, ParamScale::Log},
        {"epsT", 1e6, 1e2, 1e10, ParamScale::Log},
        {"r", 1.0, 0.05, 20.0, ParamScale::Log},
        {"k", 8446.0, 1.0, 1e7, ParamScale::Log},
        {"m", 0.53, 1e-3, 100.0, ParamScale::Log},
        {"c", 0.669, 1e-6, 1e4, ParamScale::Log},
        {"tN", 6.2, 1e-3, 1e5, ParamScale::Log},
    };
    for (const Row& r : rows)
        if (name == r.n) {
            out = FitParameter{r.n, r.v, r.lo, r.hi, true, r.s};
            return true;
        }
    return false;
}

}  // namespace stickslip::identify
