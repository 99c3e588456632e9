// The 0–1 test for chaos (Gottwald & Melbourne 2004, 2009, the "modified mean square
// displacement" form) on a sampled series φ(j), j = 1…N (e.g. a Poincaré section):
//   p_c(n) = Σ_{j≤n} φ(j) cos(j c),  q_c(n) = Σ_{j≤n} φ(j) sin(j c),
//   M_c(n) = mean_j [(p_c(j+n) − p_c(j))² + (q_c(j+n) − q_c(j))²],   n ≤ N/10,
//   D_c(n) = M_c(n) − (mean φ)² (1 − cos n c) / (1 − cos c),
//   K_c    = corr(n, D_c(n)),     K = median over c ∈ (π/5, 4π/5).
// K ≈ 1: chaotic; K ≈ 0: regular. Long mode-locked orbits on a short series can fool it:
// confirm with the Lyapunov exponent.
#pragma once

#include <string>
#include <vector>

namespace stickslip {

struct ZeroOneOptions {
    int nc = 100;                        // number of c values (deterministic, low-discrepancy in (cMin, cMax))
    double cMin = 0.6283185307179586;    // π/5
    double cMax = 2.5132741228718345;    // 4π/5
    int nCutDivisor = 10;                // n ≤ N / nCutDivisor
    // A series whose range is ≤ constantTol × max|φ| is a fixed point (period-1 section):
    // K = 0 by definition (its rounding noise would otherwise look like diffusion).
    double constantTol = 1e-8;
};

struct ZeroOneResult {
    double K = 0;                 // median of K_c
    std::vector<double> c, Kc;    // per c
    bool ok = false;
    std::string message;          // why not ok (too short, constant series, non-finite values)
};

ZeroOneResult zeroOneTest(const std::vector<double>& series, const ZeroOneOptions& opt = {});

}  // namespace stickslip
