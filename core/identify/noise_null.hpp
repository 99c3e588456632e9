// A null distribution made from the data at hand (issue 14): how much would a candidate effect
// lower the residual sum of squares if the data were the current model plus noise of the level
// and colour the current residual has? The selection accepts a candidate only when its real gain
// exceeds the (1 − α) quantile of that distribution, instead of a fixed margin.
//
// Noise: per residual block (one channel of one run), an AR(1) process e_k = φ e_{k−1} + s w_k
// fitted to the block's residual on the samples it compares (Yule–Walker lag-1), so that a
// residual whose samples are correlated (a 100 Hz low-pass at 250 Hz, or structure the model
// misses) makes a wider null: a conservative choice, structure is counted as noise.
// Gain: in the linearised model around the current fit, the gain of a candidate with extra
// Jacobian columns J_c on a replica e is ‖P⊥ e‖², P⊥ the projection onto the part of span(J_c)
// orthogonal to the current model's columns J_0 (the current parameters refitted too).
// Numerics: the replicas may carry a fixed offset d besides the noise, the part of the current
// residual that the prediction's own discretisation makes (the residual at the loop's samples and
// law steps minus the best-fit residual of the same model predicted at the recorded rate,
// identify_internal.hpp's numericsOffset): a candidate that absorbs the model's numerical error
// gains ‖Qcᵀ(e + d)‖² from data the current model explains exactly.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Dense>

namespace stickslip::identify {

// One block of the residual vector [offset, offset + length) with its noise model.
struct NoiseBlock {
    size_t offset = 0, length = 0;
    std::vector<char> used;  // samples compared (size length); the others stay 0 in a replica
    double phi = 0.0;        // AR(1) coefficient, in (−1, 1)
    double sigma = 0.0;      // standard deviation of the process (not of its innovation)
};

// AR(1) fit of r on the used samples (consecutive used pairs for the lag-1 correlation).
// phi is clamped to [−0.99, 0.99]; sigma is the RMS of r over the used samples.
void fitAr1(const std::vector<double>& r, const std::vector<char>& used, double& phi, double& sigma);

// A replica of the noise over `total` residuals: each block an independent stationary AR(1)
// path, zero where not used; blocks that do not cover an entry leave it zero.
std::vector<double> noiseReplica(const std::vector<NoiseBlock>& blocks, size_t total, uint64_t seed);

struct NullGains {
    std::vector<double> gains;  // one per replica, sorted ascending
    int rankExtra = 0;          // columns of J_c independent of J_0 (0: the candidate adds nothing)
    double offsetGain = 0.0;    // ‖Qcᵀ d‖² of the fixed offset alone (0 without one)
    double quantile(double p) const;  // empirical p-quantile (the ceil(p·B)-th smallest)
};

// Orthonormal bases of the linearised refit: Q0 of span(J0) (the current model's columns) and
// Qc of the part of span(Jc) orthogonal to it (rank-revealing QR, relative tolerance 1e-9; Qc
// has no columns when Jc adds nothing). valid is false when the shapes do not match or Jc is
// empty. The gain of the candidate on a residual e is ‖Qcᵀ e‖², the current model's refit
// removes ‖Q0ᵀ e‖².
struct ProjectionBases {
    Eigen::MatrixXd Q0, Qc;
    bool valid = false;
};
ProjectionBases projectionBases(const Eigen::MatrixXd& J0, const Eigen::MatrixXd& Jc);

// Gains ‖P⊥ e_b‖² of `replicas` noise replicas (seeds seed, seed+1, …). J0: n × p (may have
// p = 0), Jc: n × q. Columns that are numerically dependent (relative tolerance 1e-9) add
// nothing.
NullGains projectionGainNull(const Eigen::MatrixXd& J0, const Eigen::MatrixXd& Jc, const std::vector<NoiseBlock>& blocks,
                             int replicas, uint64_t seed);
// The same with the bases already made (rows: the length of the residual vector). `offset`
// (size rows, optional) is added to every replica: e_b + d.
NullGains projectionGainNull(const ProjectionBases& pb, const std::vector<NoiseBlock>& blocks, size_t rows, int replicas,
                             uint64_t seed, const std::vector<double>* offset = nullptr);

// The (p) quantile of the gamma distribution with the mean and variance of `gains` (Satterthwaite's
// scaled χ²): a null made of few replicas, each a full refit, whose gains are a noise part
// (σ² χ²_q in the linearised model) plus a systematic part, both carried by the moment match.
// Negative gains count as 0. Fewer than 2 gains, or gains without spread: their largest (≥ 0).
double momentMatchedGammaQuantile(const std::vector<double>& gains, double p);

}  // namespace stickslip::identify
