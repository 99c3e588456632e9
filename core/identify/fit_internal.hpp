// The fit engine's internals shared by fit.cpp (the Ceres solve) and fit_uncertainty.cpp
// (standard errors and identifiability at the optimum): the solver's coordinates and the
// residual evaluator with its memory of recent points. Not part of the public interface.
//
// Internal coordinates z (what Ceres sees), one per FREE parameter:
//   Linear: z = (v − lower)/(upper − lower)  ∈ [0, 1]        dv/dz = upper − lower
//   Log:    z = ln v                          ∈ [ln lo, ln up] dv/dz = v
// so every free coordinate is O(1) and the central-difference step (relativeStep·|z|) is
// meaningful for parameters spanning decades (ε_T ~ 1e6, D_c ~ 1e-5).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "fit.hpp"

namespace stickslip::identify::detail {

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

// The problem's own Jacobian (FitProblem::analyticJacobian) at internal point z, in internal
// coordinates (the chain rule through the mapping), row-major residualCount × free parameters;
// false when the problem has none or it cannot be formed there.
bool analyticJacobianAt(const Mapping& map, const std::vector<double>& z, std::vector<double>& J);

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
        if (!todo.empty() && cancelRequested(prob.cancel)) {
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

// A number for messages: 4 significant digits, or the printf format `f` (one double).
std::string fmt(double v, const char* f = "%.4g");

// Standard errors, correlations and identifiability at the optimum bestZ (FitProblem::
// uncertainty): the plain residuals and a central-difference Jacobian there
// (fit_uncertainty.cpp). False (status and message set) when the model cannot be evaluated at
// the optimum or next to it.
bool fillUncertainty(const FitProblem& prob, const Mapping& map, PointEvaluator& evaluator, const std::vector<double>& bestZ,
                     double bestCost, FitResult& res);

}  // namespace stickslip::identify::detail
