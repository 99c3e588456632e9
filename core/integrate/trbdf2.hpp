// Second-order step of the rig coupled to a viscoplastic law: TR-BDF2 (Bank et al. 1985;
// Hosea & Shampine 1996) on the whole system
//   ẋ = v,   m v̇ = F − c v − k x                          (Eq. 8)
//   ṗ = s λ̇,  α̇ = −(λ̇/D_c)(α + C2 λ̇),  λ̇ = ⟨Φ⟩/(η t_N)     (Eqs. 2–3)
//   F = ε_T (u − x − p)                                     (Eq. 4 integrated: p is the plastic slip)
// with γ = 2 − √2: a trapezoidal stage to t_n + γh, then BDF2 to t_n + h. Both stages have the
// form y = y* + d f(y) with the same d = γh/2 (for this γ, (1 − γ)/(2 − γ) = γ/2), and for this
// system such a stage is exactly the paper's constrained update: with the oscillator condensed
// (as in the Newmark step, dynamics.hpp) it is the law's backward-Euler return map from the
// stage's own start (x*, v*, p*, α*) over a step d, with the return stiffness ε_T K/(K + ε_T),
// K = m/d² + c/d + k. So the return map, its bracketed Newton solve and its consistent tangent
// are reused unchanged, and the step is L-stable: the overstress, which relaxes in
// η t_N/ε_T ≪ h, is damped in one step instead of ringing.
//
// Why not backward Euler in the law (the fixed-step path): its force is the viscous force at the
// step's mean slip rate, an O(h) error in the end-point equilibrium; the adaptive integrator
// built on it reached order 1.31 on the rate-state law (docs/adaptive.md). TR-BDF2 is second
// order in stick and slip alike.
#pragma once

#include <cmath>
#include <concepts>
#include <numbers>

#include "dynamics.hpp"

namespace stickslip {

// Laws whose internal variable has a rate form α̇(α, λ̇) (Eq. 2) next to a prepared return map.
template <class Law>
concept HasAlphaRate = requires(const Law& l) {
    { l.alphaRate(0.0, 0.0) } -> std::same_as<double>;
} && detail::HasPreparedReturnMap<Law>;

namespace detail {

inline constexpr double kTrGamma = 2.0 - std::numbers::sqrt2;
// BDF2 stage: y_{n+1} = w1 y_γ − w0 y_n + d f(y_{n+1}),  w1 = 1/(γ(2−γ)), w0 = (1−γ)²/(γ(2−γ)).
inline constexpr double kTrW1 = 1.0 / (kTrGamma * (2.0 - kTrGamma));
inline constexpr double kTrW0 = (1.0 - kTrGamma) * (1.0 - kTrGamma) / (kTrGamma * (2.0 - kTrGamma));

// Constants of the stages of a step of length h (rig, ε_T and h fixed), computed once per size.
struct TrBdf2Constants {
    double h, d, invD, m, c, k, tN, eps, Keff, invKeff, invPredictor, returnStiffness;
    TrBdf2Constants(const RigParams& rig, double epsT, double h_)
        : h(h_), d(0.5 * kTrGamma * h_), invD(1.0 / d), m(rig.mass_kg), c(rig.damping_Ns_per_m), k(rig.stiffness_N_per_m),
          tN(rig.normalForce_N), eps(epsT), Keff(m / (d * d) + c / d + k), invKeff(1.0 / Keff),
          invPredictor(1.0 / (Keff + epsT)), returnStiffness(epsT * Keff / (Keff + epsT)) {}
    // x of a stage from (xs, vs) to stage displacement uNew with the plastic slip held at p
    // (the elastic predictor, oscillator condensed: K x = F + b, F = ε_T (uNew − x − p)).
    double elasticX(double xs, double vs, double p, double uNew) const {
        const double b = m * invD * (xs * invD + vs) + c * xs * invD;
        return (b + eps * (uNew - p)) * invPredictor;
    }
    double plasticSlip(const DynState& s) const { return s.u - s.x - s.law.force_N / eps; }  // p = g − F/ε_T
    double acceleration(double x, double v, double F) const { return (F - c * v - k * x) / m; }  // Eq. 8
};

// The variables a stage advances (F follows from them and u).
struct TrStage {
    double x, v, p, alpha;
};

// One stage y = y* + d f(y) ending at stage displacement uNew: the elastic predictor with the
// oscillator condensed, then the law's return map from it. `law` supplies the aux state carried
// through. False if the return map did not converge.
template <class Prepared>
inline bool trStage(const TrBdf2Constants& K, Prepared& prep, const TrStage& ys, double uNew, const LawState& law,
                    double slipHint, TrStage& out, ReturnMapResult& rm) {
    const double xTrial = K.elasticX(ys.x, ys.v, ys.p, uNew);
    const double fTrial = K.eps * (uNew - xTrial - ys.p);
    LawState st = law;
    st.alpha = ys.alpha;
    st.force_N = fTrial;
    rm = prep.returnMapFromTrial(st, fTrial, slipHint);
    if (!rm.converged) return false;
    double x = xTrial;
    double p = ys.p;
    if (!rm.stuck) {
        x += (rm.state.force_N - fTrial) * K.invKeff;
        p += (fTrial >= 0.0 ? 1.0 : -1.0) * rm.slipIncrement_m;
    }
    out = {x, (x - ys.x) * K.invD, p, rm.state.alpha};
    return true;
}

// Force of the elastic (stuck throughout) TR-BDF2 step of length K.h from s: what the law is
// asked to bear at its end. Φ of it is ≤ 0 when the step sticks in both stages (both stages'
// trials are elastic then), so its root in the step length locates a slip onset.
inline double trElasticEndForce(const TrBdf2Constants& K, const DynState& s, double uGamma, double u1) {
    const double d = K.d, p0 = K.plasticSlip(s), a0 = K.acceleration(s.x, s.v, s.law.force_N);
    const double xs1 = s.x + d * s.v, vs1 = s.v + d * a0;
    const double xg = K.elasticX(xs1, vs1, p0, uGamma), vg = (xg - xs1) * K.invD;
    const double x1 = K.elasticX(kTrW1 * xg - kTrW0 * s.x, kTrW1 * vg - kTrW0 * s.v, p0, u1);
    return K.eps * (u1 - x1 - p0);
}

// Hosea & Shampine's (1996) embedded estimate of a TR-BDF2 step: the third-order TR-X companion
//   ŷ = y_n + h [(1 − w)/3 f_n + (3w + 1)/3 f_γ + (γ/2)/3 f_{n+1}],   w = √2/4,
// minus the step's own y_{n+1} = y_n + h [w f_n + w f_γ + (γ/2) f_{n+1}]:
//   ŷ − y = h [(1 − 4w)/3 f_n + f_γ/3 − (γ/3) f_{n+1}],
// from the stage derivatives the step already has (no further law evaluation). It estimates the
// local error of y (second order); y is kept, since ŷ is not L-stable.
inline constexpr double kTrE0 = (1.0 - std::numbers::sqrt2) / 3.0, kTrE1 = 1.0 / 3.0, kTrE2 = -kTrGamma / 3.0;
struct TrError {
    double x = 0, v = 0, alpha = 0;  // ŷ − y of x, ẋ and α
};

// One TR-BDF2 step of s to stage displacement u1 at s.t + K.h (uGamma: the stage at s.t + γh).
// s.t is advanced by K.h; s.a is the equilibrium acceleration at the end (Eq. 8); s.slipRate is
// the second stage's λ̇, s.stuck whether both stages stuck. False (with `why`, `badValue`) on failure.
template <class Law, class Prepared>
inline bool trBdf2Step(const TrBdf2Constants& K, const Law& law, Prepared& prep, const StageMotion& stage, double uGamma,
                       double u1, DynState& s, int& lawIts, const char*& why, double& badValue,
                       TrError* err = nullptr) {
    const double d = K.d;
    const double p0 = K.plasticSlip(s);
    // λ̇_n: the slip rate the last stage solved for (s.slipRate, "first same as last"), not
    // ⟨Φ_n⟩/(η t_N): the two agree while the flow rule holds, but where the return map keeps F
    // from changing sign (strength μ + K1 < 0, possible when C1 > μ) Φ_n is not η t_N λ̇ and the
    // rate from it is far too large (seen: α driven to −28 where the solution has −1 … −10).
    const double lambdaDot0 = s.stuck ? 0.0 : s.slipRate;
    const double alphaDot0 = lambdaDot0 > 0.0 ? law.alphaRate(s.law.alpha, lambdaDot0) : 0.0;
    // Direction of the slip: sign F (Eq. 4), or, where the return map held F at 0 (strength
    // below 0), the sign of the slip velocity V = u̇ − ẋ.
    const double dir = s.law.force_N != 0.0 ? s.law.force_N : stage.velocity(s.t) - s.v;
    const double sgn0 = dir >= 0.0 ? 1.0 : -1.0;
    const double a0 = K.acceleration(s.x, s.v, s.law.force_N);
    const TrStage y0{s.x, s.v, p0, s.law.alpha};
    // Trapezoidal stage: y_γ = y_n + d (f_n + f_γ).
    const TrStage start1{y0.x + d * y0.v, y0.v + d * a0, y0.p + d * sgn0 * lambdaDot0, y0.alpha + d * alphaDot0};
    TrStage yg{}, y1{};
    ReturnMapResult rm;
    if (!trStage(K, prep, start1, uGamma, s.law, lambdaDot0 * d, yg, rm)) {
        why = "return mapping did not converge (slip increment, first stage)";
        badValue = rm.slipIncrement_m;
        return false;
    }
    lawIts += rm.iterations;
    const bool firstStuck = rm.stuck;
    const double hint = rm.stuck ? 0.0 : rm.slipIncrement_m;
    // BDF2 stage: y_{n+1} = w1 y_γ − w0 y_n + d f_{n+1}.
    const TrStage start2{kTrW1 * yg.x - kTrW0 * y0.x, kTrW1 * yg.v - kTrW0 * y0.v, kTrW1 * yg.p - kTrW0 * y0.p,
                         kTrW1 * yg.alpha - kTrW0 * y0.alpha};
    LawState mid = s.law;
    mid.alpha = yg.alpha;
    if (!trStage(K, prep, start2, u1, mid, hint, y1, rm)) {
        why = "return mapping did not converge (slip increment, second stage)";
        badValue = rm.slipIncrement_m;
        return false;
    }
    lawIts += rm.iterations;
    const double F = rm.state.force_N;
    if (!std::isfinite(y1.x) || !std::isfinite(y1.v)) { why = "non-finite slider state (x)"; badValue = y1.x; return false; }
    if (!std::isfinite(F)) { why = "non-finite friction force (F)"; badValue = F; return false; }
    if (!std::isfinite(rm.state.alpha)) { why = "non-finite state variable (alpha)"; badValue = rm.state.alpha; return false; }
    if (err) {  // stage derivatives f = (y − y*)/d of both stages (each stage is y = y* + d f(y))
        const double ag = (yg.v - start1.v) * K.invD, a1 = (y1.v - start2.v) * K.invD;
        const double alg = (yg.alpha - start1.alpha) * K.invD, al1 = (y1.alpha - start2.alpha) * K.invD;
        err->x = K.h * (kTrE0 * y0.v + kTrE1 * yg.v + kTrE2 * y1.v);
        err->v = K.h * (kTrE0 * a0 + kTrE1 * ag + kTrE2 * a1);
        err->alpha = K.h * (kTrE0 * alphaDot0 + kTrE1 * alg + kTrE2 * al1);
    }
    s.t += K.h;
    s.x = y1.x;
    s.v = y1.v;
    s.u = u1;
    s.law = rm.state;
    s.a = K.acceleration(y1.x, y1.v, F);
    s.slipRate = rm.stuck ? 0.0 : rm.slipIncrement_m / d;
    // Stuck only when both stages were elastic: a step that slips in its first stage and sticks
    // in its second holds a stop (and its slip), which the caller must see as a switch.
    s.stuck = firstStuck && rm.stuck;
    return true;
}

}  // namespace detail
}  // namespace stickslip
