// analyticResidualJacobian (identify_jacobian.cpp): the identify residuals' Jacobian from forward
// sensitivities against central differences of residualVector, column by column, with every
// catalogue effect, on prescribed runs made by the project's simulator (identify_synth.hpp) and
// on dynamics runs of a shared synthetic set (both channels); and the fit that uses it reaching
// the optimum the differenced one reaches.
#include <QtTest/QtTest>

#include <cmath>

#include "core/identify/identify_internal.hpp"
#include "identify_synth.hpp"
#include "rig_set_loader.hpp"

using namespace stickslip;
using namespace stickslip::identify;
using namespace stickslip::identify::detail;

namespace {

// The model's parameters (parameters(): the baseline's, the rig's and the effects' at their
// starts) as a map.
std::map<std::string, double> valuesOf(const Context& cx, const Spec& spec, const std::vector<size_t>& idx) {
    std::map<std::string, double> vals;
    for (const FitParameter& p : parameters(cx, spec, baselineStart(cx, idx))) vals[p.name] = p.value;
    return vals;
}

// Largest relative column error ‖J − J_fd‖/‖J_fd‖ over the columns, with its name in `worst`.
void checkAgainstDifferences(const Context& cx, const Spec& spec, const std::vector<size_t>& idx) {
    const std::map<std::string, double> vals = valuesOf(cx, spec, idx);
    std::vector<std::string> names;
    for (const auto& [k, v] : vals) names.push_back(k);
    std::vector<double> r, r0;
    Eigen::MatrixXd J;
    QVERIFY(analyticResidualJacobian(cx, spec, vals, idx, names, J, &r));
    QVERIFY(residualVector(cx, spec, vals, idx, r0));
    QCOMPARE(r.size(), r0.size());
    for (size_t i = 0; i < r.size(); ++i) QCOMPARE(r[i], r0[i]);  // the same runs: the same numbers
    for (size_t j = 0; j < names.size(); ++j) {
        std::map<std::string, double> up = vals, dn = vals;
        const double h = 1e-6 * std::max(std::abs(vals.at(names[j])), 1e-3);
        up[names[j]] += h;
        dn[names[j]] -= h;
        std::vector<double> ru, rd;
        QVERIFY(residualVector(cx, spec, up, idx, ru) && residualVector(cx, spec, dn, idx, rd));
        double num = 0, den = 0, an = 0;
        for (size_t i = 0; i < r0.size(); ++i) {
            const double d = (ru[i] - rd[i]) / (2 * h), a = J(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j));
            num += (a - d) * (a - d);
            den += d * d;
            an += a * a;
        }
        const double rel = std::sqrt(num / std::max(den, 1e-300));
        qInfo("%s: |J| %.3e, |J_fd| %.3e, relative difference %.2e", names[j].c_str(), std::sqrt(an), std::sqrt(den), rel);
        if (den == 0.0) QCOMPARE(an, 0.0);  // a parameter this residual does not see (e.g. m of a prescribed run)
        else QVERIFY2(rel < 1e-4, names[j].c_str());  // seen: at most 5.9e-6 (wear_drift)
    }
}

// The first nRuns runs of D05 (dynamics), cut to `seconds`, prepared as identify prepares them
// (the context points into opt and runs, which the caller keeps).
bool prepareD05(int nRuns, double seconds, const IdentifyOptions& opt, std::vector<IdentifyRun>& runs, Context& cx) {
    runs = rigset::loadRuns(std::string(STICKSLIP_SHARED_DIR) + "/data/synthetic/D05", nRuns, seconds);
    std::string why;
    int dec = 0;
    const bool ok = prepareContext(runs, opt, cx, dec, why);
    if (!ok) qWarning("%s", why.c_str());
    return ok;
}

QStringList catalogue() {
    QStringList out = {""};
    for (const EffectInfo& e : effectCatalogue()) out << QString::fromStdString(e.name);
    return out;
}

}  // namespace

class TestIdentifyJacobian : public QObject {
    Q_OBJECT
private slots:
    void prescribedMatchesDifferences_data() {
        QTest::addColumn<QString>("effect");
        for (const QString& e : catalogue()) QTest::newRow(e.isEmpty() ? "baseline" : qPrintable(e)) << e;
    }
    void prescribedMatchesDifferences() {
        QFETCH(QString, effect);
        IdentifyOptions opt = synth::testOptions();
        opt.freeLaw = {"mu", "C1", "eta", "vc", "Dc", "epsT", "r"};
        std::vector<IdentifyRun> runs = synth::makeRuns(synth::trueModel(), 1.0, 0.02, 1);
        Context cx;
        std::string why;
        int dec = 0;
        QVERIFY2(prepareContext(runs, opt, cx, dec, why), why.c_str());
        Spec spec;
        if (!effect.isEmpty()) spec.effects.push_back(effect.toStdString());
        checkAgainstDifferences(cx, spec, {0, 1, 2, 3});
    }
    void dynamicsMatchesDifferences_data() {
        QTest::addColumn<QString>("effect");
        QTest::addColumn<bool>("stickRig");
        for (const QString& e : catalogue())
            for (bool rig : {false, true}) {
                const QString name = (e.isEmpty() ? QStringLiteral("baseline") : e) + (rig ? "/stick-rig" : "");
                QTest::newRow(qPrintable(name)) << e << rig;
            }
    }
    void dynamicsMatchesDifferences() {
        QFETCH(QString, effect);
        QFETCH(bool, stickRig);
        IdentifyOptions opt;
        opt.stickRigPrediction = stickRig;  // stuck samples' prediction from the equation of motion
        std::vector<IdentifyRun> runs;
        Context cx;
        QVERIFY(prepareD05(2, 2.0, opt, runs, cx));
        QVERIFY(cx.anyDynamics);
        Spec spec;
        if (!effect.isEmpty()) spec.effects.push_back(effect.toStdString());
        checkAgainstDifferences(cx, spec, {0, 1});
    }
    void segmentResidualIsNotCovered() {
        IdentifyOptions opt;
        std::vector<IdentifyRun> runs;
        Context cx;
        QVERIFY(prepareD05(1, 1.0, opt, runs, cx));
        Spec spec;
        spec.segments = true;
        Eigen::MatrixXd J;
        QVERIFY(!analyticResidualJacobian(cx, spec, valuesOf(cx, spec, {0}), {0}, {"mu"}, J));
    }
};

QTEST_GUILESS_MAIN(TestIdentifyJacobian)
#include "tst_identify_jacobian.moc"
