// simParamsFromOptions (core/run_options.hpp): the run options of every front end.
#include <QtTest>

#include "core/presets.hpp"
#include "core/run_options.hpp"

using namespace stickslip;

class TstRunOptions : public QObject {
    Q_OBJECT
private slots:
    void presetThenSetsThenFlags() {
        SimOptions o;
        o.preset = "fig20";
        o.model = "coulomb";
        o.sets = {"A=0.4mm", "tN = 7", "cycles=9"};
        o.cycles = std::string("5");  // not = "5": GCC 12 -O2 warns falsely there (-Wstringop-overflow)
        o.dt = "20us";
        SimParams p;
        std::string err;
        QVERIFY2(simParamsFromOptions(o, p, &err), err.c_str());
        QVERIFY(p.law == LawKind::Coulomb);
        QCOMPARE(p.drive.amplitude_m, 0.4e-3);
        QCOMPARE(p.rig.normalForce_N, 7.0);
        QCOMPARE(p.cycles, 5.0);  // the flag wins over the earlier --set
        QCOMPARE(p.integration.dt_s, 20e-6);
        Preset fig20;
        QVERIFY(findPreset("fig20", fig20));
        QCOMPARE(p.drive.frequency_Hz, fig20.params.drive.frequency_Hz);
    }

    void errorsNameKeyValueAndRange() {
        SimParams p;
        std::string err;
        SimOptions o;
        o.preset = "nope";
        QVERIFY(!simParamsFromOptions(o, p, &err));
        QVERIFY(err.find("unknown preset 'nope'") != std::string::npos);
        QVERIFY(err.find("fig20") != std::string::npos);
        o = SimOptions{};
        o.sets = {"bogus=1"};
        QVERIFY(!simParamsFromOptions(o, p, &err));
        QVERIFY(err.find("unknown parameter 'bogus'") != std::string::npos);
        o = SimOptions{};
        o.sets = {"tN=-1"};
        QVERIFY(!simParamsFromOptions(o, p, &err));
        QVERIFY2(err.find("tN = -1") != std::string::npos && err.find("must be") != std::string::npos, err.c_str());
        o = SimOptions{};
        o.setup = "sideways";
        QVERIFY(!simParamsFromOptions(o, p, &err));
        QVERIFY(err.find("dynamics, prescribed") != std::string::npos);
    }

    // --max-steps sets the per-run step budget: a whole number >= 1, named in the error.
    void maxStepsOption() {
        SimParams p;
        std::string err;
        SimOptions o;
        QVERIFY2(simParamsFromOptions(o, p, &err), err.c_str());
        QCOMPARE(p.integration.maxSteps, SimParams{}.integration.maxSteps);
        o.maxSteps = "5000";
        QVERIFY2(simParamsFromOptions(o, p, &err), err.c_str());
        QCOMPARE(p.integration.maxSteps, 5000L);
        o.maxSteps = "1e12";
        QVERIFY2(simParamsFromOptions(o, p, &err), err.c_str());
        QCOMPARE(p.integration.maxSteps, 1000000000000L);
        for (const char* bad : {"0", "-3", "2.5", "abc", "1e30", "nan", "10 steps"}) {
            o.maxSteps = bad;
            QVERIFY2(!simParamsFromOptions(o, p, &err), bad);
            QVERIFY2(err.find(std::string("--max-steps '") + bad + "'") != std::string::npos, err.c_str());
            QVERIFY2(err.find("whole number in [1, 1e+18]") != std::string::npos, err.c_str());
        }
    }

    void parseAssignmentSplits() {
        std::string key;
        double v = 0;
        std::string err;
        QVERIFY(parseAssignment(" Dc = 20um", key, v, &err));
        QCOMPARE(key, std::string("Dc"));
        QVERIFY(std::abs(v - 20e-6) < 1e-18);
        QVERIFY(!parseAssignment("Dc", key, v, &err));
        QVERIFY(presetNames().find("default") == 0);
    }
};

QTEST_GUILESS_MAIN(TstRunOptions)
#include "tst_run_options.moc"
