// The rig's motion while the contact sticks, in closed form (issue 15). While Φ ≤ 0 the law is
// elastic (Eqs. 1, 4): F = ε_T (u − x − p) with the plastic slip p and the state α constant, so
// Eq. 8 becomes linear with constant coefficients,
//   m ẍ + c ẋ + K x = ε_T (u(t) − p),   K = k + ε_T,   u = A sin θ,  θ = ω t + φ,
// whose solution is the forced response plus the free ringing of the stuck mode:
//   x = X0 + Xs sin θ + Xc cos θ + z,   X0 = −ε_T p / K,
//   (Xs, Xc) = ε_T A ((K − m ω²), −c ω) / D,   D = (K − m ω²)² + (c ω)²,
//   z(τ) = e^{−σ τ} (z0 cos ω_d τ + (ż0 + σ z0)/ω_d sin ω_d τ),   σ = c/2m,  ω_d² = K/m − σ².
// A stuck step is then exact to round-off at any length: what limits it is only where the
// stick ends (Φ > 0 somewhere inside) and the dense output (cubic Hermite, adaptive.hpp)
// between its ends. Both are bounded from the two amplitudes (forced and ringing) below.
#pragma once

#include <algorithm>
#include <cmath>

#include "dynamics.hpp"
#include "illinois.hpp"

namespace stickslip::detail {

class StuckFlow {
public:
    // The rotation of the forced and the ringing phases over a step of length h.
    struct Step {
        double h = 0, decay = 1, cosD = 1, sinD = 0, cosW = 1, sinW = 0;
    };

    StuckFlow(const RigParams& rig, double epsT, const StageMotion& stage)
        : m_(rig.mass_kg), c_(rig.damping_Ns_per_m), k_(rig.stiffness_N_per_m), eps_(epsT) {
        if (!stage.isHarmonic() || !(m_ > 0.0) || !(epsT > 0.0)) return;
        A_ = stage.amplitude();
        w_ = stage.omega();
        phase_ = stage.phase();
        const double K = k_ + eps_;
        wn2_ = K / m_;
        sigma_ = 0.5 * c_ / m_;
        if (!(sigma_ * sigma_ < 0.81 * wn2_)) return;  // not clearly underdamped: the scheme's steps instead
        wd_ = std::sqrt(wn2_ - sigma_ * sigma_);
        invK_ = 1.0 / K;
        const double re = K - m_ * w_ * w_, im = c_ * w_, D = re * re + im * im;
        if (!(D > 0.0)) return;
        Xs_ = eps_ * A_ * re / D;
        Xc_ = -eps_ * A_ * im / D;
        // |ü − ẍ_p| / ω² and |x_p,harmonic| (amplitudes of the two harmonic parts).
        relAmp_ = std::hypot(A_ - Xs_, Xc_);
        forcedAmp_ = std::hypot(Xs_, Xc_);
        ringCurv_ = wn2_ + 2.0 * sigma_ * wd_;  // |z̈| ≤ ringCurv·R, |z''''| ≤ ringCurv²·R
        valid_ = true;
    }
    bool valid() const { return valid_; }

    Step step(double h) const {
        return {h, std::exp(-sigma_ * h), std::cos(wd_ * h), std::sin(wd_ * h), std::cos(w_ * h), std::sin(w_ * h)};
    }

    // Split of a stuck state: plastic slip p, the forced part's phase, the ringing (z, ż).
    struct Split {
        double p, X0, S, C, z, zd;
    };
    Split split(const DynState& s) const {
        Split q{};
        q.p = s.u - s.x - s.law.force_N / eps_;
        q.X0 = -eps_ * q.p * invK_;
        const double th = w_ * s.t + phase_;
        q.S = std::sin(th);
        q.C = std::cos(th);
        q.z = s.x - (q.X0 + Xs_ * q.S + Xc_ * q.C);
        q.zd = s.v - w_ * (Xs_ * q.C - Xc_ * q.S);
        return q;
    }
    // Amplitude R of the ringing (its envelope decays from R).
    double ringAmplitude(const Split& q) const { return std::hypot(q.z, (q.zd + sigma_ * q.z) / wd_); }

    // The stuck state a step st.h after s (split q of s): t, x, v, a, u, F; α and aux unchanged.
    DynState advance(const DynState& s, const Split& q, const Step& st) const {
        const double e = st.decay, cs = st.cosD, sn = st.sinD;
        const double z = e * (cs * q.z + sn * (q.zd + sigma_ * q.z) / wd_);
        const double zd = e * (cs * q.zd - sn * (wn2_ * q.z + sigma_ * q.zd) / wd_);
        const double S = q.S * st.cosW + q.C * st.sinW, C = q.C * st.cosW - q.S * st.sinW;
        DynState y = s;
        y.t = s.t + st.h;
        y.x = q.X0 + Xs_ * S + Xc_ * C + z;
        y.v = w_ * (Xs_ * C - Xc_ * S) + zd;
        y.u = A_ * S;
        y.law.force_N = eps_ * (y.u - y.x - q.p);
        y.a = (y.law.force_N - c_ * y.v - k_ * y.x) / m_;
        y.slipRate = 0.0;
        y.stuck = true;
        return y;
    }
    DynState advance(const DynState& s, const Split& q, double tau) const { return advance(s, q, step(tau)); }

    // Bound on |F''| over a step from a state with ringing amplitude R (the forced part's
    // relative motion and the ringing at most at full amplitude).
    double forceCurvatureBound(double R) const { return eps_ * (relAmp_ * w_ * w_ + R * ringCurv_); }
    // Longest step whose cubic Hermite interpolant of x (x, ẋ at both ends) is within errAbs:
    // |x − H| ≤ h⁴/384 max|x''''|, max|x''''| ≤ ω⁴ |x_p| + ringCurv² R.
    double hermiteStep(double R, double errAbs) const {
        const double m4 = forcedAmp_ * w_ * w_ * w_ * w_ + ringCurv_ * ringCurv_ * R;
        return m4 > 0.0 ? std::sqrt(std::sqrt(384.0 * errAbs / m4)) : INFINITY;
    }

    // A stuck step of length h from s (split q, ringing amplitude R; `cached`: its rotation when
    // h is a grid size) against the strength Y (|F| ≤ Y while stuck, Y constant). |F| ≤ Y is
    // certain on an interval when it holds at both ends with the chord bound len²/8 max|F''|
    // added; where it is not, the step is checked on `checks` sub-intervals and the first sample
    // beyond Y brackets the onset, located by Illinois on |F(τ)| − Y of the closed form (the
    // onset of the exact motion). Unsure: a sub-interval that the bound cannot clear (the caller
    // takes a shorter step of its own scheme); NonFinite: the state is not a number.
    struct Checked {
        enum Kind { Stuck, Onset, Unsure, NonFinite } kind = Stuck;
        DynState next;  // Stuck: the step's end; Onset: the onset (on the stuck side of it)
    };
    Checked checkedStep(const DynState& s, const Split& q, double R, double h, const Step* cached, double Y,
                        int checks) const {
        Checked out;
        out.next = cached ? advance(s, q, *cached) : advance(s, q, h);
        if (!std::isfinite(out.next.x) || !std::isfinite(out.next.v) || !std::isfinite(out.next.law.force_N)) {
            out.kind = Checked::NonFinite;
            return out;
        }
        const double curv = forceCurvatureBound(R);
        auto certain = [&](double Fa, double Fb, double len) {
            const double B = 0.125 * len * len * curv;
            return std::max(Fa, Fb) + B <= Y && std::min(Fa, Fb) - B >= -Y;
        };
        if (certain(s.law.force_N, out.next.law.force_N, h)) return out;
        double ta = 0.0, Fa = s.law.force_N;
        for (int j = 1; j <= checks; ++j) {
            const double tb = h * j / checks;
            const double Fb = j == checks ? out.next.law.force_N : advance(s, q, tb).law.force_N;
            if (std::abs(Fb) > Y) {
                out.next = advance(s, q, onsetIn(s, q, Y, ta, std::abs(Fa) - Y, tb, std::abs(Fb) - Y, h));
                out.kind = Checked::Onset;
                return out;
            }
            if (!certain(Fa, Fb, tb - ta)) {
                out.kind = Checked::Unsure;
                return out;
            }
            ta = tb;
            Fa = Fb;
        }
        return out;
    }

private:
    // Root of |F(τ)| − Y in [lo, hi] (g(lo) ≤ 0 < g(hi)) to 1e-12 h; the point returned is on
    // the stuck side.
    double onsetIn(const DynState& s, const Split& q, double Y, double lo, double glo, double hi, double ghi,
                   double h) const {
        return illinois([&](double tau) { return std::abs(advance(s, q, tau).law.force_N) - Y; }, lo, glo, hi, ghi,
                        1e-12 * h, false);
    }

    double m_, c_, k_, eps_;
    double A_ = 0, w_ = 0, phase_ = 0, wn2_ = 0, sigma_ = 0, wd_ = 1, invK_ = 0;
    double Xs_ = 0, Xc_ = 0, relAmp_ = 0, forcedAmp_ = 0, ringCurv_ = 0;
    bool valid_ = false;
};

}  // namespace stickslip::detail
