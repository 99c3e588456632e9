// The generic least-squares engine on Ceres (all Ceres code of the project lives here).
//
// Internal coordinates z (what Ceres sees), one per FREE parameter:
//   Linear: z = (v − lower)/(upper − lower)  ∈ [0, 1]        dv/dz = upper − lower
//   Log:    z = ln v                          ∈ [ln lo, ln up] dv/dz = v
// so every free coordinate is O(1) and the central-difference step (relativeStep·|z|) is
// meaningful for parameters spanning decades (ε_T ~ 1e6, D_c ~ 1e-5).
//
// Uncertainty at the optimum (plain residuals r, m residuals, p free parameters):
//   σ̂² = Σ r² / (m − p − q),  q = nuisance parameters profiled out inside the callback,   Cov_z = σ̂² (J_zᵀ J_z)⁻¹,   Cov_v = D Cov_z D,  D = diag(dv/dz).
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

// Residual vectors at internal points z, with a small memory of the most recent points.
// Ceres asks for the same point several times: with bounds, every trust-region step runs an
// Armijo line search whose (cubic) interpolation evaluates the Jacobian at the trial point;
// the accepted candidate is then evaluated again, and a successful step evaluates the
// Jacobian there once more. The callback is deterministic, so a repeated point is served from
// memory: the same numbers, the solver's path unchanged, about half the evaluations.
class PointEvaluator {
public:
    struct Result {
        bool ok = false;
        std::vector<double> r;
    };
    using Ptr = std::shared_ptr<const Result>;

    PointEvaluator(const Mapping& map, long& evaluations, size_t capacity)
        : map_(map), evaluations_(evaluations), capacity_(std::max<size_t>(capacity, 1)) {}

    // Residuals at every point of zs (internal coordinates), computed together (in one batch
    // call when the problem has one) where not remembered.
    std::vector<Ptr> evaluate(const std::vector<std::vector<double>>& zs) {
        std::vector<Ptr> out(zs.size());
        std::vector<size_t> todo;
        for (size_t i = 0; i < zs.size(); ++i) {
            out[i] = find(zs[i]);
            if (!out[i]) {
                bool dup = false;  // the same point twice in one request: compute once
                for (size_t j : todo) dup = dup || zs[j] == zs[i];
                if (!dup) todo.push_back(i);
            }
        }
        const FitProblem& prob = *map_.prob;
        if (!todo.empty() && prob.cancel && prob.cancel->load(std::memory_order_relaxed)) {
            // Cancelled: no new batch (a dynamics batch takes seconds). The points fail and
            // are not remembered; the iteration callback then aborts the solve.
            for (Ptr& o : out)
                if (!o) o = std::make_shared<Result>();
            return out;
        }
        if (!todo.empty()) {
            const size_t m = prob.residualCount;
            std::vector<std::vector<double>> values(todo.size()), rs(todo.size(), std::vector<double>(m, 0.0));
            std::vector<char> ok(todo.size(), 0);
            for (size_t k = 0; k < todo.size(); ++k) values[k] = map_.allValues(zs[todo[k]].data());
            if (prob.batchResiduals) {
                prob.batchResiduals(values, rs, ok);
            } else {
                for (size_t k = 0; k < todo.size(); ++k) ok[k] = prob.residuals(values[k], rs[k]) ? 1 : 0;
            }
            evaluations_ += static_cast<long>(todo.size());
            for (size_t k = 0; k < todo.size(); ++k) {
                auto res = std::make_shared<Result>();
                res->ok = ok.size() == todo.size() && ok[k] != 0 && rs[k].size() == m &&
                          std::all_of(rs[k].begin(), rs[k].end(), [](double v) { return std::isfinite(v); });
                if (res->ok) res->r = std::move(rs[k]);
                remember(zs[todo[k]], res);
                out[todo[k]] = res;
            }
            // Duplicates within the request (not computed twice). Not through the memory: a
            // request larger than its capacity (a parameter scan) evicts its own first points.
            for (size_t i = 0; i < zs.size(); ++i)
                if (!out[i])
                    for (size_t k : todo)
                        if (zs[k] == zs[i]) out[i] = out[k];
        }
        return out;
    }

private:
    Ptr find(const std::vector<double>& z) {
        for (Entry& e : memory_)
            if (e.z == z) {
                e.used = ++clock_;
                return e.result;
            }
        return nullptr;
    }
    void remember(const std::vector<double>& z, Ptr r) {
        if (memory_.size() < capacity_) {
            memory_.push_back(Entry{z, std::move(r), ++clock_});
            return;
        }
        auto oldest = std::min_element(memory_.begin(), memory_.end(), [](const Entry& a, const Entry& b) { return a.used < b.used; });
        *oldest = Entry{z, std::move(r), ++clock_};
    }
    struct Entry {
        std::vector<double> z;
        Ptr result;
        uint64_t used = 0;
    };
    const Mapping& map_;
    long& evaluations_;
    size_t capacity_;
    std::vector<Entry> memory_;
    uint64_t clock_ = 0;
};

// The residual block seen by Ceres, with the Jacobian by finite differences: central exactly as
// ceres::NumericDiff computes it (step δ_j = max(sqrt(ε), relativeStep·|z_j|), column
// (r(z + δ_j e_j) − r(z − δ_j e_j))·((1/δ_j)/2)), or forward ((r(z + δ_j e_j) − r(z))/δ_j, the
// same step), with the displaced points requested together so that they can be computed in
// parallel. Forward needs p new points per Jacobian instead of 2p: the solver's iterations cost
// about half; its O(δ) error moves only the path (the cost still decreases at every accepted
// step), not the standard errors, which are differenced centrally at the optimum.
class DifferenceCost : public ceres::CostFunction {
public:
    DifferenceCost(PointEvaluator& ev, size_t p, size_t m, double relativeStep, JacobianKind kind)
        : ev_(ev), p_(p), m_(m), relStep_(relativeStep), kind_(kind) {
        set_num_residuals(static_cast<int>(m));
        mutable_parameter_block_sizes()->push_back(static_cast<int32_t>(p));
    }
    bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override {
        const std::vector<double> z(parameters[0], parameters[0] + p_);
        const PointEvaluator::Ptr base = ev_.evaluate({z}).front();
        if (!base->ok) return false;
        std::copy(base->r.begin(), base->r.end(), residuals);
        if (jacobians == nullptr || jacobians[0] == nullptr) return true;
        const double minStep = std::sqrt(std::numeric_limits<double>::epsilon());
        const bool central = kind_ == JacobianKind::Central;
        std::vector<double> delta(p_);
        std::vector<std::vector<double>> pts;
        pts.reserve(central ? 2 * p_ : p_);
        for (size_t j = 0; j < p_; ++j) {
            delta[j] = std::max(minStep, std::abs(z[j]) * relStep_);
            std::vector<double> zp = z;
            zp[j] = z[j] + delta[j];
            pts.push_back(std::move(zp));
            if (central) {
                std::vector<double> zm = z;
                zm[j] = z[j] - delta[j];
                pts.push_back(std::move(zm));
            }
        }
        const std::vector<PointEvaluator::Ptr> rs = ev_.evaluate(pts);
        // A forward point where the model cannot be evaluated (the edge of a feasible region
        // that is not a box in the solver's coordinates, e.g. curve_coordinates.hpp): the
        // backward point instead, all such points requested together.
        std::vector<size_t> back;
        std::vector<std::vector<double>> backPts;
        if (!central)
            for (size_t j = 0; j < p_; ++j)
                if (!rs[j]->ok) {
                    std::vector<double> zm = z;
                    zm[j] = z[j] - delta[j];
                    back.push_back(j);
                    backPts.push_back(std::move(zm));
                }
        const std::vector<PointEvaluator::Ptr> rb = backPts.empty() ? std::vector<PointEvaluator::Ptr>{} : ev_.evaluate(backPts);
        double* J = jacobians[0];  // row-major m × p
        for (size_t j = 0; j < p_; ++j) {
            const PointEvaluator::Result* rp = rs[central ? 2 * j : j].get();
            const PointEvaluator::Result* rm = central ? rs[2 * j + 1].get() : base.get();
            double scale = central ? (1.0 / delta[j]) / 2 : 1.0 / delta[j];
            if (central && rp->ok != rm->ok) {  // one side infeasible: one-sided from the point itself
                (rp->ok ? rm : rp) = base.get();
                scale = 1.0 / delta[j];
            } else if (!central && !rp->ok) {
                const size_t b = static_cast<size_t>(std::find(back.begin(), back.end(), j) - back.begin());
                rp = base.get();
                rm = rb[b].get();
            }
            if (!rp->ok || !rm->ok) return false;
            for (size_t i = 0; i < m_; ++i) J[i * p_ + j] = (rp->r[i] - rm->r[i]) * scale;
        }
        return true;
    }

private:
    PointEvaluator& ev_;
    size_t p_, m_;
    double relStep_;
    JacobianKind kind_;
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

// Standard errors, correlations and identifiability at the optimum bestZ (FitProblem::
// uncertainty): the plain residuals and a central-difference Jacobian there. False (status and
// message set) when the model cannot be evaluated at the optimum or next to it.
bool fillUncertainty(const FitProblem& prob, const Mapping& map, PointEvaluator& evaluator, const std::vector<double>& bestZ,
                     double bestCost, FitResult& res) {
    const size_t p = map.freeIdx.size();
    const size_t m = prob.residualCount;
    // Plain residuals and Jacobian (no loss) at the optimum, in internal coordinates: the
    // 2p displaced points are computed together (in parallel when the problem can).
    const PointEvaluator::Ptr base = evaluator.evaluate({bestZ}).front();
    if (!base->ok) {
        res.status = FitStatus::Failed;
        res.message = "model cannot be evaluated at the optimum";
        return false;
    }
    const std::vector<double>& r0 = base->r;
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
    Eigen::MatrixXd J(m, p);
    for (size_t k = 0; k < p; ++k) {
        // A side where the model cannot be evaluated (the edge of a feasible region that is not
        // a box in these coordinates, e.g. curve_coordinates.hpp) is replaced by the optimum:
        // a one-sided difference there.
        const PointEvaluator::Result& rp = rd[2 * k]->ok ? *rd[2 * k] : *base;
        const PointEvaluator::Result& rm = rd[2 * k + 1]->ok ? *rd[2 * k + 1] : *base;
        const double span = (rd[2 * k]->ok ? hPlus[k] : 0.0) + (rd[2 * k + 1]->ok ? hMinus[k] : 0.0);
        if (!(span > 0.0)) {
            res.status = FitStatus::Failed;
            res.message = "model cannot be evaluated next to the optimum (parameter " + res.freeNames[k] + ")";
            return false;
        }
        for (size_t i = 0; i < m; ++i)
            J(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(k)) = (rp.r[i] - rm.r[i]) / span;
    }
    double ss = 0.0;
    for (double v : r0) ss += v * v;
    res.rms = std::sqrt(ss / static_cast<double>(m));
    res.cost = bestCost;
    // Residual degrees of freedom: the free parameters and any nuisance parameters the callback
    // profiled out (FitProblem::profiledParameters) each take one.
    const size_t used = p + prob.profiledParameters;
    const double sigma2 = ss / static_cast<double>(m > used ? m - used : 1);

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
    return true;
}

}  // namespace

ParamIssues FitProblem::validate() const {
    ParamIssues issues;
    auto note = [&](std::string text) { issues.push_back(ParamIssue::note("fit", std::move(text))); };
    if (!residuals && !batchResiduals) note("residual callback is missing");
    if (residualCount == 0) note("residualCount = 0 is out of range: must be > 0");
    size_t nFree = 0;
    for (const FitParameter& p : parameters) {
        if (!std::isfinite(p.lower) || !std::isfinite(p.upper) || !(p.upper > p.lower))
            note(p.name + ": bounds [" + fmt(p.lower) + ", " + fmt(p.upper) + "] must be finite with lower < upper");
        if (p.scale == ParamScale::Log && !(p.lower > 0.0))
            note(p.name + ": lower = " + fmt(p.lower) + " is out of range: log scale needs lower > 0");
        if (!(p.value >= p.lower && p.value <= p.upper))
            note(p.name + " = " + fmt(p.value) + " is out of range: must be in [" + fmt(p.lower) + ", " +
                             fmt(p.upper) + "]");
        if (p.free) ++nFree;
    }
    if (nFree == 0) note("no free parameter");
    for (const ParameterScan& sc : scans) {
        bool isFree = false;
        for (const FitParameter& p : parameters) isFree = isFree || (p.free && p.name == sc.name);
        if (!isFree) note("scan of '" + sc.name + "': not a free parameter");
        for (double v : sc.values)
            if (!std::isfinite(v)) note("scan of '" + sc.name + "': value " + fmt(v) + " is not finite");
    }
    if (residualCount > 0 && nFree >= residualCount)
        note("residualCount = " + std::to_string(residualCount) + " must exceed the free parameters (" +
                         std::to_string(nFree) + ")");
    if (agreeingStarts < 0) note("agreeingStarts = " + std::to_string(agreeingStarts) + " is out of range: must be >= 0");
    if (!(sameCostTolerance >= 0.0)) note("sameCostTolerance = " + fmt(sameCostTolerance) + " is out of range: must be >= 0");
    if (multistarts < 1) note("multistarts = " + std::to_string(multistarts) + " is out of range: must be >= 1");
    if (maxIterations < 1) note("maxIterations must be >= 1");
    if (!(relativeStep > 0.0 && relativeStep < 0.1)) note("relativeStep = " + fmt(relativeStep) + " must be in (0, 0.1)");
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
    const ParamIssues issues = prob.validate();
    if (!issues.empty()) {
        for (size_t i = 0; i < issues.size(); ++i) res.message += (i ? "; " : "") + issues[i].message();
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

    // Remembers the last few points (a Jacobian's 2p + 1 and a line search's trial points).
    PointEvaluator evaluator(map, res.residualEvaluations, 4 * p + 4);
    for (int s = 0; s < prob.multistarts && !cancelled; ++s) {
        std::vector<double> z(p);
        // A random start where the model cannot be evaluated (e.g. a change of coordinates
        // whose box holds infeasible corners) is drawn again, up to kRandomStartDraws times.
        constexpr int kRandomStartDraws = 20;
        for (int draw = 0; draw < (s == 0 ? 1 : kRandomStartDraws); ++draw) {
            for (size_t k = 0; k < p; ++k) {
                if (s == 0) z[k] = map.toInternal(k, prob.parameters[map.freeIdx[k]].value);
                else z[k] = map.lowerZ(k) + uni(rng) * (map.upperZ(k) - map.lowerZ(k));
                z[k] = std::clamp(z[k], map.lowerZ(k), map.upperZ(k));
            }
            if (s == 0 || evaluator.evaluate({z}).front()->ok) break;
            if (draw + 1 == kRandomStartDraws)
                perStart << "start " << s << ": no evaluable random point in " << kRandomStartDraws << " draws\n";
        }
        if (s == 0) {
            for (const ParameterScan& sc : prob.scans) {
                size_t k = p;
                for (size_t q = 0; q < p; ++q)
                    if (prob.parameters[map.freeIdx[q]].name == sc.name) k = q;
                if (k == p || sc.values.empty()) continue;
                std::vector<std::vector<double>> zs;
                zs.push_back(z);
                for (double v : sc.values) {
                    std::vector<double> zq = z;
                    zq[k] = std::clamp(map.toInternal(k, v), map.lowerZ(k), map.upperZ(k));
                    zs.push_back(std::move(zq));
                }
                const std::vector<PointEvaluator::Ptr> rs = evaluator.evaluate(zs);
                size_t best = 0;
                double bestScan = std::numeric_limits<double>::infinity();
                for (size_t i = 0; i < rs.size(); ++i) {
                    if (!rs[i]->ok) continue;
                    double c = 0;
                    for (double r : rs[i]->r) c += r * r;
                    if (c < bestScan) { bestScan = c; best = i; }
                }
                perStart << "scan " << sc.name << " over " << sc.values.size() << " values: start at "
                         << map.toPhysical(k, zs[best][k]) << " (cost " << 0.5 * bestScan << ")\n";
                z = zs[best];
            }
        }
        ceres::Problem::Options po;
        ceres::Problem problem(po);
        auto* cost = new DifferenceCost(evaluator, p, m, prob.relativeStep, prob.jacobian);
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
        // Early stop: enough starts ended at the best cost found so far (none lower).
        if (prob.agreeingStarts >= 2 && s + 1 < prob.multistarts) {
            int same = 0;
            for (double c : res.startCosts)
                if (std::isfinite(c) && std::abs(c - bestCost) <= prob.sameCostTolerance * std::max(std::abs(bestCost), 1e-300)) ++same;
            if (same >= prob.agreeingStarts) {
                res.stoppedEarly = true;
                perStart << "stopped after " << (s + 1) << " of " << prob.multistarts << " starts: " << same
                         << " ended at the same cost (within " << fmt(prob.sameCostTolerance) << " relative)\n";
                break;
            }
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
    if (prob.uncertainty) {
        if (!fillUncertainty(prob, map, evaluator, bestZ, bestCost, res)) return res;
    } else {
        res.cost = bestCost;
        res.rms = prob.loss == LossKind::None ? std::sqrt(2.0 * bestCost / static_cast<double>(m))
                                              : std::numeric_limits<double>::quiet_NaN();
        for (size_t k = 0; k < p; ++k) res.stderrs[map.freeIdx[k]] = std::numeric_limits<double>::quiet_NaN();
        res.identifiabilityMessage = "not computed (FitProblem::uncertainty is false)";
    }
    res.status = cancelled ? FitStatus::Cancelled : FitStatus::Ok;
    if (cancelled) res.message = "cancelled (best result so far)";
    res.wallTime_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return res;
}

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

std::vector<double> logGrid(double lower, double upper, int points) {
    std::vector<double> g;
    if (!(lower > 0) || !(upper > lower) || points < 2) return g;
    for (int i = 0; i < points; ++i)
        g.push_back(std::exp(std::log(lower) + (std::log(upper) - std::log(lower)) * i / (points - 1)));
    return g;
}

bool defaultParameter(const std::string& name, SetupKind setup, FitParameter& out) {
    // The parameter table's fit range (the prescribed one where the row has it) and default.
    const ParamDef* d = findParam(name);
    if (!d || !d->fit.valid()) return false;
    const FitRange& r = setup == SetupKind::Prescribed && d->fitPrescribed.valid() ? d->fitPrescribed : d->fit;
    out = FitParameter{d->key, paramDefault(name), r.lower, r.upper, true, r.log ? ParamScale::Log : ParamScale::Linear};
    return true;
}

}  // namespace stickslip::identify
