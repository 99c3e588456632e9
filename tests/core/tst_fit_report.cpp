// The fit.json layout shared by `stickslip-cli fit` and the GUI (core/identify/fit_report):
// every key the issue requires, non-finite numbers as null, C1 tied to mu, two laws side by
// side with a per-run comparison.
#include <QtTest>
#include <cmath>

#include "core/identify/fit_report.hpp"

using namespace stickslip;
using namespace stickslip::identify;

namespace {

DatasetFit fakeFit(LawKind law, double nrmseFit, double nrmseVal) {
    DatasetFit f;
    f.ok = true;
    f.setup = SetupKind::Dynamics;
    f.model.law = law;
    f.model.tieC1ToMu = true;
    f.model.values = {{"mu", 0.27}, {"eta", 0.8}};
    f.fit.status = FitStatus::Ok;
    f.fit.names = {"mu", "eta", "m"};
    f.fit.values = {0.27, 0.8, 0.52};
    f.fit.free = {true, true, false};
    f.fit.stderrs = {0.01, NAN, 0.0};
    f.fit.freeNames = {"mu", "eta"};
    f.fit.correlation = {1.0, -0.4, -0.4, 1.0};
    f.fit.identifiable = false;
    f.fit.identifiabilityMessage = "not identifiable: eta";
    f.fit.conditionNumber = 3e14;
    f.fit.cost = 1.5;
    f.fit.rms = 0.1;
    f.fit.residualCount = 300;
    f.fit.solverSummary = "Ceres: CONVERGENCE";
    f.stderrsIid = {0.005, NAN, 0.0};
    f.tauInt = 4.0;
    RunScore a;
    a.file = "run_01.csv";
    a.role = "fit";
    a.samples = 200;
    a.rms_N = 0.2;
    a.nrmse = nrmseFit;
    a.ok = true;
    RunScore b = a;
    b.file = "run_02.csv";
    b.role = "validation";
    b.nrmse = nrmseVal;
    f.runs = {a, b};
    f.fitNrmse = nrmseFit;
    f.validationNrmse = nrmseVal;
    return f;
}

}  // namespace

class TstFitReport : public QObject {
    Q_OBJECT
private slots:
    void oneLawHasEveryRequiredKey() {
        const DatasetFit f = fakeFit(LawKind::RateState, 0.1, 0.2);
        const nlohmann::json j = toJson(f);
        QCOMPARE(j.at("model").get<std::string>(), std::string(toString(LawKind::RateState)));
        QCOMPARE(j.at("setup").get<std::string>(), std::string(toString(SetupKind::Dynamics)));
        const auto& p = j.at("parameters");
        QCOMPARE(p.at("mu").at("value").get<double>(), 0.27);
        QCOMPARE(p.at("mu").at("stderr").get<double>(), 0.01);
        QCOMPARE(p.at("mu").at("stderr_iid").get<double>(), 0.005);
        QVERIFY(p.at("eta").at("stderr").is_null());  // NaN -> null, never "nan"
        QCOMPARE(p.at("m").at("free").get<bool>(), false);
        QCOMPARE(p.at("m").at("unit").get<std::string>(), std::string("kg"));
        QCOMPARE(p.at("C1").at("tied_to").get<std::string>(), std::string("mu"));  // tied, not fitted
        QCOMPARE(p.at("C1").at("value").get<double>(), 0.27);
        QCOMPARE(j.at("correlation").at("names").size(), size_t(2));
        QCOMPARE(j.at("correlation").at("matrix").at(0).at(1).get<double>(), -0.4);
        QCOMPARE(j.at("identifiable").get<bool>(), false);
        QCOMPARE(j.at("tau_int").get<double>(), 4.0);
        QCOMPARE(j.at("runs").size(), size_t(2));
        QCOMPARE(j.at("runs").at(1).at("role").get<std::string>(), std::string("validation"));
        QVERIFY(j.at("runs").at(0).contains("rms_disp_m"));  // dynamics: both channels
        QCOMPARE(j.at("fit_nrmse").get<double>(), 0.1);
        QCOMPARE(j.at("validation_nrmse").get<double>(), 0.2);
        QCOMPARE(j.at("solver").at("residuals").get<size_t>(), size_t(300));
        QVERIFY(j.at("solver") == toJson(f.fit));  // one solver block for every report
        // Each start's final cost, a failed start's as null.
        FitResult two = f.fit;
        two.startsTried = 2;
        two.startCosts = {1.5, NAN};
        two.bestStart = 0;
        const nlohmann::json s = toJson(two);
        QCOMPARE(s.at("start_costs").size(), size_t(2));
        QCOMPARE(s.at("start_costs").at(0).get<double>(), 1.5);
        QVERIFY(s.at("start_costs").at(1).is_null());
        QCOMPARE(s.at("best_start").get<int>(), 0);
        QCOMPARE(s.at("starts").get<int>(), 2);
        // A Coulomb fit has no C1 to tie.
        QVERIFY(!toJson(fakeFit(LawKind::Coulomb, 0.3, 0.4)).at("parameters").contains("C1"));
    }

    void twoLawsSideBySide() {
        const DatasetFit rs = fakeFit(LawKind::RateState, 0.1, 0.2);
        const DatasetFit co = fakeFit(LawKind::Coulomb, 0.3, 0.4);
        const nlohmann::json j = fitReportJson({&rs, &co});
        QCOMPARE(j.at("model").get<std::string>(), std::string("both"));
        QCOMPARE(j.at("primary_model").get<std::string>(), std::string(toString(LawKind::RateState)));
        QCOMPARE(j.at("fit_nrmse").get<double>(), 0.1);                       // primary at top level
        QCOMPARE(j.at("coulomb").at("validation_nrmse").get<double>(), 0.4);  // second law below
        QCOMPARE(j.at("comparison").size(), size_t(2));
        QCOMPARE(j.at("comparison").at(1).at("nrmse_rate_state").get<double>(), 0.2);
        QCOMPARE(j.at("comparison").at(1).at("nrmse_coulomb").get<double>(), 0.4);
        QVERIFY(fitReportJson({}).empty());
        QCOMPARE(fitReportJson({&rs}).at("model").get<std::string>(), std::string(toString(LawKind::RateState)));
    }

    void predictionSettings() {
        PredictSettings p;
        p.filterPrediction = false;
        const nlohmann::json j = toJson(p);
        for (const char* k : {"stride", "substeps", "warmup_s", "dt_s", "segment_s", "segment_spacing_s", "residual_stride"})
            QVERIFY2(j.contains(k), k);
        QCOMPARE(j.at("filter_prediction").get<bool>(), false);
    }
};

QTEST_APPLESS_MAIN(TstFitReport)
#include "tst_fit_report.moc"
