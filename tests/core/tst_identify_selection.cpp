// Selection tests of the identify loop (identify_selection.cpp) on hand-made error tables, and
// the warm-start clamp of the fit parameters (identify_fit.cpp).
#include <QtTest/QtTest>

#include <cmath>
#include <limits>

#include "core/identify/identify_internal.hpp"

using namespace stickslip::identify;
using namespace stickslip::identify::detail;

namespace {

ModelErrors errors(const std::vector<double>& heldOut) {
    ModelErrors e;
    double ss = 0;
    for (double v : heldOut) {
        RunError r;
        r.heldOutNrmse = v;
        e.runs.push_back(r);
        ss += v * v;
    }
    e.validationNrmse = std::sqrt(ss / static_cast<double>(heldOut.size()));
    return e;
}

// The selection of one candidate of five held-out runs under the default options.
bool select(CandidateScore& sc, const ModelErrors& ref, const ModelErrors& with) {
    static const IdentifyOptions opt;
    Context cx;
    cx.opt = &opt;
    return passesSelection(cx, sc, FitOutcome{}, ref, with, {}, {0, 1, 2, 3, 4}, 1.0);
}

}  // namespace

class TestIdentifySelection : public QObject {
    Q_OBJECT
private slots:
    // D16 (session 6): every leave-one-run-out refit of a candidate failed, its held-out error
    // was NaN, and the NaN slipped past the held-out comparison: the candidate was added.
    void noHeldOutErrorIsNoEvidence() {
        CandidateScore sc;
        sc.name = "stick_healing";
        const ModelErrors ref = errors({0.1, 0.1, 0.1, 0.1, 0.1});
        ModelErrors with = errors({0.05, 0.05, 0.05, 0.05, 0.05});
        with.validationNrmse = std::numeric_limits<double>::quiet_NaN();
        for (RunError& r : with.runs) r.heldOutNrmse = 0.0;
        QVERIFY(!select(sc, ref, with));
        QVERIFY2(sc.reason.find("no held-out error") != std::string::npos, sc.reason.c_str());
    }

    // Five runs that all improve by very different amounts (D03's lag): the exact sign-flip
    // test decides (p = 1/32), and the pooled and paired held-out tests pass.
    void heterogeneousGainsPassTheExactTest() {
        CandidateScore sc;
        sc.name = "frictional_lag";
        const ModelErrors ref = errors({0.10, 0.10, 0.10, 0.10, 0.10});
        const ModelErrors with = errors({0.10 * std::exp(-0.39 / 2), 0.10 * std::exp(-0.11 / 2), 0.10 * std::exp(-0.08 / 2),
                                         0.10 * std::exp(-1.39 / 2), 0.10 * std::exp(-0.08 / 2)});
        select(sc, ref, with);
        QVERIFY(sc.heldOutExact);
        QVERIFY2(std::abs(sc.heldOutP - 1.0 / 32.0) < 1e-12, qPrintable(QString::number(sc.heldOutP)));
        QCOMPARE(sc.heldOutUnits, 5);
        // One of the five worse: the exact test does not pass.
        CandidateScore sc2;
        sc2.name = "frictional_lag";
        const ModelErrors mixed = errors({0.09, 0.09, 0.09, 0.09, 0.11});
        QVERIFY(!select(sc2, ref, mixed));
        QVERIFY(sc2.heldOutP > 0.05);
    }
};

QTEST_APPLESS_MAIN(TestIdentifySelection)
#include "tst_identify_selection.moc"
