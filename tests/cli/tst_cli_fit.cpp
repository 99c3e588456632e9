// stickslip-cli fit, run as a separate process: the report has every key issue 5 asks for,
// with finite values, its NRMSE values agree with the --residuals CSV, and bad input exits
// non-zero with a message naming file:line:column or the offending field.
#include <QProcess>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QFile>
#include <QTemporaryDir>
#include <QtTest>

#include <cmath>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "cli_runner.hpp"

using json = nlohmann::json;

namespace {

using Result = stickslip::testing::CliResult;

// Fits take minutes on a loaded machine.
Result runCli(const QStringList& args) { return stickslip::testing::runCli(args, 1200000); }

QString damper(const char* name) { return QStringLiteral(STICKSLIP_SHARED_DIR "/data/real/friction-damper/") + name; }
QString d05(const char* name) { return QStringLiteral(STICKSLIP_SHARED_DIR "/data/synthetic/D05/") + name; }

json readJson(const QString& path) {
    std::ifstream f(path.toStdString());
    return json::parse(f);
}

bool finite(const json& v) { return v.is_number() && std::isfinite(v.get<double>()); }

// Per run and pooled over each role: NRMSE recomputed from the residual CSV.
struct CsvScores {
    std::map<std::string, double> nrmse;  // by run name
    std::map<std::string, double> pooled; // by role
    size_t rows = 0;
};

CsvScores scoresFromCsv(const QString& path, bool dynamics) {
    std::ifstream f(path.toStdString());
    std::string line;
    struct Acc { double eF = 0, mF = 0, eX = 0, mX = 0; size_t n = 0; std::string role; };
    std::map<std::string, Acc> acc;
    CsvScores out;
    bool header = false;
    while (std::getline(f, line)) {
        if (line.empty() || line[0] == '#') continue;
        if (!header) { header = true; continue; }
        std::stringstream in(line);
        std::string run, role, cell;
        std::getline(in, run, ',');
        std::getline(in, role, ',');
        std::vector<double> v;
        while (std::getline(in, cell, ',')) v.push_back(std::stod(cell));
        Acc& a = acc[run];
        a.role = role;
        // time, measured F, predicted F, residual F [, measured x, predicted x, residual x]
        a.eF += v[3] * v[3];
        a.mF += v[1] * v[1];
        if (dynamics) {
            a.eX += v[6] * v[6];
            a.mX += v[4] * v[4];
        }
        ++a.n;
        ++out.rows;
    }
    std::map<std::string, std::pair<double, double>> pool;
    for (const auto& [run, a] : acc) {
        double nr = std::sqrt(a.eF / a.mF);
        if (dynamics) nr = std::sqrt(0.5 * (a.eF / a.mF + a.eX / a.mX));
        out.nrmse[run] = nr;
        // Both set-ups pool each run's error over its own measured RMS (the fit's objective and
        // identify's NRMSE): √(Σ n_k NRMSE_k² / Σ n_k).
        pool[a.role].first += nr * nr * a.n;
        pool[a.role].second += a.n;
    }
    for (const auto& [role, p] : pool) out.pooled[role] = std::sqrt(p.first / p.second);
    return out;
}

std::string baseName(const std::string& path) {
    const size_t s = path.find_last_of('/');
    return s == std::string::npos ? path : path.substr(s + 1);
}

void checkReport(const json& rep, const QString& residualsPath, bool dynamics, const std::vector<std::string>& freeNames,
                 const std::string& model = "rate-state") {
    for (const char* key : {"model", "parameters", "correlation", "runs", "fit_nrmse", "validation_nrmse", "solver",
                            "preprocessing", "identifiable", "tau_int"})
        QVERIFY2(rep.contains(key), key);
    QCOMPARE(rep["model"].get<std::string>(), model);
    QCOMPARE(rep["setup"].get<std::string>(), std::string(dynamics ? "dynamics" : "prescribed"));
    for (const std::string& n : freeNames) {
        QVERIFY2(rep["parameters"].contains(n), n.c_str());
        const json& p = rep["parameters"][n];
        QVERIFY2(finite(p["value"]), n.c_str());
        QVERIFY2(p.contains("stderr"), n.c_str());
        QVERIFY(p["free"].get<bool>());
        // Either a finite positive standard error, or null when the fit says not identifiable.
        if (rep["identifiable"].get<bool>()) QVERIFY2(finite(p["stderr"]) && p["stderr"].get<double>() > 0, n.c_str());
        else QVERIFY(p["stderr"].is_null());
    }
    QVERIFY(rep["tau_int"].get<double>() >= 1.0);
    const json& corr = rep["correlation"];
    QCOMPARE(corr["names"].size(), freeNames.size());
    QCOMPARE(corr["matrix"].size(), freeNames.size());
    if (rep["identifiable"].get<bool>())
        for (size_t a = 0; a < freeNames.size(); ++a) {
            QVERIFY(std::abs(corr["matrix"][a][a].get<double>() - 1.0) < 1e-9);
            for (size_t b = 0; b < freeNames.size(); ++b) {
                const double c = corr["matrix"][a][b].get<double>();
                QVERIFY(std::abs(c) <= 1.0 + 1e-9);
                QVERIFY(std::abs(c - corr["matrix"][b][a].get<double>()) < 1e-9);
            }
        }
    for (const char* k : {"summary", "converged", "cost", "residuals", "starts", "stopped_early", "evaluations"})
        QVERIFY2(rep["solver"].contains(k), k);
    QVERIFY(rep["solver"]["residuals"].get<int>() > 0);
    for (const char* k : {"band_stop", "low_pass", "savitzky_golay", "trim", "runs"})
        QVERIFY2(rep["preprocessing"].contains(k), k);
    QVERIFY(finite(rep["fit_nrmse"]) && finite(rep["validation_nrmse"]));

    const CsvScores csv = scoresFromCsv(residualsPath, dynamics);
    QVERIFY(csv.rows > 100);
    int fits = 0, vals = 0;
    for (const json& r : rep["runs"]) {
        for (const char* k : {"file", "role", "rms", "nrmse"}) QVERIFY2(r.contains(k), k);
        const std::string role = r["role"].get<std::string>();
        QVERIFY(role == "fit" || role == "validation");
        (role == "fit" ? fits : vals)++;
        QVERIFY(finite(r["rms"]) && finite(r["nrmse"]));
        const double nr = r["nrmse"].get<double>();
        QVERIFY(nr > 0 && nr < 1.0);
        const std::string name = baseName(r["file"].get<std::string>());
        QVERIFY2(csv.nrmse.count(name), name.c_str());
        QVERIFY2(std::abs(csv.nrmse.at(name) - nr) < 1e-5 * nr + 1e-7,
                 qPrintable(QString("%1: csv %2 report %3").arg(name.c_str()).arg(csv.nrmse.at(name)).arg(nr)));
    }
    QVERIFY(fits >= 1 && vals == 1);
    QVERIFY(std::abs(csv.pooled.at("fit") - rep["fit_nrmse"].get<double>()) < 1e-5);
    QVERIFY(std::abs(csv.pooled.at("validation") - rep["validation_nrmse"].get<double>()) < 1e-5);
}

void writeText(const QString& path, const std::string& text) {
    std::ofstream f(path.toStdString(), std::ios::binary);
    f << text;
}

}  // namespace

class TstCliFit : public QObject {
    Q_OBJECT
private slots:
    void prescribedDamperRunsWithValidation() {
        QTemporaryDir dir;
        const QString rep = dir.filePath("fit.json"), res = dir.filePath("res.csv");
        const Result r = runCli({"fit", "--data", damper("1Hz_30lb_1in.csv"), damper("1Hz_30lb_1.5in.csv"), "--validate-on",
                                 damper("1Hz_30lb_0.5in.csv"), "--setup", "prescribed", "--free", "mu,eta,epsT",
                                 "--multistarts", "1", "--max-iterations", "8", "--report", rep, "--residuals", res});
        QVERIFY2(r.exitCode == 0, r.err.constData());
        checkReport(readJson(rep), res, false, {"mu", "eta", "epsT"});
    }

    // A law added by registration alone (Dieterich–Ruina) is simulated and fitted by the same
    // commands; its own keys (a, b) are free parameters like any other.
    void dieterichRuinaSimulatesAndFits() {
        QTemporaryDir dir;
        const QString run = dir.filePath("dr.csv"), rep = dir.filePath("fit.json"), res = dir.filePath("res.csv");
        Result r = runCli({"simulate", "--model", "dieterich-ruina", "--set", "a=0.02", "--cycles", "3", "--out", run});
        QVERIFY2(r.exitCode == 0, r.err.constData());
        QFile f(run);
        QVERIFY(f.open(QIODevice::ReadOnly));
        const QByteArray text = f.readAll();
        QVERIFY(text.contains("# model = dieterich-ruina") && text.contains("# a = 0.02\n"));
        r = runCli({"fit", "--data", d05("run_03.csv"), "--validate-on", d05("run_05.csv"), "--manifest", d05("manifest.json"),
                    "--model", "dieterich-ruina", "--free", "mu,a,b,epsT", "--multistarts", "1", "--max-iterations", "4",
                    "--report", rep, "--residuals", res});
        QVERIFY2(r.exitCode == 0, r.err.constData());
        const json j = readJson(rep);
        checkReport(j, res, true, {"mu", "a", "b", "epsT"}, "dieterich-ruina");
    }

    void dynamicsD05WithManifest() {
        QTemporaryDir dir;
        const QString rep = dir.filePath("fit.json"), res = dir.filePath("res.csv");
        const Result r = runCli({"fit", "--data", d05("run_03.csv"), "--validate-on", d05("run_05.csv"), "--manifest",
                                 d05("manifest.json"), "--free", "mu,C1,eta", "--multistarts", "1", "--max-iterations", "4",
                                 "--report", rep, "--residuals", res});
        QVERIFY2(r.exitCode == 0, r.err.constData());
        const json j = readJson(rep);
        checkReport(j, res, true, {"mu", "C1", "eta"});
        // The manifest's settings reached the run (k of run_03 is 8446 N/m).
        bool sawK = false;
        for (const json& run : j["preprocessing"]["runs"])
            if (baseName(run["file"].get<std::string>()) == "run_03.csv")
                sawK = std::abs(run["settings"]["k"]["value"].get<double>() - 8446.0) < 1e-9;
        QVERIFY(sawK);
        // The dynamics defaults are reported: segments start in slip, initial states profiled out.
        QCOMPARE(j["prediction"]["fit_initial_state"].get<bool>(), true);
        QCOMPARE(j["prediction"]["slip_start_fraction"].get<double>(), 0.5);
        QVERIFY(j["parameters"]["mu"].contains("stderr_jackknife"));
        QVERIFY(j["parameters"]["mu"]["stderr_jackknife"].is_null());  // not asked for
        QVERIFY(j.contains("stderr_warning") && j["stderr_warning"].is_null());  // vc not free: no valley warning
    }

    // --jackknife with 3 fit runs: every free parameter gets a jackknife standard error, and the
    // reported one is the larger of it and the Jacobian one; --initial-state measured is kept.
    void jackknifeOverRunsAndMeasuredInitialState() {
        QTemporaryDir dir;
        const QString rep = dir.filePath("fit.json");
        const Result r = runCli({"fit", "--data", d05("run_01.csv"), d05("run_03.csv"), d05("run_05.csv"), "--manifest",
                                 d05("manifest.json"), "--free", "mu,m", "--multistarts", "1", "--max-iterations", "3",
                                 "--initial-state", "measured", "--jackknife", "--report", rep});
        QVERIFY2(r.exitCode == 0, r.err.constData());
        const json j = readJson(rep);
        QCOMPARE(j["prediction"]["fit_initial_state"].get<bool>(), false);
        QCOMPARE(j["jackknife_fits"].get<int>(), 3);
        for (const char* n : {"mu", "m"}) {
            const json& p = j["parameters"][n];
            QVERIFY2(p["stderr_jackknife"].is_number() && p["stderr_jackknife"].get<double>() > 0, n);
            const double want = std::max(p["stderr_jacobian"].get<double>(), p["stderr_jackknife"].get<double>());
            QCOMPARE(p["stderr"].get<double>(), want);
        }
        const Result bad = runCli({"fit", "--data", d05("run_01.csv"), "--manifest", d05("manifest.json"), "--initial-state",
                                   "guessed", "--report", dir.filePath("x.json")});
        QVERIFY(bad.exitCode != 0);
        QVERIFY2(bad.err.contains("--initial-state") && bad.err.contains("guessed"), bad.err.constData());
        const Result badCoords = runCli({"fit", "--data", d05("run_01.csv"), "--manifest", d05("manifest.json"), "--coordinates",
                                         "polar", "--report", dir.filePath("y.json")});
        QVERIFY(badCoords.exitCode != 0);
        QVERIFY2(badCoords.err.contains("--coordinates") && badCoords.err.contains("polar"), badCoords.err.constData());
    }

    void badInputIsRefusedWithAPreciseMessage() {
        QTemporaryDir dir;
        const QString good = damper("1Hz_30lb_1in.csv");
        // missing file
        Result r = runCli({"fit", "--data", dir.filePath("nope.csv"), "--report", dir.filePath("a.json")});
        QVERIFY(r.exitCode != 0);
        QVERIFY2(r.err.contains("nope.csv"), r.err.constData());
        QVERIFY(!QFile::exists(dir.filePath("a.json")));
        // malformed CSV: a non-number in row 3 (line 3), column 3
        const QString bad = dir.filePath("bad.csv");
        writeText(bad, "time_s,stage_disp_m,friction_force_N\n0,0,1\n0.001,0,x2\n");
        r = runCli({"fit", "--data", bad, "--report", dir.filePath("b.json")});
        QVERIFY(r.exitCode != 0);
        QVERIFY2(r.err.contains("bad.csv:3:"), r.err.constData());
        QVERIFY2(r.err.contains("x2"), r.err.constData());
        QVERIFY(!QFile::exists(dir.filePath("b.json")));
        // unknown free parameter
        r = runCli({"fit", "--data", good, "--free", "mu,bogus", "--report", dir.filePath("c.json")});
        QVERIFY(r.exitCode != 0);
        QVERIFY2(r.err.contains("--free") && r.err.contains("bogus"), r.err.constData());
        QVERIFY(!QFile::exists(dir.filePath("c.json")));
        // unknown model
        r = runCli({"fit", "--data", good, "--model", "magic", "--report", dir.filePath("d.json")});
        QVERIFY(r.exitCode != 0);
        QVERIFY2(r.err.contains("--model") && r.err.contains("magic"), r.err.constData());
    }

    // fit and identify take the same input and cleaning options (one definition,
    // cli_common addMeasuredInputOptions / addCleaningOptions): a low-pass above Nyquist is refused
    // by both with the same message, before anything is fitted.
    void fitAndIdentifyShareTheCleaningOptions() {
        QTemporaryDir dir;
        const QString good = damper("1Hz_30lb_1in.csv");
        QByteArray msg[2];
        int k = 0;
        for (const char* cmd : {"fit", "identify"}) {
            const Result r = runCli({cmd, "--data", good, "--lowpass-hz", "5000", "--report", dir.filePath("r.json")});
            QVERIFY2(r.exitCode != 0 && r.err.contains("low-pass cut-off 5000"), r.err.constData());
            msg[k++] = r.err.mid(r.err.indexOf(':', r.err.indexOf(cmd)));
            QVERIFY(!QFile::exists(dir.filePath("r.json")));
        }
        QCOMPARE(msg[0], msg[1]);
    }

    // identify --self-test: bad self-test options exit 2 naming the option and the value, before
    // any fit; a run writes the table to stdout and the report's self_test block.
    void identifySelfTest() {
        QTemporaryDir dir;
        const QStringList base = {"identify", "--quiet", "--data", damper("1Hz_30lb_1in.csv"), damper("0.5Hz_36lb_1in.csv"),
                                  "--setup", "prescribed", "--max-effects", "0", "--multistarts", "1", "--self-test"};
        struct Bad { QStringList extra; const char* says; };
        for (const Bad& b : {Bad{{"--self-test-replicas", "0"}, "--self-test-replicas = 0"},
                             Bad{{"--self-test-levels", "0.5,-1"}, "level = -1"},
                             Bad{{"--self-test-size", "backlash"}, "--self-test-size 'backlash'"},
                             Bad{{"--self-test-size", "no_such=1"}, "no_such"},
                             Bad{{"--self-test-size", "backlash.halfWidth_m=1e-3"}, "is the size parameter"},
                             Bad{{"--self-test-size", "stick_healing.no_such=1"}, "its other parameters: tc_s, Dh_m"}}) {
            const QString rep = dir.filePath("bad.json");
            const Result r = runCli(base + b.extra + QStringList{"--report", rep});
            QVERIFY2(r.exitCode == 2, r.err.constData());
            QVERIFY2(r.err.contains(b.says), r.err.constData());
            QVERIFY(!QFile::exists(rep));
        }
        const QString rep = dir.filePath("st.json");
        const Result r = runCli(base + QStringList{"--candidates", "normal_load_mu,backlash", "--self-test-replicas", "5",
                                                   "--self-test-levels", "0.5,1", "--self-test-size", "backlash=1e-3",
                                                   "--report", rep});
        QVERIFY2(r.exitCode == 0, r.err.constData());
        QVERIFY2(r.out.contains("self-test (5 replicas per row") && r.out.contains("false alarms on 10 replicas"), r.out.constData());
        QFile f(rep);
        QVERIFY(f.open(QIODevice::ReadOnly));
        const QJsonObject st = QJsonDocument::fromJson(f.readAll()).object().value("self_test").toObject();
        QVERIFY(st.value("ok").toBool());
        const QJsonArray rows = st.value("rows").toArray();
        QVERIFY(rows.size() >= 2 && rows.size() <= 3);  // normal_load_mu at two levels (or one at its bound), backlash stated
        const QJsonObject last = rows.last().toObject();
        QCOMPARE(last.value("effect").toString(), QString("backlash"));
        QCOMPARE(last.value("size").toDouble(), 1e-3);
        QVERIFY(last.value("level").isNull());
        QCOMPARE(last.value("replicas").toInt(), 5);
    }

    // Measured data beyond the physical ranges (core/io/channel_ranges.hpp) is refused by the
    // reader for fit and identify alike: exit 3, file:line:column, the value as written, the range.
    void outOfRangeDataExit3() {
        QTemporaryDir dir;
        const QString bad = dir.filePath("huge.csv");
        std::string text = "time_s,stage_disp_m,friction_force_N\n";
        for (int i = 0; i < 10; ++i) text += std::to_string(i) + ",1e-4," + (i == 6 ? "5e6" : "1.5") + "\n";
        writeText(bad, text);
        for (const char* cmd : {"fit", "identify"}) {
            const QString rep = dir.filePath(QString(cmd) + ".json");
            const Result r = runCli({cmd, "--data", bad, "--report", rep});
            QVERIFY2(r.exitCode == 3, r.err.constData());
            QVERIFY2(r.err.contains((bad + ":8:8: friction_force_N = 5e+06 N is outside the allowed range [-1e+06, 1e+06] N").toUtf8()),
                     r.err.constData());
            QVERIFY(!QFile::exists(rep));
        }
        // The same file with the force in mN is fine as far as the ranges go (5e6 mN = 5 kN).
        const Result mN = runCli({"fit", "--data", bad, "--units", "friction=mN", "--setup", "prescribed", "--free", "mu",
                                  "--multistarts", "1", "--max-iterations", "1", "--report", dir.filePath("mN.json")});
        QVERIFY2(!mN.err.contains("allowed range"), mN.err.constData());
    }
};

// A longer per-function watchdog than Qt's default 300 s: each fit takes tens of seconds of CPU,
// which a loaded machine (or a sanitizer build) stretches.
int main(int argc, char** argv) {
    if (qEnvironmentVariableIsEmpty("QTEST_FUNCTION_TIMEOUT")) qputenv("QTEST_FUNCTION_TIMEOUT", "1800000");
    QCoreApplication app(argc, argv);
    TstCliFit tc;
    QTEST_SET_MAIN_SOURCE_PATH
    return QTest::qExec(&tc, argc, argv);
}
#include "tst_cli_fit.moc"
