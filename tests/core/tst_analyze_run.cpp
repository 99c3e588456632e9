// analyzeRunTable (core/analysis/analyze_run.hpp): the analyses of `stickslip-cli analyze`.
#include <QtTest>

#include <cmath>

#include "core/analysis/analyze_run.hpp"
#include "core/integrate/simulate.hpp"
#include "core/io/run_csv.hpp"
#include "core/presets.hpp"

using namespace stickslip;

class TstAnalyzeRun : public QObject {
    Q_OBJECT
private slots:
    void simulatedRunFrequencyFromTheFile() {
        Preset pr;
        QVERIFY(findPreset("fig20", pr));
        pr.params.cycles = 8;
        const RunResult r = simulate(pr.params);
        QVERIFY2(r.ok(), r.message.c_str());
        io::CsvTable t;
        io::CsvError e;
        QVERIFY2(io::parseCsvTable(io::runCsvText(pr.params, r), "run.csv", t, e), e.what().c_str());
        nlohmann::json j;
        std::string err;
        QVERIFY2(analyzeRunTable(t, "run.csv", AnalyzeSettings{}, "test", j, &err), err.c_str());
        QCOMPARE(j["input"].get<std::string>(), std::string("run.csv"));
        QCOMPARE(j["program"].get<std::string>(), std::string("test"));
        QCOMPARE(j["rows"].get<size_t>(), r.samples.size());
        QCOMPARE(j["forcing_frequency_source"].get<std::string>(), std::string("file"));
        QCOMPARE(j["forcing_frequency_Hz"].get<double>(), pr.params.drive.frequency_Hz);
        QVERIFY(j.contains("spectrum") && j.contains("phase_lag") && j.contains("loops") && j.contains("zero_one_test"));
        QCOMPARE(j["columns_used"]["rel_vel"].get<std::string>(), std::string("rel_vel_mps"));
        // The option wins over the file.
        AnalyzeSettings s;
        s.frequency_Hz = 2.5;
        QVERIFY(analyzeRunTable(t, "run.csv", s, "test", j, &err));
        QCOMPARE(j["forcing_frequency_source"].get<std::string>(), std::string("option"));
    }

    void tooFewRowsOrNoTime() {
        io::CsvTable t;
        t.header = {"time_s"};
        t.columns = {std::vector<double>(10, 0.0)};
        nlohmann::json j;
        std::string err;
        QVERIFY(!analyzeRunTable(t, "x.csv", AnalyzeSettings{}, "test", j, &err));
        QVERIFY2(err.find("need at least 64") != std::string::npos, err.c_str());
        t.header = {"t"};
        QVERIFY(!analyzeRunTable(t, "x.csv", AnalyzeSettings{}, "test", j, &err));
        QVERIFY2(err.find("no 'time_s' column") != std::string::npos, err.c_str());
    }
};

QTEST_GUILESS_MAIN(TstAnalyzeRun)
#include "tst_analyze_run.moc"
