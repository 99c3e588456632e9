// Import of measured runs: default column names, mapping and units, manifest and --run-set
// settings, t_N from columns, and bad files reported with file:line:column, nothing half-loaded.
#include <QtTest>

#include <cmath>
#include <fstream>
#include <set>

#include "core/io/dataset.hpp"

using namespace stickslip::io;

namespace {
std::string writeTemp(const QString& name, const std::string& text) {
    const QString path = QDir::temp().filePath(name);
    std::ofstream(path.toStdString()) << text;
    return path.toStdString();
}
const std::string kShared = STICKSLIP_SHARED_DIR;
}  // namespace

class TstDataset : public QObject {
    Q_OBJECT
private slots:
    void realDamperRunLoadsWithDefaults() {
        Run r;
        DatasetError err;
        const std::string f = kShared + "/data/real/friction-damper/1Hz_30lb_1in.csv";
        QVERIFY2(loadRun(f, ColumnMapping{}, r, err), err.what().c_str());
        QCOMPARE(r.size(), size_t(7174 - 5));
        QVERIFY(r.has(Signal::StageDisp) && r.has(Signal::StageVel) && r.has(Signal::Friction) && r.has(Signal::Tension));
        QVERIFY(!r.has(Signal::SliderDisp));
        QCOMPARE(r.comments.size(), size_t(4));
        QVERIFY(std::abs(r[Signal::Time][1] - 1.0 / 1024) < 1e-6);
        QCOMPARE(r.name(), std::string("1Hz_30lb_1in.csv"));
    }

    void datasetTakesManifestColumnsAndRunSetInPriority() {
        const std::string dir = kShared + "/data/synthetic/D05/";
        DatasetOptions o;
        o.manifestPath = dir + "manifest.json";
        o.runSets = {"run_02.csv:k=1600", "run_02.csv:m=510g"};
        Dataset ds;
        DatasetError err;
        QVERIFY2(loadDataset({dir + "run_01.csv", dir + "run_02.csv"}, o, ds, err), err.what().c_str());
        QCOMPARE(ds.runs.size(), size_t(2));
        double k = 0, m = 0, tN = 0, A = 0;
        QVERIFY(ds.runs[0].setting("k", k) && k == 8446.0);
        QVERIFY(ds.runs[0].setting("A", A) && std::abs(A - 0.0005317551) < 1e-6);
        QVERIFY(ds.runs[0].setting("m", m) && m == 0.53);   // nominal mass from the manifest
        QCOMPARE(ds.runs[0].settingSource.at("k"), std::string("manifest"));
        // t_N from the measured normal force column beats the manifest's nominal value.
        QVERIFY(ds.runs[0].setting("tN", tN));
        QVERIFY(std::abs(tN - 11.6394) < 0.05);
        QVERIFY(ds.runs[0].settingSource.at("tN").find("column") != std::string::npos);
        // --run-set beats both, with units.
        QVERIFY(ds.runs[1].setting("k", k) && k == 1600.0);
        QVERIFY(ds.runs[1].setting("m", m) && std::abs(m - 0.51) < 1e-12);
        QCOMPARE(ds.runs[1].settingSource.at("k"), std::string("run-set"));
    }

    void mappingAndUnitsConvertToSI() {
        const std::string f = writeTemp("h5_map.csv", "# mm and kN\nt;pos;Fx\n0;1.5;0.002\n0.001;2.0;0.003\n0.002;2.5;0.004\n"
                                                      "0.003;3;0\n0.004;3;0\n0.005;3;0\n0.006;3;0\n0.007;3;0\n");
        ColumnMapping m;
        std::string why;
        QVERIFY(m.addColumns("time=t,stage_disp=pos", &why));
        QVERIFY(m.addColumns("friction=Fx", &why));
        QVERIFY2(m.addUnits("stage_disp=mm,friction=kN", &why), why.c_str());
        Run r;
        DatasetError err;
        QVERIFY2(loadRun(f, m, r, err), err.what().c_str());
        QVERIFY(std::abs(r[Signal::StageDisp][0] - 1.5e-3) < 1e-15);
        QVERIFY(std::abs(r[Signal::Friction][2] - 4.0) < 1e-12);
        // A unit of the wrong dimension and an unknown signal are refused with a reason.
        QVERIFY(!m.addUnits("friction=mm", &why));
        QVERIFY(why.find("friction") != std::string::npos);
        QVERIFY(!m.addColumns("force=Fx", &why));
        QVERIFY(why.find("unknown signal") != std::string::npos);
    }

    // The signal table of dataset.hpp (the enum comment): each signal's key, default column and
    // SI unit as documented; keys and columns distinct; every key parses back to its signal;
    // every SI unit is accepted for its signal by --units with factor exactly 1; and a file
    // whose header is the default column names loads every signal without a mapping.
    void signalKeysColumnsAndUnits() {
        struct Row {
            Signal s;
            const char* key;
            const char* column;
            const char* unit;
        };
        const Row rows[] = {
            {Signal::Time, "time", "time_s", "s"},
            {Signal::StageDisp, "stage_disp", "stage_disp_m", "m"},
            {Signal::SliderDisp, "slider_disp", "slider_disp_m", "m"},
            {Signal::Slip, "slip", "slip_m", "m"},
            {Signal::RelVel, "rel_vel", "rel_vel_mps", "m/s"},
            {Signal::StageVel, "stage_vel", "stage_vel_mps", "m/s"},
            {Signal::SliderVel, "slider_vel", "slider_vel_mps", "m/s"},
            {Signal::Friction, "friction", "friction_force_N", "N"},
            {Signal::Normal, "normal", "normal_force_N", "N"},
            {Signal::Tension, "tension", "band_tension_N", "N"},
            {Signal::SliderAccel, "slider_accel", "slider_accel_mps2", "m/s^2"},
        };
        QCOMPARE(std::size(rows), kSignalCount);
        std::set<std::string> keys, columns;
        std::string header, line;
        for (const Row& r : rows) {
            QCOMPARE(std::string(signalKey(r.s)), std::string(r.key));
            QCOMPARE(std::string(defaultColumn(r.s)), std::string(r.column));
            QCOMPARE(std::string(signalUnit(r.s)), std::string(r.unit));
            keys.insert(r.key);
            columns.insert(r.column);
            Signal back = r.s == Signal::Time ? Signal::Friction : Signal::Time;  // anything else
            QVERIFY2(parseSignal(signalKey(r.s), back), r.key);
            QVERIFY2(back == r.s, r.key);
            ColumnMapping m;
            std::string why;
            QVERIFY2(m.addUnits(std::string(r.key) + "=" + signalUnit(r.s), &why), why.c_str());
            QCOMPARE(m.scaleToSI.at(r.s), 1.0);
            header.append(header.empty() ? "" : ",").append(defaultColumn(r.s));
        }
        QCOMPARE(keys.size(), kSignalCount);
        QCOMPARE(columns.size(), kSignalCount);
        std::string csv = header + "\n";
        for (int i = 0; i < 8; ++i) {
            csv += std::to_string(i * 1e-3);  // time increasing; the rest small physical values
            for (size_t j = 1; j < kSignalCount; ++j) csv.append(",").append(std::to_string(0.5 + 0.01 * double(j)));
            csv += "\n";
        }
        Run run;
        DatasetError err;
        QVERIFY2(loadRun(writeTemp("h5_defaults.csv", csv), ColumnMapping{}, run, err), err.what().c_str());
        for (const Row& r : rows) {
            QVERIFY2(run.has(r.s), r.key);
            QCOMPARE(run.sourceColumn.at(r.s), std::string(r.column));
        }
        QCOMPARE(run[Signal::Normal][3], 0.5 + 0.01 * double(static_cast<size_t>(Signal::Normal)));
    }

    // parseSignal accepts exactly the keys: not the column names, another case, blanks around
    // the key or a hyphen for the underscore; on refusal `out` keeps the caller's value.
    void parseSignalRejectsUnknownKeys() {
        for (const char* bad : {"", "force", "Friction", "FRICTION", " friction", "friction ", "friction_force_N",
                                "time_s", "slider-disp", "slider_accel_mps2", "-"}) {
            Signal out = Signal::SliderAccel;
            QVERIFY2(!parseSignal(bad, out), bad);
            QVERIFY2(out == Signal::SliderAccel, bad);
        }
        Signal out = Signal::Time;
        QVERIFY(parseSignal("slider_accel", out) && out == Signal::SliderAccel);
    }

    void signalMappedToDashIsNotRead() {
        const std::string d05 = kShared + "/data/synthetic/D05/run_01.csv";
        Run all, some;
        DatasetError err;
        QVERIFY2(loadRun(d05, ColumnMapping{}, all, err), err.what().c_str());
        QVERIFY(all.has(Signal::Friction) && all.has(Signal::SliderAccel));
        ColumnMapping m;
        std::string why;
        QVERIFY2(m.addColumns("friction=-,slider_accel=-", &why), why.c_str());
        QVERIFY2(loadRun(d05, m, some, err), err.what().c_str());
        QVERIFY(!some.has(Signal::Friction) && !some.has(Signal::SliderAccel));
        QVERIFY(some.has(Signal::SliderDisp));
        QVERIFY(some[Signal::SliderDisp] == all[Signal::SliderDisp]);
        // an empty name set directly means the same; time cannot be unmapped
        ColumnMapping e;
        e.columns[Signal::Normal] = "";
        QVERIFY2(loadRun(d05, e, some, err), err.what().c_str());
        QVERIFY(!some.has(Signal::Normal));
        QVERIFY(!m.addColumns("time=-", &why));
        QVERIFY(why.find("time") != std::string::npos);
        e.columns[Signal::Time] = "";
        QVERIFY(!loadRun(d05, e, some, err));
        QVERIFY(err.message.find("time") != std::string::npos);
    }

    void badFilesNameFileLineColumn() {
        const std::string f = writeTemp("h5_bad.csv", "time_s,friction_force_N\n0,1\n0.001,2\n0.002,abc\n");
        Run r;
        r.file = "untouched";
        DatasetError err;
        QVERIFY(!loadRun(f, ColumnMapping{}, r, err));
        QCOMPARE(r.file, std::string("untouched"));
        QCOMPARE(err.line, 4L);
        QCOMPARE(err.column, 7L);  // character column of the bad cell
        QVERIFY(err.what().find("h5_bad.csv:4:7") != std::string::npos);
        // time going backwards
        const std::string g = writeTemp("h5_time.csv", "time_s,x\n0,1\n0.1,1\n0.2,1\n0.15,1\n0.3,1\n0.4,1\n0.5,1\n0.6,1\n0.7,1\n");
        QVERIFY(!loadRun(g, ColumnMapping{}, r, err));
        QCOMPARE(err.line, 5L);
        QVERIFY(err.message.find("time does not increase") != std::string::npos);
        // a mapped column that is not there
        ColumnMapping m;
        std::string why;
        m.addColumns("friction=Fx", &why);
        QVERIFY(!loadRun(kShared + "/data/synthetic/D05/run_01.csv", m, r, err));
        QVERIFY(err.message.find("Fx") != std::string::npos);
        // a whole dataset with one bad file loads nothing
        Dataset ds;
        ds.manifestPath = "keep";
        QVERIFY(!loadDataset({kShared + "/data/synthetic/D05/run_01.csv", f}, DatasetOptions{}, ds, err));
        QCOMPARE(ds.manifestPath, std::string("keep"));
        QVERIFY(ds.runs.empty());
    }

    void runSetErrors() {
        Dataset ds;
        DatasetError err;
        QVERIFY(loadDataset({kShared + "/data/real/friction-damper/1Hz_30lb_1in.csv"}, DatasetOptions{}, ds, err));
        double tN = 0;
        QVERIFY(ds.runs[0].setting("tN", tN));  // from the band tension column
        QVERIFY(std::abs(tN - 133.4466) < 1e-3);
        std::string why;
        QVERIFY(!applyRunSet(ds, "nosuch.csv:tN=3", &why));
        QVERIFY(why.find("nosuch.csv") != std::string::npos);
        QVERIFY(!applyRunSet(ds, "1Hz_30lb_1in.csv:tN=3Hz", &why));
        QVERIFY(!applyRunSet(ds, "1Hz_30lb_1in.csv-tN", &why));
        QVERIFY(applyRunSet(ds, "1Hz_30lb_1in.csv:tN=30lbf", &why));
        QVERIFY(ds.runs[0].setting("tN", tN) && std::abs(tN - 133.4466) < 0.01);
    }

    void manifestErrorsAreLocated() {
        const std::string f = writeTemp("h5_manifest.json", "{\n \"runs\": [\n  {\"file\": \"a.csv\",, }\n ]\n}\n");
        Manifest m;
        DatasetError err;
        QVERIFY(!readManifest(f, m, err));
        QCOMPARE(err.line, 3L);
        QVERIFY(err.column > 1);
    }

    void manifestParsesFromText() {
        Manifest m;
        DatasetError err;
        const std::string text = R"({"nominal_mass_kg": 0.53, "runs": [{"file": "sub/run_01.csv", "k_N_per_m": 1547, "A_m": 0.0026}]})";
        QVERIFY2(parseManifest(text, "mem.json", m, err), err.what().c_str());
        QCOMPARE(m.path, std::string("mem.json"));
        QCOMPARE(m.common.at("m"), 0.53);
        QCOMPARE(m.runs.at("run_01.csv").at("k"), 1547.0);
        QCOMPARE(m.runs.at("run_01.csv").at("A"), 0.0026);
        // Errors name the given path; trailing text after the JSON value is malformed too.
        QVERIFY(!parseManifest(R"({"runs": []} x)", "mem.json", m, err));
        QCOMPARE(err.file, std::string("mem.json"));
        QCOMPARE(err.line, 1L);
        QVERIFY(!parseManifest(R"({"runs": [{"file": "a.csv", "f_Hz": "4"}]})", "mem.json", m, err));
        QVERIFY(err.message.find("f_Hz") != std::string::npos);
    }

    // Found by fuzz/fuzz_manifest: a number beyond the double range made nlohmann throw
    // out_of_range, which escaped readManifest and terminated the program.
    void manifestNumberOverflowIsAnError() {
        Manifest m;
        DatasetError err;
        QVERIFY(!parseManifest(R"({"runs": [{"file": "a.csv", "k_N_per_m": 1e999}]})", "mem.json", m, err));
        QCOMPARE(err.file, std::string("mem.json"));
        QVERIFY2(err.message.find("1e999") != std::string::npos, err.message.c_str());
        const std::string f = writeTemp("fuzz_manifest_overflow.json", "{\"runs\": [{\"file\": \"a.csv\", \"A_m\": -1e999}]}");
        QVERIFY(!readManifest(f, m, err));
        QVERIFY2(err.message.find("-1e999") != std::string::npos, err.message.c_str());
    }
};

QTEST_GUILESS_MAIN(TstDataset)
#include "tst_dataset.moc"
