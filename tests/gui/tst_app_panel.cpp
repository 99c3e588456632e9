// The parameter panel (one value per change, log sliders, presets, flagged issues) and the
// session file format. No simulation runs here.
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QSignalSpy>
#include <QSlider>
#include <QTemporaryDir>
#include <QtTest>
#include <cmath>

#include "core/presets.hpp"
#include "model_settings.hpp"
#include "param_specs.hpp"
#include "parameter_panel.hpp"
#include "session.hpp"

using namespace stickslip;
using namespace stickslip::gui;

class TstAppPanel : public QObject {
    Q_OBJECT
private slots:
    void specsCoverEveryKey() {
        // Every SimParams key has a row, and every row a known key.
        for (const auto& k : paramKeys()) QVERIFY2(findSpec(QString::fromStdString(k)), k.c_str());
        for (const auto& s : parameterSpecs()) {
            double v;
            QVERIFY2(getParam(SimParams{}, s.key.toStdString(), v), qPrintable(s.key));
            QVERIFY(s.max > s.min);
        }
        // The issue's decade-spanning ranges are logarithmic.
        for (const char* k : {"eta", "Dc", "vc", "epsT", "k"}) QVERIFY2(findSpec(k)->logScale, k);
    }

    void sliderMappingRoundTrips() {
        const ParamSpec& eta = *findSpec("eta");   // 0.01 … 10 s/m, logarithmic
        QCOMPARE(sliderPosition(eta, eta.min), 0);
        QCOMPARE(sliderPosition(eta, eta.max), kSliderSteps);
        // Half way along a log slider is the geometric mean.
        QVERIFY(std::abs(sliderValue(eta, kSliderSteps / 2) - std::sqrt(eta.min * eta.max)) < 1e-12);
        const ParamSpec& a = *findSpec("A");       // linear
        QVERIFY(std::abs(sliderValue(a, kSliderSteps / 2) - 0.5 * (a.min + a.max)) < 1e-12);
        for (int p : {0, 1, 137, 500, 999, 1000}) {
            QCOMPARE(sliderPosition(eta, sliderValue(eta, p)), p);
            QCOMPARE(sliderPosition(a, sliderValue(a, p)), p);
        }
        // Out of range clamps.
        QCOMPARE(sliderPosition(eta, 1e6), kSliderSteps);
        QCOMPARE(sliderPosition(eta, -1.0), 0);
    }

    void sliderEmitsOneValueInSI() {
        ParameterPanel panel;
        QSignalSpy spy(&panel, &ParameterPanel::paramsChanged);
        panel.slider("A")->setValue(kSliderSteps / 2);   // 5 mm on the 0–10 mm slider
        QCOMPARE(spy.count(), 1);
        const auto s = spy.at(0).at(0).value<ModelSettings>();
        QVERIFY(std::abs(s.params.drive.amplitude_m - 5.0e-3) < 1e-12);
        QVERIFY(std::abs(panel.spinBox("A")->value() - 5.0) < 1e-12);
        // Everything else is still the Fig. 20 set.
        Preset fig20;
        findPreset("fig20", fig20);
        QCOMPARE(s.params.rig.stiffness_N_per_m, fig20.params.rig.stiffness_N_per_m);
        QCOMPARE(s.params.integration.dt_s, fig20.params.integration.dt_s);   // not rounded by its spin box
    }

    void spinBoxMovesLogSlider() {
        ParameterPanel panel;
        QSignalSpy spy(&panel, &ParameterPanel::paramsChanged);
        panel.spinBox("eta")->setValue(0.316);
        QCOMPARE(spy.count(), 1);
        QCOMPARE(panel.settings().params.lawParams<RateStateParams>().eta_s_per_m, 0.316);
        QVERIFY(std::abs(panel.slider("eta")->value() - kSliderSteps / 2) <= 1);
        panel.spinBox("Dc")->setValue(25.0);   // µm
        QVERIFY(std::abs(panel.settings().params.lawParams<RateStateParams>().Dc_m - 25e-6) < 1e-15);
    }

    void modelSelectorDisablesRateStateOnlyFields() {
        ParameterPanel panel;
        QSignalSpy spy(&panel, &ParameterPanel::paramsChanged);
        panel.modelBox()->setCurrentIndex(panel.modelBox()->findData(int(ModelChoice::Coulomb)));
        QCOMPARE(spy.count(), 1);
        QVERIFY(panel.settings().params.law == LawKind::Coulomb);
        QVERIFY(!panel.spinBox("eta")->isEnabled());
        QVERIFY(!panel.slider("Dc")->isEnabled());
        QVERIFY(panel.spinBox("mu")->isEnabled());
        panel.modelBox()->setCurrentIndex(panel.modelBox()->findData(int(ModelChoice::Both)));
        QCOMPARE(panel.settings().laws().size(), size_t(2));
        QVERIFY(panel.settings().params.law == LawKind::RateState);
        QVERIFY(panel.spinBox("eta")->isEnabled());
        panel.setupBox()->setCurrentIndex(panel.setupBox()->findData(int(SetupKind::Prescribed)));
        QVERIFY(panel.settings().params.setup == SetupKind::Prescribed);
    }

    // The stepping choice: one value per change, dt greyed out while error-controlled (the
    // integrator picks its steps), the tolerance reaching the runs only in the dynamics set-up,
    // and kept across preset switches like the model choice. Error-controlled by default.
    void steppingChoiceReachesDynamicsRuns() {
        ParameterPanel panel;
        QComboBox* box = panel.steppingBox();
        QVERIFY(box);
        QCOMPARE(box->currentData().toDouble(), ModelSettings::kDefaultTolerance);
        QCOMPARE(panel.settings().paramsFor(LawKind::RateState).integration.tolerance, ModelSettings::kDefaultTolerance);
        QVERIFY(!panel.spinBox("dt")->isEnabled());
        QSignalSpy spy(&panel, &ParameterPanel::paramsChanged);
        const int f = box->findData(0.0);  // the paper's fixed step
        QVERIFY(f >= 0);
        box->setCurrentIndex(f);
        emit box->activated(f);
        QCOMPARE(spy.count(), 1);
        QCOMPARE(spy.last().first().value<ModelSettings>().paramsFor(LawKind::RateState).integration.tolerance, 0.0);
        QVERIFY(panel.spinBox("dt")->isEnabled());
        spy.clear();
        const int i = box->findData(1e-4);
        QVERIFY(i > 0);
        box->setCurrentIndex(i);
        emit box->activated(i);
        QCOMPARE(spy.count(), 1);
        const ModelSettings s = spy.last().first().value<ModelSettings>();
        QCOMPARE(s.tolerance, 1e-4);
        QCOMPARE(s.paramsFor(LawKind::RateState).integration.tolerance, 1e-4);
        QCOMPARE(s.paramsFor(LawKind::Coulomb).integration.tolerance, 1e-4);
        QVERIFY(!panel.spinBox("dt")->isEnabled());
        QVERIFY(panel.issuesText().isEmpty());
        QVERIFY(panel.loadPreset("fig19"));
        QCOMPARE(panel.settings().tolerance, 1e-4);
        QCOMPARE(box->currentData().toDouble(), 1e-4);
        panel.setupBox()->setCurrentIndex(panel.setupBox()->findData(int(SetupKind::Prescribed)));
        QVERIFY(!box->isEnabled());
        QVERIFY(panel.spinBox("dt")->isEnabled());
        QCOMPARE(panel.settings().paramsFor(LawKind::RateState).integration.tolerance, 0.0);
        QVERIFY2(panel.issuesText().isEmpty(), qPrintable(panel.issuesText()));
    }

    void presetsAndReset() {
        ParameterPanel panel;
        QSignalSpy spy(&panel, &ParameterPanel::paramsChanged);
        QVERIFY(panel.loadPreset("fig19"));
        QCOMPARE(spy.count(), 1);   // one value per preset switch, not one per field
        QCOMPARE(panel.settings().params.rig.stiffness_N_per_m, 3034.0);
        QCOMPARE(panel.spinBox("k")->value(), 3034.0);
        QCOMPARE(panel.settings().preset, QString("fig19"));
        QVERIFY(!panel.loadPreset("no-such-figure"));
        panel.spinBox("k")->setValue(5000.0);
        QCOMPARE(panel.settings().params.rig.stiffness_N_per_m, 5000.0);
        panel.resetToPreset();
        QCOMPARE(panel.settings().params.rig.stiffness_N_per_m, 3034.0);
        QVERIFY(panel.loadPreset("fig16"));
        QVERIFY(panel.settings().params.setup == SetupKind::Prescribed);
        QCOMPARE(panel.setupBox()->currentData().toInt(), int(SetupKind::Prescribed));
    }

    void invalidValuesAreFlaggedWithTheReason() {
        ParameterPanel panel;
        QVERIFY(panel.issuesText().isEmpty());
        ModelSettings bad = panel.settings();
        bad.params.rig.normalForce_N = -1.0;   // e.g. from a hand-edited session
        bad.params.integration.dt_s = 0.1;     // > T/8 at 3 Hz
        panel.setSettings(bad);
        QVERIFY2(panel.issuesText().contains("tN = -1"), qPrintable(panel.issuesText()));
        QVERIFY2(panel.issuesText().contains("dt"), qPrintable(panel.issuesText()));
        QVERIFY(panel.spinBox("tN")->toolTip().contains("must be > 0"));
        QVERIFY(!panel.spinBox("tN")->styleSheet().isEmpty());
        QVERIFY(panel.spinBox("k")->styleSheet().isEmpty());
        panel.loadPreset("fig20");
        QVERIFY(panel.issuesText().isEmpty());
        QVERIFY(panel.spinBox("tN")->styleSheet().isEmpty());
    }

    void sessionJsonRoundTrip() {
        Session s;
        Preset p;
        QVERIFY(findPreset("fig23", p));
        s.settings.params = p.params;
        s.settings.params.lawParams<RateStateParams>().Dc_m = 17.25e-6;
        s.settings.params.lawParams<CoulombParams>().mu = 0.31;   // the Coulomb law may differ
        s.settings.model = ModelChoice::Both;
        s.settings.preset = "fig23";
        s.settings.tolerance = 1e-5;
        s.visibleViews = QStringList{"timeseries", "rig"};
        s.measuredFile = "/tmp/x.csv";
        QTemporaryDir dir;
        const QString path = dir.filePath("s.json");
        QString why;
        QVERIFY2(saveSession(s, path, &why), qPrintable(why));
        Session back;
        QVERIFY2(loadSession(path, back, &why), qPrintable(why));
        for (const auto& k : paramKeys()) {
            double a = 0, b = 0;
            getParam(s.settings.params, k, a);
            getParam(back.settings.params, k, b);
            QVERIFY2(a == b, k.c_str());   // bit-exact through JSON
        }
        QCOMPARE(back.settings.params.lawParams<CoulombParams>().mu, 0.31);
        QCOMPARE(back.settings.params.lawParams<CoulombParams>().epsT_N_per_m, s.settings.params.lawParams<CoulombParams>().epsT_N_per_m);
        QVERIFY(back.settings.model == ModelChoice::Both);
        QVERIFY(back.settings.params.setup == s.settings.params.setup);
        QCOMPARE(back.settings.preset, QString("fig23"));
        QCOMPARE(back.settings.tolerance, 1e-5);
        QCOMPARE(back.visibleViews, s.visibleViews);
        QCOMPARE(back.measuredFile, s.measuredFile);
    }

    void sessionErrorsSayWhere() {
        Session out;
        QString why;
        QVERIFY(!Session::fromJson("{\n  \"format\": \"stickslip-session\",\n  \"model\" \"both\"\n}", out, &why));
        QVERIFY2(why.contains("line 3"), qPrintable(why));
        QVERIFY(!Session::fromJson(R"({"format":"stickslip-session","model":"both","setup":"dynamics","params":{"zeta":1}})",
                                   out, &why));
        QVERIFY2(why.contains("zeta"), qPrintable(why));
        QVERIFY(!Session::fromJson(R"({"format":"other"})", out, &why));
        QVERIFY(!Session::fromJson(R"({"format":"stickslip-session","model":"lugre","setup":"dynamics"})", out, &why));
        QVERIFY2(why.contains("lugre"), qPrintable(why));
        QTemporaryDir dir;
        QVERIFY(!loadSession(dir.filePath("missing.json"), out, &why));
        QVERIFY2(why.contains("missing.json"), qPrintable(why));
    }
};

QTEST_MAIN(TstAppPanel)
#include "tst_app_panel.moc"
