// The first-root search of the return maps' slip solve (core/friction/slip_first_root.hpp):
// its slope bounds hold (sampled R' inside them), and on residuals with three roots it returns
// the first one, where a dense scan of R finds it; on residuals with one root it agrees with
// the ordinary solve; solveSlipFirstRoot, the laws' entry, keeps the ordinary solve's result
// where it is the first root.
#include <QtTest>

#include <cmath>
#include <random>

#include "core/friction/slip_first_root.hpp"

using namespace stickslip;

namespace {

// R(x) = a − k x − y0 − P r (exp(α(x)/r) − 1) and its slope, α from the shape's state step.
struct Residual {
    SlipShape s;
    double a = 0, y0 = 0;
    double alpha(double x, double& dalpha) const {
        const double Dc = 1.0 / s.invDc, y = x * s.invDc;
        if (s.constantRate) {
            const double E = std::exp(-y);
            dalpha = -s.c * (1.0 - E) - (s.alpha0 + s.c * x) * E / Dc;
            return (s.alpha0 + s.c * x) * E - s.c * x;
        }
        const double al = (s.alpha0 - s.c * Dc * y * y) / (1.0 + y);
        dalpha = (-2.0 * s.c * y - al / Dc) / (1.0 + y);
        return al;
    }
    void operator()(double x, double& R, double& dR) const {
        double da = 0;
        const double al = alpha(x, da), e = std::exp(al * s.invR), r = 1.0 / s.invR;
        R = a - s.k * x - y0 - s.P * r * (e - 1.0);
        dR = -s.k - s.P * e * da;
    }
};

Residual randomResidual(std::mt19937_64& rng, bool constantRate) {
    std::uniform_real_distribution<double> u(0.0, 1.0);
    Residual q;
    q.s.constantRate = constantRate;
    q.s.invDc = 1.0 / std::pow(10.0, -7.5 + 3.5 * u(rng));    // D_c 3e-8 … 1e-4 m
    q.s.c = std::pow(10.0, 2.0 + 3.0 * u(rng));                // C2/Δt 1e2 … 1e5 1/m
    q.s.invR = 1.0 / (0.3 + 1.7 * u(rng));
    q.s.alpha0 = -0.5 + 0.7 * u(rng);
    q.s.k = std::pow(10.0, 2.0 + 3.0 * u(rng));                // ε + η t_N/Δt
    q.s.P = std::pow(10.0, -1.0 + 2.0 * u(rng)) * q.s.invR;    // t_N C1 / r
    q.y0 = q.s.P / q.s.invR * (1.0 + u(rng));  // t_N μ ≥ t_N C1, so |F_tr| = a > 0
    return q;
}

}  // namespace

class TstSlipFirstRoot : public QObject {
    Q_OBJECT
private slots:
    // slopeFromRanges: the interval product −k − P e α' over every corner, for either sign of P
    // and of α' (against a grid of e and α').
    void slopeFromRangesCoversEveryCorner() {
        for (const double P : {2.0, -3.0, 0.0}) {
            SlipShape s;
            s.P = P, s.k = 10.0;
            const double e1 = 0.5, e2 = 2.0, d1 = -4.0, d2 = 7.0;
            const SlopeRange r = slopeFromRanges(s, e1, e2, d1, d2);
            double lo = 1e300, hi = -1e300;
            for (int i = 0; i <= 10; ++i)
                for (int j = 0; j <= 10; ++j) {
                    const double v = -s.k - P * (e1 + (e2 - e1) * i / 10.0) * (d1 + (d2 - d1) * j / 10.0);
                    lo = std::min(lo, v), hi = std::max(hi, v);
                }
            QCOMPARE(r.min, lo);  // the extremes are at corners, which the grid contains
            QCOMPARE(r.max, hi);
        }
    }
    // slopeRangeOn and slopeRangeEverywhere bound R' at every sampled point of their interval.
    void slopeBoundsHold() {
        std::mt19937_64 rng(11);
        std::uniform_real_distribution<double> u(0.0, 1.0);
        long checked = 0;
        for (int trial = 0; trial < 4000; ++trial) {
            const Residual q = randomResidual(rng, trial % 2 == 0);
            const double Dc = 1.0 / q.s.invDc;
            const double l = Dc * std::pow(10.0, -3.0 + 5.0 * u(rng)) * (trial % 5 == 0 ? 0.0 : 1.0);
            const double h = l + Dc * std::pow(10.0, -3.0 + 5.0 * u(rng));
            const SlopeRange on = slopeRangeOn(q.s, l, h);
            const SlopeRange all = slopeRangeEverywhere(q.s, std::exp(q.s.alpha0 * q.s.invR));
            for (int i = 0; i <= 20; ++i) {
                const double x = l + (h - l) * i / 20.0;
                double R = 0, dR = 0;
                q(x, R, dR);
                const double tol = 1e-9 * (std::abs(dR) + q.s.k);
                QVERIFY2(dR >= on.min - tol && dR <= on.max + tol,
                         qPrintable(QString("R'=%1 outside [%2, %3] on [%4, %5]").arg(dR).arg(on.min).arg(on.max).arg(l).arg(h)));
                QVERIFY2(dR >= all.min - tol && dR <= all.max + tol,
                         qPrintable(QString("R'=%1 outside global [%2, %3]").arg(dR).arg(all.min).arg(all.max)));
                ++checked;
            }
        }
        qInfo("%ld points checked", checked);
    }
    // On random residuals (R(0) > 0, R(hi) < 0) the search returns a root with no sign change
    // of R before it on a dense grid; where the residual has one root it is the ordinary solve's.
    void returnsTheFirstRoot() {
        std::mt19937_64 rng(5);
        std::uniform_real_distribution<double> u(0.0, 1.0);
        int multiple = 0, single = 0, predictorMisses = 0, ordinaryIsFirst = 0, keptBitForBit = 0;
        long evaluations = 0;
        for (int trial = 0; trial < 3000; ++trial) {
            Residual q = randomResidual(rng, trial % 2 == 1);
            const double r = 1.0 / q.s.invR, e0 = std::exp(q.s.alpha0 * q.s.invR);
            // Trial force just above the strength: Φ_tr = a − y0 − P r (e0 − 1) > 0, small.
            const double phi = (0.001 + 0.2 * u(rng)) * q.s.P * r;
            q.a = phi + q.y0 + q.s.P * r * (e0 - 1.0);
            const double hi = (q.a - q.y0 + q.s.P * r) / q.s.k;  // R(hi) ≤ 0 since exp(α/r) ≥ 0
            double R0 = 0, dR0 = 0;
            q(0.0, R0, dR0);
            double Rhi = 0, dRhi = 0;
            q(hi, Rhi, dRhi);
            if (!(R0 > 0.0 && Rhi <= 0.0)) continue;
            const double ftol = 1e-13 * (q.a + 1.0);
            const SlipRoot f = solveFirstSlip(q, q.s, R0, dR0, 0.0, hi, ftol);
            // The laws' entry: the same first root; bit for bit the ordinary solve where that is it.
            const double hint = phi / q.s.k;
            const SlipRoot g = solveSlipFirstRoot(q, q.s, e0, R0, dR0, hi, hint, ftol);
            const SlipRoot ordinary = solveSlip(q, 0.0, R0, dR0, 0.0, hi, hint, ftol);
            QVERIFY(g.converged);
            QVERIFY2(std::abs(g.x - f.x) <= 1e-9 * f.x + 1e-12 * hi, qPrintable(QString("%1 vs %2").arg(g.x).arg(f.x)));
            if (slopeRangeOn(q.s, 0.0, ordinary.x).max < 0.0) {  // certainly the first root: kept as it is
                QVERIFY(g.x == ordinary.x && g.R == ordinary.R && g.iterations == ordinary.iterations);
                ++keptBitForBit;
            }
            if (std::abs(ordinary.x - f.x) <= 1e-9 * f.x + 1e-12 * hi) ++ordinaryIsFirst;
            QVERIFY(f.converged);
            QVERIFY2(std::abs(f.R) <= 1e-9 * (q.a + q.s.k * f.x) || f.R <= 0.0, qPrintable(QString::number(f.R)));
            // No root before f.x: R > 0 on a dense grid below it (to the grid's resolution).
            int changes = 0;
            for (int i = 1; i < 20000; ++i) {
                const double x = f.x * i / 20000.0;
                double R = 0, dR = 0;
                q(x, R, dR);
                if (R < -1e-9 * (q.a + q.s.k * x)) {
                    QFAIL(qPrintable(QString("R(%1) = %2 < 0 before the root %3 returned").arg(x).arg(R).arg(f.x)));
                }
            }
            // Scan past it: how many sign changes R has on [0, hi] tells the kind of residual.
            double prev = R0;
            for (int i = 1; i <= 20000; ++i) {
                const double x = hi * i / 20000.0;
                double R = 0, dR = 0;
                q(x, R, dR);
                if ((R > 0.0) != (prev > 0.0)) ++changes;
                prev = R;
            }
            // The ordinary solve from the elastic–viscous predictor, as the laws called it before.
            const SlipRoot fromPredictor = solveSlip(q, 0.0, R0, dR0, 0.0, hi, phi / q.s.k, ftol);
            if (fromPredictor.x > f.x * (1.0 + 1e-6) + 1e-15) ++predictorMisses;
            evaluations += f.iterations;
            if (changes > 1) {
                ++multiple;
            } else {
                ++single;
                const SlipRoot n = solveSlip(q, 0.0, R0, dR0, 0.0, hi, 0.0, ftol);
                QVERIFY2(std::abs(n.x - f.x) <= 1e-9 * n.x + 1e-12 * hi,
                         qPrintable(QString("%1 vs %2").arg(n.x).arg(f.x)));
            }
        }
        qInfo("%d residuals with more than one root, %d with one; the solve from the predictor missed the first "
              "root on %d; %.1f evaluations per search",
              multiple, single, predictorMisses, double(evaluations) / (multiple + single));
        QVERIFY(predictorMisses > 0);  // the residuals include the case the search exists for
        qInfo("the ordinary solve's root is the first on %d; certainly so, and kept bit for bit, on %d",
              ordinaryIsFirst, keptBitForBit);
        QVERIFY(keptBitForBit > 0);
        QVERIFY(multiple >= 50);
        QVERIFY(single >= 50);
    }
};

QTEST_APPLESS_MAIN(TstSlipFirstRoot)
#include "tst_slip_first_root.moc"
