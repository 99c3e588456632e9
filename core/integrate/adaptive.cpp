#include "adaptive.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <type_traits>
#include <limits>
#include <numbers>
#include <optional>
#include <utility>
#include <vector>

#include "adaptive_calibration.hpp"
#include "illinois.hpp"
#include "stuck_flow.hpp"
#include "trbdf2.hpp"

namespace stickslip {

namespace {

using namespace adaptive_calibration;

// Constants of one step size: the Newmark step's, or (tr) the TR-BDF2 stages' with the law
// prepared for their stage length d = γh/2.
template <class Law>
struct Kit {
    using Prep = decltype(std::declval<const Law&>().prepare(0.0, 0.0, 0.0));
    detail::NewmarkConstants K;
    detail::TrBdf2Constants T;
    Prep prep;
    double cosWh = 1, sinWh = 0;  // rotation of the harmonic stage's phase over h
    double cosWg = 1, sinWg = 0;  // ... over γh (the TR-BDF2 stage)
    Kit(const RigParams& rig, const Law& law, double h, double omega, bool tr)
        : K(rig, law.epsT(), h), T(rig, law.epsT(), h),
          prep(tr ? law.prepare(T.returnStiffness, T.d, T.tN) : law.prepare(K.returnStiffness, h, K.tN)),
          cosWh(std::cos(omega * h)), sinWh(std::sin(omega * h)),
          cosWg(tr ? std::cos(omega * detail::kTrGamma * h) : 1.0), sinWg(tr ? std::sin(omega * detail::kTrGamma * h) : 0.0) {}
};

template <class Law>
class Adaptive {
public:
    Adaptive(const DynamicsModel& m, const Law& law, const AdaptiveOptions& o) : m_(m), law_(law), o_(o) {
        const double T = m.stage.isHarmonic() && m.stage.omega() > 0 ? 2.0 * std::numbers::pi / m.stage.omega() : 0.0;
        period_ = T > 0 ? T : 1.0;
        hMax_ = o.maxStep_s > 0 ? o.maxStep_s : (T > 0 ? T / 32.0 : 1e-2);
        // 2^-26 h_max (1.6e-10 s at 3 Hz): at ~1e-13 s Newmark's a = 4/h² (Δx − h v) − a is round-off (a
        // grazing stop then chatters at the smallest step, measured); the step sizes in use stay far above.
        hMin_ = o.minStep_s > 0 ? o.minStep_s : hMax_ * std::pow(2.0, -26.0);
        kMax_ = std::min(kLevels - 5, static_cast<int>(std::ceil(4.0 * std::log2(hMax_ / hMin_))));
        scale_ = o.displacementScale_m > 0 ? o.displacementScale_m
                                           : (m.stage.isHarmonic() ? 0.05 * std::abs(m.stage.amplitude()) : 0.0);
        scale_ = std::max(scale_, 1e-12);
        cache_.resize(kLevels);  // the only allocation: before the time loop
        for (int k = 0; k < kLevels; ++k) hTable_[static_cast<size_t>(k)] = hMax_ * std::exp2(-0.25 * k);
        harmonic_ = m.stage.isHarmonic();
        if constexpr (requires { Law::kViscous; }) viscous_ = Law::kViscous;
        if constexpr (HasAlphaRate<Law>) tr_ = o.trBdf2;
        embedded_ = tr_ && o.embeddedSlip;
        if constexpr (requires { law.params.r; }) alphaScale_ = law.params.r;
        omega_ = harmonic_ ? m.stage.omega() : 0.0;
        ringTime_ = 1.0 / std::max(std::sqrt(m.rig.stiffness_N_per_m / m.rig.mass_kg), 2.0 * std::numbers::pi / period_);
        kStart_ = std::min(kMax_, 24);
        kOnset_ = std::min(kMax_, kStart_ + 16);
        if constexpr (requires { Law::kElasticStick; }) {
            if (Law::kElasticStick && o.closedFormStick) {
                flow_.emplace(m.rig, law.epsT(), m.stage);
                if (!flow_->valid()) flow_.reset();
                else flowSteps_.resize(kLevels);
            }
        }
    }
    AdaptiveReport run(DynState& s, double tEnd, const AdaptiveObserver& obs, const RunControl& ctl);

private:
    // A closed-form stuck step (stuck_flow.hpp) from a stuck state: `next` is its end (on the
    // stuck side of a located slip onset when `onset`); `fallback`: the bounds cannot exclude an
    // onset inside it, the scheme's step takes it at `level`.
    struct StuckStep {
        DynState next;
        bool onset = false, atEnd = false, fallback = false;
        int level = 0;
    };
    StuckStep stuckStep(const DynState& s, double tEnd);
    bool closedFormStep(DynState& s, double tEnd, int& k, int& relabels, const AdaptiveObserver& obs);
    // Bookkeeping of an accepted step from s to next (which ends exactly at tEnd when atEnd).
    void accept(DynState& s, const DynState& next, bool atEnd, double tEnd, const AdaptiveObserver& obs) {
        ++rep_.accepted;
        rep_.stuckSteps += next.stuck ? 1 : 0;
        if (obs) obs(s, next);
        s = next;
        if (atEnd) s.t = tEnd;
        maxAbsX_ = std::max(maxAbsX_, std::abs(s.x));
    }
    const detail::StuckFlow::Step& flowStep(int k) {
        auto& c = flowSteps_[static_cast<size_t>(k)];
        if (!c) c = flow_->step(hOf(k));
        return *c;
    }
    double hOf(int k) const { return hTable_[static_cast<size_t>(k)]; }
    Kit<Law>& kit(int k) {
        if (!cache_[static_cast<size_t>(k)]) cache_[static_cast<size_t>(k)].emplace(m_.rig, law_, hOf(k), omega_, tr_);
        return *cache_[static_cast<size_t>(k)];
    }
    // One base step of y to tNew, stage at u1, with the kit's step: TR-BDF2 (tr_) or Newmark with
    // the condensed return map. uGamma: the stage at y.t + γh (NaN: computed here).
    bool base(Kit<Law>& kt, DynState& y, double tNew, double u1, double uGamma = NAN, detail::TrError* err = nullptr) {
        int nIts = 0, lIts = 0;
        const char* why = nullptr;
        double bad = 0;
        ++rep_.baseSteps;
        bool ok = false;
        if constexpr (HasAlphaRate<Law>) {
            if (tr_) {
                if (std::isnan(uGamma)) uGamma = m_.stage.displacement(y.t + detail::kTrGamma * kt.T.h);
                ok = detail::trBdf2Step(kt.T, law_, kt.prep, m_.stage, uGamma, u1, y, lIts, why, bad, err);
            }
        }
        if (!tr_) ok = detail::newmarkStep(kt.K, law_, &kt.prep, u1, y, Coupling::Condensed, nIts, lIts, why, bad);
        rep_.lawIterations += lIts;
        if (ok) y.t = tNew;
        return ok;
    }
    bool base(Kit<Law>& kt, DynState& y, double tNew) { return base(kt, y, tNew, m_.stage.displacement(tNew)); }
    // sin and cos of a harmonic stage's phase at t, and its amplitude: what the kits' rotations
    // turn into the stage displacement at the ends and stages of a step from t.
    std::array<double, 3> phaseAt(double t) const {
        const double th = omega_ * t + m_.stage.phase();
        return {std::sin(th), std::cos(th), m_.stage.amplitude()};
    }
    // y1: one step h from s; ym, y2: two steps h/2. False if a base step failed. A harmonic stage
    // is advanced from one sincos at s.t by the kits' rotations (angle addition, exact to round-off)
    // instead of a sine per base step (13 % of the run time, measured with perf).
    bool doubled(Kit<Law>& full, Kit<Law>& half, const DynState& s, double h, DynState& y1, DynState& ym, DynState& y2) {
        double uHalf, uFull, gFull = NAN, gHalf1 = NAN, gHalf2 = NAN;
        if (harmonic_) {
            const auto [S, C, A] = phaseAt(s.t);
            uHalf = A * (S * half.cosWh + C * half.sinWh);
            uFull = A * (S * full.cosWh + C * full.sinWh);
            if (tr_) {  // the stages at s.t + γh, s.t + γh/2 and s.t + h/2 + γh/2
                gFull = A * (S * full.cosWg + C * full.sinWg);
                gHalf1 = A * (S * half.cosWg + C * half.sinWg);
                const double Sh = S * half.cosWh + C * half.sinWh, Ch = C * half.cosWh - S * half.sinWh;
                gHalf2 = A * (Sh * half.cosWg + Ch * half.sinWg);
            }
        } else {
            uHalf = m_.stage.displacement(s.t + 0.5 * h);
            uFull = m_.stage.displacement(s.t + h);
        }
        y1 = s;
        ym = s;
        errFull_ = {};
        if (!base(full, y1, s.t + h, uFull, gFull, tr_ ? &errFull_ : nullptr) || !base(half, ym, s.t + 0.5 * h, uHalf, gHalf1))
            return false;
        y2 = ym;
        return base(half, y2, s.t + h, uFull, gHalf2);
    }
    // One TR-BDF2 step h from s with its embedded estimate (AdaptiveOptions::embeddedSlip).
    bool single(Kit<Law>& kt, const DynState& s, double h, DynState& y, detail::TrError& err) {
        double u1, ug;
        if (harmonic_) {
            const auto [S, C, A] = phaseAt(s.t);
            u1 = A * (S * kt.cosWh + C * kt.sinWh);
            ug = A * (S * kt.cosWg + C * kt.sinWg);
        } else {
            u1 = m_.stage.displacement(s.t + h);
            ug = m_.stage.displacement(s.t + detail::kTrGamma * h);
        }
        y = s;
        return base(kt, y, s.t + h, u1, ug, &err);
    }
    bool singleFresh(const DynState& s, double h, DynState& y, detail::TrError& err) {
        Kit<Law> kt(m_.rig, law_, h, omega_, tr_);
        return single(kt, s, h, y, err);
    }
    bool doubledFresh(const DynState& s, double h, DynState& y1, DynState& ym, DynState& y2) {
        Kit<Law> full(m_.rig, law_, h, omega_, tr_), half(m_.rig, law_, 0.5 * h, omega_, tr_);
        return doubled(full, half, s, h, y1, ym, y2);
    }
    // Local Richardson extrapolation (header comment): weight 1/3 when stuck throughout (the
    // trapezoidal rule's even expansion) or with TR-BDF2 (second order in slip too), 1 otherwise
    // (backward Euler's h term in the law).
    DynState combine(const DynState& y1, const DynState& y2, bool stuckThroughout, bool stuck) const {
        const double w = stuckThroughout || tr_ ? 1.0 / 3.0 : 1.0;
        DynState y = y2;
        y.x += w * (y2.x - y1.x);
        y.v += (stuckThroughout || tr_ || !viscous_ ? w : kViscousVelocityWeight) * (y2.v - y1.v);
        y.law.force_N += w * (y2.law.force_N - y1.law.force_N);
        y.law.alpha += w * (y2.law.alpha - y1.law.alpha);
        // Equilibrium at the end of the step (Eq. 8), as the Newmark step itself enforces it.
        y.a = (y.law.force_N - m_.rig.damping_Ns_per_m * y.v - m_.rig.stiffness_N_per_m * y.x) / m_.rig.mass_kg;
        y.stuck = stuck;
        return y;
    }
    // What the estimate of a step of length h may be (error per unit step), times `factor`.
    double allowance(double h, double factor) const {
        return o_.tolerance * std::max(scale_, maxAbsX_) * kPerPeriod * factor * h / period_;
    }
    // Estimate over allowance (error per unit step; accept when ≤ 1). errFull: the TR-X estimate
    // of y1 (TR-BDF2 slip steps; see kRoundoffUlps for the estimate of the kept value).
    double ratio(const DynState& y1, const DynState& y2, double h, bool stuckThroughout, const detail::TrError& errFull) const {
        // x and h·ẋ only. Measured alternatives: adding |ΔF|/k or the α difference (× t_N C1/(r k))
        // makes the estimate stall in slip (the viscoplastic overstress relaxes in η t_N/ε_T ≈ 4 µs
        // at the paper's set, far below any useful step) and the runs 10–1000× slower.
        double est = 0, allowed = 0;
        if (tr_ && !stuckThroughout) {
            // ŷ₁ − kept = (ŷ₁ − y₁) − (4/3)(y₂ − y₁): both third order, so this is O(h⁴).
            const double ex = errFull.x - (4.0 / 3.0) * (y2.x - y1.x), ev = errFull.v - (4.0 / 3.0) * (y2.v - y1.v);
            const double wv = std::max(h, ringTime_);
            est = std::max(std::abs(ex), wv * std::abs(ev));
            const double d = 0.5 * detail::kTrGamma * h;
            allowed = std::max(allowance(h, 1.0),
                               kRoundoffUlps * std::numeric_limits<double>::epsilon() * std::max(scale_, maxAbsX_) * wv / d);
        } else {
            est = std::max(std::abs(y2.x - y1.x), h * std::abs(y2.v - y1.v));
            allowed = allowance(h, stuckThroughout ? kStuckAllowance : 1.0);
        }
        // Guard, not accuracy: the extrapolation is only meaningful where the one step and the two
        // half steps nearly agree. Where α (whose effect on the strength is exponential, K1 ∝
        // exp(α/r)) differs between them by more than kAlphaResolution·r, the step is not
        // resolved and y + (y₂ − y₁)/3 can land anywhere (seen: α = +17.7 from y₂ = −0.0001 and
        // y₁ = −53 in one accepted step, the contact then stuck for good; random parameter sets
        // in tst_adaptive::randomSetsAgreeAcrossTolerances).
        const double guard = std::abs(y2.law.alpha - y1.law.alpha) / (kAlphaResolution * alphaScale_);
        return std::max(est / allowed, guard);
    }
    // The same for a step judged by its embedded estimate: x and h·ẋ, α as the guard.
    double ratioEmbedded(const detail::TrError& e, double h) const {
        const double est = std::max(std::abs(e.x), h * std::abs(e.v));
        return std::max(est / allowance(h, kEmbeddedAllowance), std::abs(e.alpha) / (kAlphaResolution * alphaScale_));
    }
    double trialSlip(const DynState& s, double tau) const;
    double locate(const DynState& s, double h, const DynState& y1);
    // The step run() attempts from s.
    struct Attempt {
        double h;         // its length
        bool atEnd;       // it ends at tEnd (not when it is cut at a switch inside it)
        bool stuckEnd;    // the regime it ends in
        bool toOnset;     // it ends at a located stick → slip switch
        bool throughout;  // stuck in every base step
    };
    bool cutAtSwitch(DynState& s, int& k, int& relabels, bool one, Attempt& at, DynState& y1, DynState& ym,
                     DynState& y2, detail::TrError& err);
    // The step of length tau from s, in y; false if the base step failed.
    bool stepFrom(const DynState& s, double tau, DynState& y) {
        Kit<Law> kt(m_.rig, law_, tau, omega_, tr_);
        y = s;
        return base(kt, y, s.t + tau);
    }
    // The same; true if it ends slipping.
    bool slipStep(const DynState& s, double tau, DynState& y) { return stepFrom(s, tau, y) && !y.stuck; }
    bool keepsSlipping(const DynState& s, double tau) {
        DynState y;
        return slipStep(s, tau, y);
    }
    // First root of sign(F_s) V(t) on the dense output between s and y (length tau: ẋ Hermite
    // in ẋ, ẍ as denseState forms it), by Illinois (the bisection used before took 60 stage
    // velocities and interpolants per stop, a sixth of a run's time in sin and cos); the point
    // returned is on the slip side. −1 if V does not go from the slip direction to the other
    // within the step.
    double reversalOn(const DynState& s, const DynState& y, double tau) const {
        const double sgn = s.law.force_N >= 0.0 ? 1.0 : -1.0;
        auto g = [&](double t) {
            const double th = t / tau, th2 = th * th, th3 = th2 * th;
            const double v = (2 * th3 - 3 * th2 + 1) * s.v + (th3 - 2 * th2 + th) * tau * s.a + (-2 * th3 + 3 * th2) * y.v +
                             (th3 - th2) * tau * y.a;
            return sgn * (m_.stage.velocity(s.t + t) - v);
        };
        const double glo = g(0.0), ghi = g(tau);
        if (!(glo > 0.0) || !(ghi < 0.0)) return -1.0;
        return detail::illinois(g, 0.0, glo, tau, ghi, 1e-12 * tau, true);
    }
    int nextLevel(int k, double r, bool stuck) const {
        // est/h ∝ h² for y₂'s estimate: the estimate is on x, whose local error is O(h³) also in slip
        // (backward Euler's O(h²) force error enters x with h²/m). An exponent 1 in slip, tried
        // first, rejected 32 % of the attempts (now ~2 %; 31–41 % fewer base steps, measured).
        // TR-BDF2 slip steps' estimate is O(h⁴) (kRoundoffUlps), but the cube root took 1–9 % more
        // base steps on the bench set than this square root (session 26).
        (void)stuck;
        const double f = 0.85 / std::sqrt(std::max(r, 1e-10));
        const int dk = -static_cast<int>(std::floor(4.0 * std::log2(std::clamp(f, 0.0625, 2.0))));
        return std::clamp(k + dk, 0, kMax_);
    }

    const DynamicsModel& m_;
    const Law& law_;
    const AdaptiveOptions& o_;
    double period_ = 1, hMax_ = 0, hMin_ = 0, scale_ = 0, maxAbsX_ = 0, omega_ = 0, alphaScale_ = 1;
    double ringTime_ = 0;  // 1/ω_n, ω_n = √(k/m) (at least 2π/period_): see kRoundoffUlps
    // Levels the steps restart from: kStart_ = h_max/64, where the first steps resolve the start
    // from rest (and, in the scheme's own path, a slip onset); kOnset_ = h_max/1024 (T/32 768)
    // after an onset located on the closed form. The onset starts the law's transients (the
    // overstress relaxing in η t_N/ε_T, α over D_c/|V| from V = 0); a first step that spans them
    // damps them alike in the one step and the two half steps (L-stable), so the estimate does
    // not see its error. From h_max/64 that error was a floor that did not fall with TOL (5.6e-5
    // at TOL 1e-4, 1.9e-5 at 1e-5 on the bench_core set; from h_max/1024 2.4e-5 and 2.7e-6, for
    // 2 % more steps; docs/adaptive.md, session 24).
    int kStart_ = 0, kOnset_ = 0;
    bool harmonic_ = false, viscous_ = false, tr_ = false, embedded_ = false;
    std::array<double, kLevels> hTable_{};
    int kMax_ = 0;
    std::vector<std::optional<Kit<Law>>> cache_;
    std::optional<detail::StuckFlow> flow_;  // closed-form stick (laws elastic in stick, harmonic stage)
    std::vector<std::optional<detail::StuckFlow::Step>> flowSteps_;
    AdaptiveReport rep_;
    detail::TrError errFull_;  // TR-X estimate of the last doubled attempt's one step (TR-BDF2)
};

// Φ_trial (Eq. 1) of the elastic predictor of a step of length τ from s: the same arithmetic as
// newmarkStep's predictor, so Φ_trial(τ) ≤ 0 exactly when that step sticks.
template <class Law>
double Adaptive<Law>::trialSlip(const DynState& s, double tau) const {
    if (tr_) {
        const detail::TrBdf2Constants T(m_.rig, law_.epsT(), tau);
        LawState end = s.law;
        end.force_N = detail::trElasticEndForce(T, s, m_.stage.displacement(s.t + detail::kTrGamma * tau),
                                                m_.stage.displacement(s.t + tau));
        return law_.slipFunction(end, T.tN);
    }
    const detail::NewmarkConstants K(m_.rig, law_.epsT(), tau);
    const double du = m_.stage.displacement(s.t + tau) - s.u;
    const double b = K.m * (K.i4h2 * (s.x + tau * s.v) + s.a) + K.c * (K.i2h * s.x + s.v);
    const double x = (b + s.law.force_N + K.eps * (du + s.x)) * K.invPredictor;
    LawState tr = s.law;
    tr.force_N = s.law.force_N + K.eps * (du - (x - s.x));
    return law_.slipFunction(tr, K.tN);
}

// Length τ ∈ (0, h) of the step from s that ends at the switch (on the side of s's regime);
// 0 when the switch is at s itself; −1 when no switch is bracketed by [0, h] (or [0, h/2]);
// kSwitchInside when the step may keep it (judged by the error control alone).
template <class Law>
double Adaptive<Law>::locate(const DynState& s, double h, const DynState& y1) {
    double lo = 0.0, hi = h;
    if (s.stuck) {
        // Stick → slip: root of Φ_trial(τ), Illinois (regula falsi with halving) in [0, h].
        double glo = law_.slipFunction(s.law, m_.rig.normalForce_N);
        if (glo > 0.0) return 0.0;
        double ghi = trialSlip(s, hi);
        if (ghi <= 0.0) { hi = 0.5 * h; ghi = trialSlip(s, hi); }
        if (ghi <= 0.0) return -1.0;
        lo = detail::illinois([&](double tau) { return trialSlip(s, tau); }, lo, glo, hi, ghi, 1e-10 * h, false);
    } else {
        // Slip → stick. The step's trial is elastic over the whole step, so a step still slips a
        // little after the slip velocity has reversed; the slip ends where V = u̇ − ẋ changes sign
        // (sign F = sign V in slip, Eq. 4; for the viscoplastic law Φ = η t_N λ̇ falls to 0 within
        // η t_N/ε_T of it): the root of V on the scheme's own interpolant (Hermite in ẋ) of a step
        // that still slips and contains it. Such steps are those from that root to the largest
        // τ* that still slips, so: guess the root from the attempted step's own dense output, take
        // the step to just past the guess and read the root off it (one base step, as a rule).
        // From a state past the reversal what is left is the overstress relaxing: it has ended
        // when Φ ≤ 0 (the switch is at s), else the step is left to the error control (below).
        const double tN = m_.rig.normalForce_N;
        const double sgn = s.law.force_N >= 0.0 ? 1.0 : -1.0;
        const bool reversed = !(sgn * (m_.stage.velocity(s.t) - s.v) > 0.0);
        if (reversed && !(law_.slipFunction(s.law, tN) > 0.0)) return 0.0;
        if (!y1.stuck) {
            hi = 0.5 * h;
            if (keepsSlipping(s, hi)) return -1.0;
        }
        DynState y;
        if (!reversed) {
            double guess = reversalOn(s, y1, h);
            guess = guess > 0.0 && guess < hi ? guess * (1.0 + kStopOvershoot) : -1.0;
            for (int it = 0; it < 3 && guess > 0.0; ++it) {
                const double tau = std::clamp(guess, lo + 0.01 * (hi - lo), hi - 0.01 * (hi - lo));
                if (!slipStep(s, tau, y)) { hi = tau; guess = lo + 0.5 * (tau - lo); continue; }
                lo = tau;
                const double root = reversalOn(s, y, tau);
                if (root >= 0.0) return root <= 1e-6 * h ? 0.0 : root;
                guess = tau * (1.0 + 4.0 * kStopOvershoot);  // the root lies a little beyond
            }
        }
        // The overstress relaxing (Φ(s) > 0 with V already reversed) ends within the step: the
        // force is continuous through that end and only its slope changes, by ε_T λ̇ → 0, so the
        // step is judged by the error control alone instead of being cut there (cutting it took
        // ~25 base steps per stop, for a kink the estimate does not see).
        if (reversed) return kSwitchInside;
        // τ*, the largest τ whose step still slips, by bisection on the step's outcome.
        while (hi - lo > 1e-7 * h) {
            const double mid = 0.5 * (lo + hi);
            if (keepsSlipping(s, mid)) lo = mid; else hi = mid;
        }
        if (lo > 0.0 && slipStep(s, lo, y)) {
            const double root = reversalOn(s, y, lo);
            if (root >= 0.0) lo = root;
        }
    }
    return lo <= 1e-6 * h ? 0.0 : lo;
}

// The closed-form stuck step (stuck_flow.hpp): as long as the Hermite interpolant allows, unless
// the contact may start to slip inside it (StuckFlow::checkedStep).
template <class Law>
typename Adaptive<Law>::StuckStep Adaptive<Law>::stuckStep(const DynState& s, double tEnd) {
    const detail::StuckFlow& f = *flow_;
    const detail::StuckFlow::Split q = f.split(s);
    const double R = f.ringAmplitude(q);
    const double hH = f.hermiteStep(R, kHermiteShare * o_.tolerance * std::max(scale_, maxAbsX_));
    StuckStep out;
    const double lv = 4.0 * std::log2(hMax_ / hH);  // NaN or +inf when hH is not a positive number
    out.level = hH >= hMax_ ? 0 : (lv < kMax_ ? std::max(0, static_cast<int>(std::ceil(lv))) : kMax_);
    double h = hOf(out.level);
    out.atEnd = s.t + h >= tEnd - 1e-9 * h;
    if (out.atEnd) h = tEnd - s.t;
    LawState free = s.law;
    free.force_N = 0.0;
    const double Y = -law_.slipFunction(free, m_.rig.normalForce_N);  // the strength while stuck
    const auto c = f.checkedStep(s, q, R, h, out.atEnd ? nullptr : &flowStep(out.level), Y, kStuckChecks);
    out.next = c.next;
    switch (c.kind) {
        case detail::StuckFlow::Checked::Stuck: break;
        case detail::StuckFlow::Checked::Onset: out.onset = true; out.atEnd = false; break;
        case detail::StuckFlow::Checked::Unsure: out.fallback = true; out.level = std::min(kMax_, out.level + 12); break;  // h/8
        case detail::StuckFlow::Checked::NonFinite: out.fallback = true; break;  // the scheme reports the failure
    }
    return out;
}

// One closed-form stuck step from a stuck s, accepted (true), or false when it hands the step
// to the scheme (level k raised to the size it asks for).
template <class Law>
bool Adaptive<Law>::closedFormStep(DynState& s, double tEnd, int& k, int& relabels, const AdaptiveObserver& obs) {
    const StuckStep st = stuckStep(s, tEnd);
    if (st.fallback) {
        k = std::max(k, st.level);
        return false;
    }
    if (st.next.t > s.t) {
        accept(s, st.next, st.atEnd, tEnd, obs);
        ++rep_.closedFormSteps;
        relabels = 0;
    } else {
        ++relabels;  // the onset is at s
    }
    if (st.onset) {  // continue in slip, the steps growing again from h_max/1024
        s.stuck = false;
        s.slipRate = 0.0;
        ++rep_.switches;
        k = kOnset_;
    }
    return true;
}

// An attempt whose base steps disagree on stick or slip: the switch is located (locate()). At s:
// s is relabelled. Inside: the step is redone up to it and ends on s's side of it. Otherwise the
// error control alone judges the step, or (no bracket) it is rejected. False: the attempt is
// over (relabelled or rejected), run() starts the next one.
template <class Law>
bool Adaptive<Law>::cutAtSwitch(DynState& s, int& k, int& relabels, bool one, Attempt& at, DynState& y1, DynState& ym,
                                DynState& y2, detail::TrError& err) {
    const double tau = locate(s, at.h, y1);
    if (tau == 0.0) {  // the switch is at s: continue in the other regime
        if (s.stuck && tr_) k = std::max(k, kStart_);
        s.stuck = !s.stuck;
        if (!s.stuck) s.slipRate = 0.0;
        ++rep_.switches;
        ++relabels;
        return false;
    }
    if (tau > 0.0) {
        at.h = tau;
        at.atEnd = false;
        const bool again = one ? singleFresh(s, at.h, y1, err) : doubledFresh(s, at.h, y1, ym, y2);
        if (!again) { ++rep_.rejected; k = std::min(kMax_, k + 4); return false; }
        if (one) ym = y2 = y1;
        at.stuckEnd = s.stuck;  // the step ends at the switch, on s's side of it
        at.toOnset = s.stuck;
        at.throughout = s.stuck && y1.stuck && ym.stuck && y2.stuck;
    } else if (tau == kSwitchInside) {
        // error control only (locate())
    } else if (k < kMax_) {
        ++rep_.rejected;  // no bracket in [0, h]: shrink and try again
        k = std::min(kMax_, k + 4);
        return false;
    }  // else: at the smallest step, accept the switch inside it (error control only)
    return true;
}

template <class Law>
AdaptiveReport Adaptive<Law>::run(DynState& s, double tEnd, const AdaptiveObserver& obs, const RunControl& ctl) {
    int k = kStart_;
    int relabels = 0;
    DynState y1, ym, y2;
    auto fail = [&](const char* what) {
        char buf[256];
        std::snprintf(buf, sizeof buf, "adaptive step at t = %.9g s: %s", s.t, what);
        rep_.status = RunStatus::Failed;
        rep_.message = buf;
        return rep_;
    };
    while (s.t < tEnd) {
        if ((rep_.accepted & 255) == 0 && ctl.cancelled()) {
            rep_.status = RunStatus::Cancelled;
            rep_.message = "cancelled";
            return rep_;
        }
        if (rep_.accepted + rep_.rejected >= o_.maxSteps) return fail("step budget (max_steps) exceeded");
        if (flow_ && s.stuck && relabels < 2 && closedFormStep(s, tEnd, k, relabels, obs)) continue;
        Attempt at{hOf(k), false, false, false, false};
        const bool last = s.t + at.h >= tEnd - 1e-9 * at.h;
        if (last) at.h = tEnd - s.t;
        at.atEnd = last;
        // A slip step by TR-BDF2 is one base step judged by its embedded estimate (err); the
        // other steps are doubled and extrapolated.
        const bool one = embedded_ && !s.stuck;
        detail::TrError err;
        const bool ok = one ? (last ? singleFresh(s, at.h, y1, err) : single(kit(k), s, at.h, y1, err))
                            : (last ? doubledFresh(s, at.h, y1, ym, y2) : doubled(kit(k), kit(k + 4), s, at.h, y1, ym, y2));
        if (!ok) {
            ++rep_.rejected;
            if (k >= kMax_) return fail("base step failed at the smallest step");
            k = std::min(kMax_, k + 4);
            continue;
        }
        if (one) ym = y2 = y1;
        const bool same = y1.stuck == s.stuck && ym.stuck == s.stuck && y2.stuck == s.stuck;
        at.stuckEnd = y2.stuck;
        at.throughout = same && s.stuck;
        if (!same && o_.locateSwitches && relabels < 2 && !cutAtSwitch(s, k, relabels, one, at, y1, ym, y2, err)) continue;
        const double r = one ? ratioEmbedded(err, at.h) : ratio(y1, y2, at.h, at.throughout, errFull_);
        if (!(r <= 1.0) && k < kMax_) {
            ++rep_.rejected;
            // A located step that is too long: regular steps approach the switch instead.
            while (k < kMax_ && hOf(k) > at.h) ++k;
            k = std::max(k, nextLevel(k, r, at.throughout));
            continue;
        }
        DynState next = y1;
        if (one) next.stuck = at.stuckEnd;
        else next = combine(y1, y2, at.throughout, at.stuckEnd);
        if (!std::isfinite(next.x) || !std::isfinite(next.v) || !std::isfinite(next.law.force_N) ||
            !std::isfinite(next.law.alpha))
            return fail("non-finite state");
        relabels = 0;
        accept(s, next, at.atEnd, tEnd, obs);
        k = nextLevel(k, r, at.throughout);
        // A slip onset located by the scheme (closedFormStick off, or handed back to it): the
        // steps grow again from h_max/64 instead of one step of the size reached in stick
        // spanning the law's transients. (From kOnset, the order test's run at h_max = T/2000,
        // TOL 0.5, went from 4.7e-6 to 1.0e-4: kept as it was for the scheme's own path.)
        if (at.toOnset && tr_) k = std::max(k, kStart_);
    }
    return rep_;
}

}  // namespace

AdaptiveReport advanceAdaptive(const DynamicsModel& m, DynState& s, double tEnd, const AdaptiveOptions& o,
                               const AdaptiveObserver& onStep, const RunControl& ctl) {
    AdaptiveReport rep;
    ParamIssues issues = m.validate();
    const ParamIssues more = o.validate();
    issues.insert(issues.end(), more.begin(), more.end());
    if (!issues.empty()) {
        rep.status = RunStatus::Failed;
        rep.message = formatIssues(issues);
        return rep;
    }
    return std::visit([&](const auto& law) {
        Adaptive<std::decay_t<decltype(law)>> a(m, law, o);
        return a.run(s, tEnd, onStep, ctl);
    }, m.law);
}

}  // namespace stickslip
