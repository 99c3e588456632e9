// The generic least-squares engine on Ceres (all Ceres code of the project lives here): the
// solver's residual block with its finite-difference Jacobian, the starts (given, scanned,
// random) and the solve. The solver's coordinates and the residual memory are in
// fit_internal.hpp; the standard errors at the optimum in fit_uncertainty.cpp.
#include "fit.hpp"

#include <ceres/ceres.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <random>
#include <sstream>

#include "fit_internal.hpp"

namespace stickslip::identify {

namespace detail {

bool analyticJacobianAt(const Mapping& map, const std::vector<double>& z, std::vector<double>& J) {
    const FitProblem& prob = *map.prob;
    if (!prob.analyticJacobian) return false;
    const size_t P = prob.parameters.size(), p = map.freeIdx.size(), m = prob.residualCount;
    std::vector<double> full(m * P, 0.0);
    if (!prob.analyticJacobian(map.allValues(z.data()), full) || full.size() != m * P) return false;
    J.assign(m * p, 0.0);
    for (size_t k = 0; k < p; ++k) {
        const double f = map.dvdz(k, z[k]);
        const size_t c = map.freeIdx[k];
        for (size_t i = 0; i < m; ++i) J[i * p + k] = full[i * P + c] * f;
    }
    return true;
}

std::string fmt(double v, const char* f) {
    char b[64];
    std::snprintf(b, sizeof b, f, v);
    return b;
}

}  // namespace detail

namespace {

using detail::fmt;
using detail::Mapping;
using detail::PointEvaluator;

// The residual block seen by Ceres, with the Jacobian by finite differences: central exactly as
// ceres::NumericDiff computes it (step δ_j = max(sqrt(ε), relativeStep·|z_j|), column
// (r(z + δ_j e_j) − r(z − δ_j e_j))·((1/δ_j)/2)), or forward ((r(z + δ_j e_j) − r(z))/δ_j, the
// same step), with the displaced points requested together so that they can be computed in
// parallel. Forward needs p new points per Jacobian instead of 2p: the solver's iterations cost
// about half; its O(δ) error moves only the path (the cost still decreases at every accepted
// step), not the standard errors, which are differenced centrally at the optimum. A problem
// with its own Jacobian (FitProblem::analyticJacobian) is not differenced at all.
class DifferenceCost : public ceres::CostFunction {
public:
    DifferenceCost(PointEvaluator& ev, const Mapping& map, size_t m, double relativeStep, JacobianKind kind)
        : ev_(ev), map_(map), p_(map.freeIdx.size()), m_(m), relStep_(relativeStep), kind_(kind) {
        set_num_residuals(static_cast<int>(m));
        mutable_parameter_block_sizes()->push_back(static_cast<int32_t>(p_));
    }
    bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override {
        const std::vector<double> z(parameters[0], parameters[0] + p_);
        const PointEvaluator::Ptr base = ev_.evaluate({z}).front();
        if (!base->ok) return false;
        std::copy(base->r.begin(), base->r.end(), residuals);
        if (jacobians == nullptr || jacobians[0] == nullptr) return true;
        if (analytic(z, jacobians[0])) return true;
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
    // The problem's own Jacobian, in the solver's coordinates (chain rule through the mapping).
    bool analytic(const std::vector<double>& z, double* J) const {
        if (!map_.prob->analyticJacobian) return false;
        std::vector<double> full;
        if (!detail::analyticJacobianAt(map_, z, full)) return false;
        std::copy(full.begin(), full.end(), J);
        return true;
    }

    PointEvaluator& ev_;
    const Mapping& map_;
    size_t p_, m_;
    double relStep_;
    JacobianKind kind_;
};

class ControlCallback : public ceres::IterationCallback {
public:
    ControlCallback(const FitProblem& p, int start, int starts) : p_(p), start_(start), starts_(starts) {}
    ceres::CallbackReturnType operator()(const ceres::IterationSummary& s) override {
        if (cancelRequested(p_.cancel)) return ceres::SOLVER_ABORT;
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

// Start s of a multistart: the given values (s = 0), or a random point of the box where the
// model can be evaluated (a change of coordinates whose box holds infeasible corners gets
// kRandomStartDraws draws). `uni` draws the random coordinates from the problem's generator.
std::vector<double> startPoint(const FitProblem& prob, const Mapping& map, PointEvaluator& evaluator, int s,
                               std::mt19937_64& rng, std::uniform_real_distribution<double>& uni, std::ostringstream& perStart) {
    const size_t p = map.freeIdx.size();
    std::vector<double> z(p);
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
    return z;
}

// The parameter scans of the first start (FitProblem::scans), each from the best point of the
// last, all of a scan's points in one batch; one line per scan in perStart.
std::vector<double> scannedPoint(const FitProblem& prob, const Mapping& map, PointEvaluator& evaluator, std::vector<double> z,
                                 std::ostringstream& perStart) {
    const size_t p = map.freeIdx.size();
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
    return z;
}

// The robust loss of FitProblem::loss on the residual block (null: plain least squares).
std::unique_ptr<ceres::LossFunction> makeLoss(const FitProblem& prob) {
    if (prob.loss == LossKind::Huber) return std::make_unique<ceres::HuberLoss>(prob.lossScale);
    if (prob.loss == LossKind::Cauchy) return std::make_unique<ceres::CauchyLoss>(prob.lossScale);
    return nullptr;
}

// Ceres' cost ½ Σ ρ(r²) at z (infinite where the model cannot be evaluated); z was evaluated
// by the solve that ended there, so the residuals come from the evaluator's memory.
double costAt(const FitProblem& prob, PointEvaluator& evaluator, const std::vector<double>& z) {
    const PointEvaluator::Ptr r = evaluator.evaluate({z}).front();
    if (!r->ok) return std::numeric_limits<double>::infinity();
    const std::unique_ptr<ceres::LossFunction> loss = makeLoss(prob);
    double sq = 0;
    for (double v : r->r) sq += v * v;
    if (!loss) return 0.5 * sq;
    double rho[3];
    loss->Evaluate(sq, rho);
    return 0.5 * rho[0];
}

// One bounded trust-region solve from z (moved to the solver's end point), start s of the
// multistart (for the progress callback); the coordinates `held` stay where they are.
ceres::Solver::Summary solveOnce(const FitProblem& prob, const Mapping& map, PointEvaluator& evaluator, std::vector<double>& z,
                                 int s, const std::vector<int>& held) {
    const size_t p = map.freeIdx.size();
    ceres::Problem::Options po;
    ceres::Problem problem(po);
    auto* cost = new DifferenceCost(evaluator, map, prob.residualCount, prob.relativeStep, prob.jacobian);
    problem.AddResidualBlock(cost, makeLoss(prob).release(), z.data());  // the problem owns the loss
    if (!held.empty()) problem.SetManifold(z.data(), new ceres::SubsetManifold(static_cast<int>(p), held));
    for (size_t k = 0; k < p; ++k) {
        problem.SetParameterLowerBound(z.data(), static_cast<int>(k), map.lowerZ(k));
        problem.SetParameterUpperBound(z.data(), static_cast<int>(k), map.upperZ(k));
    }
    ceres::Solver::Options so;
    so.linear_solver_type = ceres::DENSE_QR;
    so.max_num_iterations = prob.maxIterations;
    so.max_num_line_search_step_size_iterations = prob.maxLineSearchSteps;
    so.function_tolerance = prob.functionTolerance;
    so.parameter_tolerance = prob.parameterTolerance;
    so.gradient_tolerance = 1e-12;
    // Bounded problems get Ceres' projected Armijo line search after every trust-region step.
    // Its default cubic interpolation asks for the gradient at each trial point, and our
    // gradient is a differenced Jacobian (p or 2p more residual vectors): a whole Jacobian at
    // every trial, most of them at steps the trust region then rejects. Quadratic interpolation
    // needs only the trial's cost; the Jacobian is then differenced once per accepted point
    // (tst_fit_engine::jacobiansOnlyAtAcceptedPoints).
    so.line_search_interpolation_type = ceres::QUADRATIC;
    so.num_threads = 1;
    so.logging_type = ceres::SILENT;
    so.minimizer_progress_to_stdout = false;
    ControlCallback cb(prob, s, prob.multistarts);
    so.callbacks.push_back(&cb);
    ceres::Solver::Summary summary;
    ceres::Solve(so, &problem, &summary);
    return summary;
}

// solveOnce, and again with the coordinates that start on a bound held there when the first
// solve could not take a single step. Ceres judges a step by the decrease its linear model
// predicts for the step before the bounds clip it (its issue 187): from a start on a bound with
// the gradient pointing out of the box, the clipped step gains a small part of that prediction,
// every step is rejected, and the solve ends where it began (seen: all four leave-one-run-out
// refits of a backlash model whose C1 and eta sat on their lower bounds and v_c on its upper,
// tst_identify_contact::findsBacklash; its jackknife standard error came out 0). Holding those
// coordinates is the active set the clipped step implies; the second solve is kept only when it
// ends lower.
//
// Ceres' final_cost is the lowest cost of any iteration, and an iteration that rejects its step
// records the rejected trial's cost (seen lower than the cost at the returned point, in the case
// above). The summary returned carries the cost at its end point instead, which is what the
// multistart compares and the result reports.
ceres::Solver::Summary solveFrom(const FitProblem& prob, const Mapping& map, PointEvaluator& evaluator, std::vector<double>& z,
                                 int s) {
    const std::vector<double> z0 = z;
    ceres::Solver::Summary first = solveOnce(prob, map, evaluator, z, s, {});
    if (first.IsSolutionUsable()) first.final_cost = costAt(prob, evaluator, z);
    if (z != z0 || !first.IsSolutionUsable() || cancelRequested(prob.cancel)) return first;
    std::vector<int> held;
    for (size_t k = 0; k < z0.size(); ++k) {
        const double tol = 1e-12 * std::max(1.0, std::abs(z0[k]));
        if (std::abs(z0[k] - map.lowerZ(k)) <= tol || std::abs(z0[k] - map.upperZ(k)) <= tol) held.push_back(static_cast<int>(k));
    }
    if (held.empty() || held.size() == z0.size()) return first;
    std::vector<double> z1 = z0;
    ceres::Solver::Summary second = solveOnce(prob, map, evaluator, z1, s, held);
    if (!second.IsSolutionUsable()) return first;
    second.final_cost = costAt(prob, evaluator, z1);
    if (!(second.final_cost < first.final_cost)) return first;
    z = std::move(z1);
    return second;
}

// How many starts ended at bestCost within FitProblem::sameCostTolerance (relative).
int startsAtCost(const FitProblem& prob, const std::vector<double>& startCosts, double bestCost) {
    int same = 0;
    for (double c : startCosts)
        if (std::isfinite(c) && std::abs(c - bestCost) <= prob.sameCostTolerance * std::max(std::abs(bestCost), 1e-300)) ++same;
    return same;
}

// The result at the optimum bestZ: with standard errors (FitProblem::uncertainty), or only its
// values and cost. False when the standard errors could not be computed (status set).
bool finishAtOptimum(const FitProblem& prob, const Mapping& map, PointEvaluator& evaluator, const std::vector<double>& bestZ,
                     double bestCost, FitResult& res) {
    res.values = map.allValues(bestZ.data());
    if (prob.uncertainty) return detail::fillUncertainty(prob, map, evaluator, bestZ, bestCost, res);
    res.cost = bestCost;
    res.rms = prob.loss == LossKind::None ? std::sqrt(2.0 * bestCost / static_cast<double>(prob.residualCount))
                                          : std::numeric_limits<double>::quiet_NaN();
    for (size_t idx : map.freeIdx) res.stderrs[idx] = std::numeric_limits<double>::quiet_NaN();
    res.identifiabilityMessage = "not computed (FitProblem::uncertainty is false)";
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
    if (maxLineSearchSteps < 1) note("maxLineSearchSteps must be >= 1");
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

namespace {

// The multistart's outcome: the lowest-cost start (z empty when none was usable).
struct BestStart {
    double cost = std::numeric_limits<double>::infinity();
    std::vector<double> z;
    ceres::Solver::Summary summary;
    bool cancelled = false;
    std::string lastFailure;
};

// Starts 0, 1, … (start 0 from the given values after the scans, the others random), each
// solved to its end; stops early once FitProblem::agreeingStarts ended at the best cost. Fills
// res's per-start fields (startsTried, startCosts, bestStart, stoppedEarly) and perStart.
BestStart runStarts(const FitProblem& prob, const Mapping& map, PointEvaluator& evaluator, FitResult& res,
                    std::ostringstream& perStart) {
    std::mt19937_64 rng(prob.seed);
    std::uniform_real_distribution<double> uni(0.1, 0.9);  // random starts stay off the bounds
    BestStart best;
    for (int s = 0; s < prob.multistarts && !best.cancelled; ++s) {
        const long evalsBefore = res.residualEvaluations;
        std::vector<double> z = startPoint(prob, map, evaluator, s, rng, uni, perStart);
        if (s == 0) z = scannedPoint(prob, map, evaluator, std::move(z), perStart);
        const ceres::Solver::Summary summary = solveFrom(prob, map, evaluator, z, s);
        ++res.startsTried;
        if (cancelRequested(prob.cancel)) best.cancelled = true;
        const bool usable = summary.IsSolutionUsable() && std::isfinite(summary.final_cost);
        res.startCosts.push_back(usable ? summary.final_cost : std::numeric_limits<double>::quiet_NaN());
        perStart << "start " << s << ": " << (usable ? "cost " + fmt(summary.final_cost) : "failed: " + summary.message)
                 << ", " << summary.iterations.size() << " iterations, " << ceres::TerminationTypeToString(summary.termination_type)
                 << ", " << (res.residualEvaluations - evalsBefore) << " evaluations\n";
        if (!usable) { best.lastFailure = summary.message; continue; }
        if (summary.final_cost < best.cost) {
            best.cost = summary.final_cost;
            best.z = z;
            best.summary = summary;
            res.bestStart = s;
        }
        // Early stop: enough starts ended at the best cost found so far (none lower).
        if (prob.agreeingStarts >= 2 && s + 1 < prob.multistarts) {
            const int same = startsAtCost(prob, res.startCosts, best.cost);
            if (same >= prob.agreeingStarts) {
                res.stoppedEarly = true;
                perStart << "stopped after " << (s + 1) << " of " << prob.multistarts << " starts: " << same
                         << " ended at the same cost (within " << fmt(prob.sameCostTolerance) << " relative)\n";
                break;
            }
        }
    }
    return best;
}

}  // namespace

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

    // Remembers the last few points (a Jacobian's 2p + 1 and a line search's trial points).
    PointEvaluator evaluator(map, res.residualEvaluations, 4 * p + 4);
    std::ostringstream perStart;
    const BestStart best = runStarts(prob, map, evaluator, res, perStart);
    res.wallTime_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (best.z.empty()) {
        res.status = best.cancelled ? FitStatus::Cancelled : FitStatus::Failed;
        res.message = best.cancelled ? "cancelled" : "no start gave a usable solution: " + best.lastFailure;
        res.solverSummary = perStart.str();
        return res;
    }
    res.converged = best.summary.termination_type == ceres::CONVERGENCE;
    res.initialCost = best.summary.initial_cost;
    res.solverSummary = best.summary.BriefReport() + "\n" + perStart.str();
    if (!finishAtOptimum(prob, map, evaluator, best.z, best.cost, res)) return res;
    res.status = best.cancelled ? FitStatus::Cancelled : FitStatus::Ok;
    if (best.cancelled) res.message = "cancelled (best result so far)";
    res.wallTime_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return res;
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
