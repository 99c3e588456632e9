// The adaptive stepper's calibrated constants (adaptive.cpp), each with the measurement that set
// it; docs/adaptive.md has the sessions' figures. Internal to the stepper.
#pragma once

namespace stickslip::adaptive_calibration {

// Step-size grid h_k = h_max 2^(−k/4): changing h moves k, so the constants of every size in
// use are computed once per run (law.prepare depends on h through η t_N/h and C2/(D_c h)).
inline constexpr int kLevels = 148;

// Error per unit step: the local estimate of a step of length h may use tol·scale·kPerPeriod·h/T,
// so that local errors summed over a run stay proportional to the tolerance instead of to the
// number of steps. kPerPeriod is a calibration constant (see docs/adaptive.md: the estimate is
// that of the unextrapolated two-half-step result, larger than the error of what is kept).
inline constexpr double kPerPeriod = 1.0;
// Stuck throughout, the kept value (4 y₂ − y₁)/3 is fourth order while the estimate is that of
// the second-order y₂: stuck steps may use 10× the allowance. Calibrated (bench_core set, TOL
// 1e-2 … 1e-5): a third of the stuck steps, error/TOL still 0.5–1.8 (rate-state to 1e-4) and
// 0.7–1.8 (Coulomb); 100× overshoots TOL up to 17×.
inline constexpr double kStuckAllowance = 10.0;
// TR-BDF2 slip steps are judged by an estimate of the error of what is kept, the extrapolated
// (4y₂ − y₁)/3, not of y₂ (ratio()): two third-order values of the step are at hand, that
// extrapolation and the TR-X companion ŷ₁ of the one step h (Hosea & Shampine; trbdf2.hpp's
// TrError is ŷ₁ − y₁, formed from stage derivatives the step already has), and their difference
// is the kept value's error estimate. Until session 25 the estimate was that of
// y₂ with a credit of 3–4× the allowance: on the bench set (ε_T = 1e6) the error did not move for
// credits 1 … 64, on the app's Fig. 20 preset (ε_T = 1.1e4) it grew in proportion (2.91 TOL at
// TOL 1e-4 with 4; docs/adaptive.md, session 26).
//
// Velocity errors of slip steps count as displacement errors over the time a velocity error acts
// before the rig's ringing turns it round, 1/ω_n (ω_n = √(k/m), at least the forcing frequency),
// not over one step: on the preset the slider rings while it slides and those errors were what
// the per-step weight h missed. Such an estimate cannot fall below the round-off of a stage
// velocity, which TR-BDF2 forms as a difference quotient (x − x*)/d over the stage length
// d = γh/2: the floor is kRoundoffUlps·ε·|x|/d. Measured at the smallest steps (h = 1.6e-10 s,
// bench set, TOL 1e-5, no floor): the estimate's velocity part sits at 4–32 ε|x|/d there, and
// the steps after a slip onset shrank to that size chasing it (10 M steps, 4 000 TOL off); with
// 2.9 ε|x|/d as the floor they still did, with 32 they do not (session 26).
inline constexpr double kRoundoffUlps = 32.0;
// Slip steps judged by TR-BDF2's embedded estimate (AdaptiveOptions::embeddedSlip): the estimate
// is that of the kept value, so the allowance is the plain one.
inline constexpr double kEmbeddedAllowance = 1.0;
// Largest difference of α between the one-step and the two-half-step results of an accepted
// step, in units of the law's α scale (r of K1(α) = C1 (exp(α/r) − 1)): 10 % in the strength's
// exponent. A resolution guard (ratio() below), not part of the tolerance.
inline constexpr double kAlphaResolution = 0.1;

// Velocity weight of the extrapolation in viscoplastic slip (rate-state law). The overstress
// relaxes in τ_r = η t_N/ε_T (4 µs at the paper's ε_T = 1e6), so for h ≫ τ_r backward Euler
// gives F_{n+1} ≈ t_N(μ + K1) + η t_N Δλ/h: the viscous force at the step's mean slip rate, an
// O(h) error −η t_N V̇ h/2 in the end-point equilibrium, i.e. in ẍ_{n+1}. Newmark carries ẍ as
// state and the extrapolated start is free of that lag, so the local error of ẋ is −K h²/4 for
// one step and −3K h²/16 for two half steps (K = η t_N V̇/m): not in the ratio 2 that
// 2y₂ − y₁ assumes. y₂ + 3(y₂ − y₁) cancels it. Measured (docs/adaptive.md): error/TOL 1.0–1.9
// over TOL 1e-2 … 1e-5 on the 1 mm set (was 0.2–5.5) and 0.9–1.5 on the 0.4 mm / ε_T = 1.1e4
// set, same step counts; Coulomb has no viscous term and keeps 1.
inline constexpr double kViscousVelocityWeight = 3.0;

// Slip → stick location (locate()): the first trial step runs this fraction past the stop
// guessed from the attempted step, so that it contains the stop although the guess, read off a
// step that crossed it, is only approximate.
inline constexpr double kStopOvershoot = 0.02;
// Share of the tolerance given to the dense output of a closed-form stuck step (stuck_flow.hpp):
// the step is exact, so its length is set by the cubic Hermite interpolant between its ends.
inline constexpr double kHermiteShare = 0.25;
// Sub-intervals on which a closed-form stuck step is checked for a slip onset when the bound
// over the whole step cannot exclude one.
inline constexpr int kStuckChecks = 8;

// locate()'s answer for a switch that the step may contain (judged by the error control alone).
inline constexpr double kSwitchInside = -2.0;

}  // namespace stickslip::adaptive_calibration
