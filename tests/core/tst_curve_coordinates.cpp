// The steady-state curve's coordinates (core/identify/curve_coordinates.hpp) in the fit engine:
// when they are installed, the map between them and C1, eta, vc both ways, and the covariance
// they carry back.
#include <QtTest>

#include <cmath>
#include <map>

#include "core/identify/curve_coordinates.hpp"
#include "core/identify/fit.hpp"

using namespace stickslip::identify;

namespace {

// mu, C1, eta, vc at a start inside the curve coordinates' ranges (kappa = 24.4, s = -1.50),
// vc free or fixed.
std::vector<FitParameter> curveParams(bool vcFree) {
    std::vector<FitParameter> ps(4);
    const char* names[4] = {"mu", "C1", "eta", "vc"};
    for (int i = 0; i < 4; ++i)
        if (!defaultParameter(names[i], stickslip::SetupKind::Dynamics, ps[static_cast<size_t>(i)])) qFatal("no default for %s", names[i]);
    ps[0].value = 0.27;
    ps[1].value = 0.23;
    ps[2].value = 0.87;
    ps[3].value = 0.097;
    ps[3].free = vcFree;
    return ps;
}

// The law's values at a point z = (mu, kappa, s, vc) of the curve coordinates.
std::map<std::string, double> curveToLaw(const CurveCoordinates& cc, const std::vector<double>& z) {
    std::map<std::string, double> m = {{"mu", z[0]}, {CurveCoordinates::kCurvature, z[1]}, {CurveCoordinates::kSlope, z[2]}, {"vc", z[3]}};
    cc.toLaw(z, m);
    return m;
}

}  // namespace

class TstCurveCoordinates : public QObject {
    Q_OBJECT
private slots:
    // The steady-state-curve coordinates (curve_coordinates.hpp): installed only with C1, eta,
    // vc all free and from a start inside their ranges.
    void curveCoordinatesInstallOnlyFromAStartInside() {
        std::vector<FitParameter> fixedVc = curveParams(false);
        // startInside: κ = 24.4, s = −1.50 inside [1e-6, 1e9] × [−50, 50]; not with v_c fixed,
        // nor where s leaves its range (a start install() would clamp: another start).
        QVERIFY(CurveCoordinates::startInside(curveParams(true)));
        QVERIFY(!CurveCoordinates::startInside(fixedVc));
        std::vector<FitParameter> steep = curveParams(true);
        steep[2].value = 60.0;  // s = 57.6
        QVERIFY(!CurveCoordinates::startInside(steep));
        steep[2].value = 0.87;
        steep[1].value = 0.5;
        steep[3].value = 0.009;  // s = 0.87 − 55.6
        QVERIFY(!CurveCoordinates::startInside(steep));
        std::vector<FitParameter> onBound = curveParams(true);  // C1 on its upper bound: the valley ends there
        onBound[1].value = onBound[1].upper;
        QVERIFY(!CurveCoordinates::startInside(onBound));
        QVERIFY(!CurveCoordinates::install(fixedVc, {}).active());
        QCOMPARE(fixedVc[1].name, std::string("C1"));
        std::vector<FitParameter> scanned = curveParams(true);
        QVERIFY(!CurveCoordinates::install(scanned, {{"eta", {0.5, 1.0}}}).active());
    }

    // kappa = C1/vc^2, s = eta - C1/vc and back; points outside C1's or eta's bounds flagged.
    void curveCoordinatesMapBothWays() {
        std::vector<FitParameter> ps = curveParams(true);
        const CurveCoordinates cc = CurveCoordinates::install(ps, {});
        QVERIFY(cc.active());
        QCOMPARE(ps[1].name, std::string(CurveCoordinates::kCurvature));
        QCOMPARE(ps[2].name, std::string(CurveCoordinates::kSlope));
        QVERIFY(std::abs(ps[1].value - 0.23 / (0.097 * 0.097)) < 1e-9 * ps[1].value);
        QVERIFY(std::abs(ps[2].value - (0.87 - 0.23 / 0.097)) < 1e-12);
        const std::vector<double> z = {ps[0].value, ps[1].value, ps[2].value, ps[3].value};
        const std::map<std::string, double> back = curveToLaw(cc, z);
        QVERIFY(!back.count(CurveCoordinates::kCurvature) && !back.count(CurveCoordinates::kSlope));
        QVERIFY(std::abs(back.at("C1") - 0.23) < 1e-12);
        QVERIFY(std::abs(back.at("eta") - 0.87) < 1e-12);
        QVERIFY(cc.withinLawBounds(back));
        std::vector<double> far = z;
        far[3] = 1.0;  // C1 = kappa * 1 = 24 > 2
        QVERIFY(!cc.withinLawBounds(curveToLaw(cc, far)));
        std::vector<double> neg = z;
        neg[2] = -10.0;  // eta < 0
        QVERIFY(!cc.withinLawBounds(curveToLaw(cc, neg)));
    }

    // The covariance carried back by the delta method, checked against a finite-difference
    // Jacobian of the map.
    void curveCoordinatesCarryTheCovariance() {
        std::vector<FitParameter> ps = curveParams(true);
        const CurveCoordinates cc = CurveCoordinates::install(ps, {});
        QVERIFY(cc.active());
        const std::vector<double> z = {ps[0].value, ps[1].value, ps[2].value, ps[3].value};
        // A fit result in the internal coordinates with a full covariance.
        FitResult fr;
        fr.names = {"mu", CurveCoordinates::kCurvature, CurveCoordinates::kSlope, "vc"};
        fr.freeNames = fr.names;
        fr.values = z;
        fr.free = {true, true, true, true};
        const std::vector<double> se = {1e-3, 2.0, 0.05, 0.01};
        const double R[16] = {1, 0.3, -0.2, 0.1, 0.3, 1, 0.5, 0.6, -0.2, 0.5, 1, 0.4, 0.1, 0.6, 0.4, 1};
        fr.stderrs = se;
        fr.correlation.assign(R, R + 16);
        FitResult restored = fr;
        cc.restore(restored);
        QCOMPARE(restored.names, (std::vector<std::string>{"mu", "C1", "eta", "vc"}));
        QCOMPARE(restored.freeNames, restored.names);
        QVERIFY(std::abs(restored.value("C1") - 0.23) < 1e-12 && std::abs(restored.value("eta") - 0.87) < 1e-12);
        // Expected: G Cov Gt with G by central differences of the map (order mu, C1, eta, vc).
        double G[4][4];
        const char* out[4] = {"mu", "C1", "eta", "vc"};
        for (int j = 0; j < 4; ++j) {
            const double h = 1e-6 * std::max(1.0, std::abs(z[j]));
            std::vector<double> zp = z, zm = z;
            zp[j] += h;
            zm[j] -= h;
            std::map<std::string, double> lp = curveToLaw(cc, zp), lm = curveToLaw(cc, zm);
            for (int i = 0; i < 4; ++i) G[i][j] = (lp.at(out[i]) - lm.at(out[i])) / (2 * h);
        }
        double cov[4][4], want[4][4];
        for (int a = 0; a < 4; ++a)
            for (int b = 0; b < 4; ++b) cov[a][b] = R[a * 4 + b] * se[a] * se[b];
        for (int a = 0; a < 4; ++a)
            for (int b = 0; b < 4; ++b) {
                want[a][b] = 0;
                for (int i = 0; i < 4; ++i)
                    for (int j = 0; j < 4; ++j) want[a][b] += G[a][i] * cov[i][j] * G[b][j];
            }
        for (int a = 0; a < 4; ++a) {
            QVERIFY2(std::abs(restored.stderrs[a] - std::sqrt(want[a][a])) < 1e-6 * std::sqrt(want[a][a]), out[a]);
            for (int b = 0; b < 4; ++b)
                QVERIFY(std::abs(restored.correlation[a * 4 + b] - want[a][b] / std::sqrt(want[a][a] * want[b][b])) < 1e-6);
        }
        QVERIFY(restored.solverSummary.find("steady-state curve") != std::string::npos);
        // Not identifiable (NaN standard errors): C1 and eta get NaN, not a number made of NaN.
        FitResult nan = fr;
        nan.stderrs[1] = std::numeric_limits<double>::quiet_NaN();
        cc.restore(nan);
        QVERIFY(std::isnan(nan.stderrOf("C1")) && std::isnan(nan.stderrOf("eta")));
    }
};

QTEST_GUILESS_MAIN(TstCurveCoordinates)
#include "tst_curve_coordinates.moc"
