// The noise null of the identify selection (noise_null.hpp): AR(1) fit, replicas, and the
// distribution of projection gains against its closed form for white noise.
#include <QtTest/QtTest>

#include <cmath>
#include <random>

#include "core/identify/diagnostics.hpp"
#include "core/identify/noise_null.hpp"

using namespace stickslip::identify;

class TestNoiseNull : public QObject {
    Q_OBJECT
private slots:
    // An AR(1) path with known φ and σ is fitted back; unused samples do not enter.
    void ar1FitRecoversItsParameters() {
        NoiseBlock b;
        b.length = 200000;
        b.used.assign(b.length, 1);
        b.phi = 0.7;
        b.sigma = 0.3;
        const std::vector<double> e = noiseReplica({b}, b.length, 42);
        double phi = 0, sigma = 0;
        fitAr1(e, b.used, phi, sigma);
        QVERIFY2(std::abs(phi - 0.7) < 0.01, qPrintable(QString::number(phi)));
        QVERIFY2(std::abs(sigma - 0.3) < 0.01 * 0.3, qPrintable(QString::number(sigma)));
        // Half the samples masked out: still the same process on the rest.
        std::vector<char> half(b.length, 0);
        for (size_t i = 0; i < half.size(); ++i) half[i] = (i / 1000) % 2 == 0;
        fitAr1(e, half, phi, sigma);
        QVERIFY(std::abs(phi - 0.7) < 0.02);
        QVERIFY(std::abs(sigma - 0.3) < 0.02 * 0.3);
        // No usable pair: φ = 0; nothing used: σ = 0.
        fitAr1({1.0, 2.0}, {1, 0}, phi, sigma);
        QCOMPARE(phi, 0.0);
        fitAr1({1.0, 2.0}, {0, 0}, phi, sigma);
        QCOMPARE(sigma, 0.0);
    }

    // A replica is zero where a block does not compare, reproducible by seed, and different
    // for another seed.
    void replicaRespectsMaskAndSeed() {
        NoiseBlock b;
        b.offset = 3;
        b.length = 5;
        b.used = {1, 0, 1, 1, 0};
        b.sigma = 1.0;
        const std::vector<double> e = noiseReplica({b}, 10, 7);
        QCOMPARE(e.size(), size_t(10));
        for (size_t i : {0, 1, 2, 4, 7, 8, 9}) QCOMPARE(e[i], 0.0);
        QVERIFY(e[3] != 0.0 && e[5] != 0.0 && e[6] != 0.0);
        QCOMPARE(noiseReplica({b}, 10, 7), e);
        QVERIFY(noiseReplica({b}, 10, 8) != e);
    }

    // White noise of variance σ² and q extra independent columns: the gain is σ² χ²_q, so its
    // 95 % quantile is σ² · 3.841 (q = 1) and σ² · 5.991 (q = 2); columns already in J_0 add
    // nothing (rank 0, all gains 0).
    void whiteNoiseGainIsChiSquare() {
        const Eigen::Index n = 2000;
        std::mt19937 rng(3);
        std::normal_distribution<double> nd(0.0, 1.0);
        Eigen::MatrixXd J0(n, 2), Jc(n, 2);
        for (Eigen::Index i = 0; i < n; ++i) {
            J0(i, 0) = 1.0;
            J0(i, 1) = std::sin(0.01 * static_cast<double>(i));
            Jc(i, 0) = nd(rng);
            Jc(i, 1) = nd(rng);
        }
        NoiseBlock b;
        b.length = static_cast<size_t>(n);
        b.used.assign(b.length, 1);
        b.sigma = 0.5;
        const NullGains one = projectionGainNull(J0, Jc.leftCols(1), {b}, 4000, 11);
        QCOMPARE(one.rankExtra, 1);
        QCOMPARE(one.gains.size(), size_t(4000));
        QVERIFY2(std::abs(one.quantile(0.95) / (0.25 * 3.841) - 1.0) < 0.08, qPrintable(QString::number(one.quantile(0.95))));
        const NullGains two = projectionGainNull(J0, Jc, {b}, 4000, 11);
        QCOMPARE(two.rankExtra, 2);
        QVERIFY2(std::abs(two.quantile(0.95) / (0.25 * 5.991) - 1.0) < 0.08, qPrintable(QString::number(two.quantile(0.95))));
        // A column that is a combination of J_0's adds nothing.
        const NullGains none = projectionGainNull(J0, (2.0 * J0.col(0) - J0.col(1)).eval(), {b}, 50, 11);
        QCOMPARE(none.rankExtra, 0);
        QCOMPARE(none.quantile(0.95), 0.0);
        // Coloured noise of the same variance makes the null of a slowly varying column wider.
        NoiseBlock red = b;
        red.phi = 0.95;
        Eigen::MatrixXd slow(n, 1);
        for (Eigen::Index i = 0; i < n; ++i) slow(i, 0) = std::cos(0.003 * static_cast<double>(i));
        const double whiteQ = projectionGainNull(J0, slow, {b}, 2000, 5).quantile(0.95);
        const double redQ = projectionGainNull(J0, slow, {red}, 2000, 5).quantile(0.95);
        QVERIFY2(redQ > 5.0 * whiteQ, qPrintable(QString("%1 vs %2").arg(redQ).arg(whiteQ)));
    }

    // A fixed offset d in every replica (the residual's numerical part): its own gain is
    // ‖Qcᵀ d‖², the replicas' gains are those of e + d; a d that J_c cannot absorb (in span(J_0)
    // or orthogonal to both) changes nothing, a d along J_c's new direction moves the quantile
    // to about (‖Qcᵀd‖ + 1.645 σ)² for one column.
    void offsetIsCarriedByEveryReplica() {
        const Eigen::Index n = 1000;
        Eigen::MatrixXd J0(n, 1), Jc(n, 1);
        std::vector<double> inJ0(static_cast<size_t>(n)), along(static_cast<size_t>(n));
        for (Eigen::Index i = 0; i < n; ++i) {
            J0(i, 0) = 1.0;
            Jc(i, 0) = std::sin(0.05 * static_cast<double>(i));
            inJ0[static_cast<size_t>(i)] = 3.0;
            along[static_cast<size_t>(i)] = 0.2 * Jc(i, 0);
        }
        NoiseBlock b;
        b.length = static_cast<size_t>(n);
        b.used.assign(b.length, 1);
        b.sigma = 0.1;
        const ProjectionBases pb = projectionBases(J0, Jc);
        const NullGains plain = projectionGainNull(pb, {b}, static_cast<size_t>(n), 2000, 3);
        const NullGains flat = projectionGainNull(pb, {b}, static_cast<size_t>(n), 2000, 3, &inJ0);
        QCOMPARE(plain.offsetGain, 0.0);
        QVERIFY(flat.offsetGain < 1e-18);
        QVERIFY(std::abs(flat.quantile(0.95) - plain.quantile(0.95)) < 1e-12);
        const NullGains shifted = projectionGainNull(pb, {b}, static_cast<size_t>(n), 2000, 3, &along);
        const double dNorm2 = 0.04 * Jc.squaredNorm();  // d lies along J_c (orthogonal to J_0 up to the mean)
        QVERIFY2(std::abs(shifted.offsetGain / dNorm2 - 1.0) < 0.01, qPrintable(QString::number(shifted.offsetGain)));
        const double expect = std::pow(std::sqrt(shifted.offsetGain) + 1.645 * b.sigma, 2.0);
        QVERIFY2(std::abs(shifted.quantile(0.95) / expect - 1.0) < 0.05,
                 qPrintable(QString("%1 vs %2").arg(shifted.quantile(0.95)).arg(expect)));
        QVERIFY(shifted.quantile(0.95) > 10.0 * plain.quantile(0.95));
        // An offset of the wrong length is refused (no gains), not read past its end.
        const std::vector<double> shortOffset(10, 1.0);
        QVERIFY(projectionGainNull(pb, {b}, static_cast<size_t>(n), 20, 3, &shortOffset).gains.empty());
    }

    // The bases of the linearised refit: Q0 orthonormal over span(J0), Qc orthonormal and
    // orthogonal to it, spanning what J_c adds; a column that J0 already has adds nothing.
    void projectionBasesSplitTheSpans() {
        std::mt19937_64 rng(7);
        std::normal_distribution<double> nd;
        const int n = 400;
        Eigen::MatrixXd J0(n, 2), Jc(n, 2);
        for (int i = 0; i < n; ++i) {
            J0(i, 0) = nd(rng);
            J0(i, 1) = nd(rng);
            Jc(i, 0) = nd(rng);
            Jc(i, 1) = 2.0 * J0(i, 0) - J0(i, 1);  // inside span(J0)
        }
        const ProjectionBases pb = projectionBases(J0, Jc);
        QVERIFY(pb.valid);
        QCOMPARE(pb.Q0.cols(), Eigen::Index(2));
        QCOMPARE(pb.Qc.cols(), Eigen::Index(1));
        QVERIFY((pb.Q0.transpose() * pb.Q0 - Eigen::MatrixXd::Identity(2, 2)).norm() < 1e-12);
        QVERIFY((pb.Qc.transpose() * pb.Qc - Eigen::MatrixXd::Identity(1, 1)).norm() < 1e-12);
        QVERIFY((pb.Q0.transpose() * pb.Qc).norm() < 1e-12);
        // Q0 spans J0: J0 is reproduced by its projection.
        QVERIFY((pb.Q0 * (pb.Q0.transpose() * J0) - J0).norm() < 1e-10 * J0.norm());
        // The gain of Jc's first column is its part orthogonal to J0.
        const Eigen::VectorXd e = Jc.col(0);
        const Eigen::VectorXd perp = e - pb.Q0 * (pb.Q0.transpose() * e);
        QVERIFY(std::abs((pb.Qc.transpose() * e).squaredNorm() - perp.squaredNorm()) < 1e-10 * e.squaredNorm());
        // Only dependent columns: nothing extra; mismatched shapes: invalid.
        QCOMPARE(projectionBases(J0, J0.col(1)).Qc.cols(), Eigen::Index(0));
        QVERIFY(!projectionBases(J0, Eigen::MatrixXd(n + 1, 1)).valid);
        QVERIFY(!projectionBases(J0, Eigen::MatrixXd(n, 0)).valid);
        // No current columns: Q0 is empty and Qc spans Jc.
        const ProjectionBases alone = projectionBases(Eigen::MatrixXd(n, 0), J0);
        QVERIFY(alone.valid);
        QCOMPARE(alone.Q0.cols(), Eigen::Index(0));
        QCOMPARE(alone.Qc.cols(), Eigen::Index(2));
    }
    void momentMatchedGammaQuantileOfReplicaGains() {
        // Many draws of 0.3 χ²_2: the matched gamma's 95 % point is that of 0.3 χ²_2 (5.99 × 0.3).
        std::mt19937_64 rng(3);
        std::chi_squared_distribution<double> chi(2.0);
        std::vector<double> g(20000);
        for (double& v : g) v = 0.3 * chi(rng);
        QVERIFY(std::abs(momentMatchedGammaQuantile(g, 0.95) / (0.3 * 5.991464547107979) - 1.0) < 0.03);
        // Few replicas: finite and above their mean; negatives count as 0; no spread: the largest.
        const std::vector<double> few{0.2, 0.5, 0.1, 0.9, 0.3, 0.4, 0.25, 0.6};
        QVERIFY(momentMatchedGammaQuantile(few, 0.95) > 0.7 && momentMatchedGammaQuantile(few, 0.95) < 2.0);
        QCOMPARE(momentMatchedGammaQuantile({-1.0, -2.0}, 0.95), 0.0);
        QCOMPARE(momentMatchedGammaQuantile({0.4, 0.4, 0.4}, 0.95), 0.4);
        QCOMPARE(momentMatchedGammaQuantile({0.7}, 0.95), 0.7);
        QCOMPARE(momentMatchedGammaQuantile({}, 0.95), 0.0);
    }

    void quantileOfEmptyAndEdges() {
        NullGains g;
        QCOMPARE(g.quantile(0.95), 0.0);
        g.gains = {1, 2, 3, 4};
        QCOMPARE(g.quantile(0.0), 1.0);
        QCOMPARE(g.quantile(0.5), 2.0);
        QCOMPARE(g.quantile(0.95), 4.0);
        QCOMPARE(g.quantile(1.0), 4.0);
    }
};

QTEST_APPLESS_MAIN(TestNoiseNull)
#include "tst_noise_null.moc"
