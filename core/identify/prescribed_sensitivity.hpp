// Forward sensitivities of a prescribed-slip run: the derivatives of the predicted force with
// respect to the model's parameters, carried through the return map step by step alongside the
// run itself (one simulation instead of the 2p of a central-difference Jacobian).
//
// Each step's slip increment Δλ solves R(Δλ; a, α_n, θ) = 0 (extended_model.cpp), so by the
// implicit function theorem
//   ∂Δλ/∂θ = −(R_a ∂a/∂θ + R_α ∂α_n/∂θ + ∂R/∂θ) / R′,
// with R′ the slope the slip solve already uses; F_{n+1} = s (a − ε Δλ) and α_{n+1} = α(Δλ; α_n)
// then follow by the chain rule. A stuck step is F_n + ε Δg. The stick/slip decision of every
// step is the run's own: the result is the derivative of the discrete map where it is smooth,
// which is what a finite difference with a small step sees.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "extended_model.hpp"

namespace stickslip::identify {

// The parameters this covers: the law's keys (RateStateLaw::field: mu, eta, Dc, C1, r, vc,
// epsT) and "<effect>.<param>" of every catalogue effect switched on in the model; false with
// the name of the first other one.
bool sensitivitySupported(const ExtendedModel& m, const std::vector<std::string>& names, std::string* why = nullptr);

struct PrescribedSensitivity {
    RunStatus status = RunStatus::Ok;
    std::string message;
    ExtendedTrace trace;        // the run, as simulateExtendedPrescribed returns it
    Eigen::MatrixXd dMeasured;  // n × p: ∂(measured force)_i / ∂θ_j, θ in `names` order
    bool ok() const { return status == RunStatus::Ok; }
};

// simulateExtendedPrescribed (same arguments, same force) with the derivatives of its measured
// force with respect to `names`. Fails with a message naming the parameter or effect when
// sensitivitySupported does not hold.
PrescribedSensitivity simulatePrescribedSensitivity(const ExtendedModel& m, const RunContext& ctx,
                                                    const std::vector<double>& t_s, const std::vector<double>& slip_m,
                                                    const std::vector<double>* accel_mps2, int substeps,
                                                    const std::vector<std::string>& names, const RunControl& ctl = {},
                                                    const std::vector<double>* stepSlip_m = nullptr);

}  // namespace stickslip::identify
