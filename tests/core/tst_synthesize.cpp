// The rig-like synthetic sets of `stickslip-cli synthesize` (core/identify/synthesize.hpp):
// options checked at the boundary, the shared sets' format, determinism in the seed, wear
// carried over the runs, effects switched on and stated in the answer.
#include <QtTest/QtTest>

#include <cmath>
#include <fstream>
#include <numeric>

#include "core/identify/synthesize.hpp"

using namespace stickslip;
using namespace stickslip::identify;

namespace {

// A short set (2 runs of 1 s, 20 steps per sample) for the format checks.
SynthOptions small(uint64_t seed) {
    SynthOptions o;
    o.seed = seed;
    o.runs = 2;
    o.seconds = 1.0;
    o.stepsPerSample = 20;
    return o;
}

double mean(const std::vector<double>& v) { return std::accumulate(v.begin(), v.end(), 0.0) / static_cast<double>(v.size()); }

}  // namespace

class TestSynthesize : public QObject {
    Q_OBJECT
private slots:
    void validateNamesFieldValueAndRange() {
        SynthOptions o;
        o.runs = 0;
        o.seconds = -1;
        o.effects = {{"no_such_effect", {1.0}}, {"backlash", {1e-5, 2.0}}, {"stick_healing", {0.5, 1e-3, 1e-5}}};
        const std::string m = formatIssues(o.validate());
        QVERIFY2(m.find("runs = 0") != std::string::npos, m.c_str());
        QVERIFY2(m.find("seconds = -1") != std::string::npos, m.c_str());
        QVERIFY2(m.find("unknown effect 'no_such_effect'") != std::string::npos, m.c_str());
        QVERIFY2(m.find("backlash takes 1 parameter(s), got 2") != std::string::npos, m.c_str());
        QVERIFY2(m.find("stick_healing.b_heal = 0.5") != std::string::npos, m.c_str());  // physical range 0 ... 0.2
        const SynthResult r = synthesizeRigSet(o);
        QVERIFY(!r.ok);
        QVERIFY(r.message.find("runs = 0") != std::string::npos);
        QVERIFY(SynthOptions{}.validate().empty());
    }

    void recordsTheSharedFormat() {
        const SynthResult r = synthesizeRigSet(small(3));
        QVERIFY2(r.ok, r.message.c_str());
        QCOMPARE(r.runs.size(), size_t(2));
        QCOMPARE(r.manifest["runs"].size(), size_t(2));
        for (const SynthRun& run : r.runs) {
            QCOMPARE(run.t_s.size(), size_t(1000));
            QCOMPARE(run.t_s.front(), 0.0);
            QVERIFY(std::abs(run.t_s[1] - 1e-3) < 1e-12);
            QVERIFY(std::abs(mean(run.normal_N) - run.tN_N) < 0.02);  // 0.05 N noise + mains over 1000 samples
            // The slider moves and the force is of the size μ t_N.
            double fmax = 0;
            for (double f : run.force_N) fmax = std::max(fmax, std::abs(f));
            QVERIFY(fmax > 0.15 * run.tN_N && fmax < 0.6 * run.tN_N);
        }
        // The header of the shared sets, so `identify` reads it with the shared manifests' rules.
        const std::string csv = synthRunCsv(r.runs[0]);
        std::ifstream shared(std::string(STICKSLIP_SHARED_DIR) + "/data/synthetic/D05/run_01.csv");
        std::string header;
        if (shared && std::getline(shared, header)) QCOMPARE(csv.substr(0, csv.find('\n')), header);
        QCOMPARE(static_cast<long>(std::count(csv.begin(), csv.end(), '\n')), 1001L);
    }

    void seedDecides() {
        const SynthResult a = synthesizeRigSet(small(7)), b = synthesizeRigSet(small(7)), c = synthesizeRigSet(small(8));
        QVERIFY(a.ok && b.ok && c.ok);
        QVERIFY(a.runs[0].force_N == b.runs[0].force_N);
        QCOMPARE(a.answer.dump(), b.answer.dump());
        QVERIFY(a.runs[0].force_N != c.runs[0].force_N);
        QVERIFY(a.answer["baseline_params"]["mu"] != c.answer["baseline_params"]["mu"]);
        // Every drawn value inside its stated range.
        const SynthRanges rg;
        const double mu = a.answer["baseline_params"]["mu"], epsT = a.answer["baseline_params"]["epsT"];
        QVERIFY(mu >= rg.mu.lo && mu <= rg.mu.hi);
        QVERIFY(epsT >= rg.epsT_N_per_m.lo && epsT <= rg.epsT_N_per_m.hi);
    }

    // The noise scale changes the noise alone: the same law and runs, the noise-free twin's
    // channels are the simulation itself (the normal force exactly t_N), and a scale of 2 puts
    // every channel twice as far from it.
    void noiseScaleScalesTheNoiseAlone() {
        SynthOptions o0 = small(4), o1 = small(4), o2 = small(4);
        o0.noiseScale = 0.0;
        o2.noiseScale = 2.0;
        const SynthResult r0 = synthesizeRigSet(o0), r1 = synthesizeRigSet(o1), r2 = synthesizeRigSet(o2);
        QVERIFY(r0.ok && r1.ok && r2.ok);
        QCOMPARE(r0.answer["baseline_params"].dump(), r1.answer["baseline_params"].dump());
        QCOMPARE(double(r0.answer["noise"]["force_N"]), 0.0);
        QCOMPARE(double(r2.answer["noise"]["disp_m"]), 2.0 * o1.dispNoise_m);
        for (double v : r0.runs[0].normal_N) QCOMPARE(v, r0.runs[0].tN_N);
        for (size_t k = 0; k < r0.runs[0].t_s.size(); ++k) {
            const double d1 = r1.runs[0].force_N[k] - r0.runs[0].force_N[k], d2 = r2.runs[0].force_N[k] - r0.runs[0].force_N[k];
            QVERIFY(std::abs(d2 - 2.0 * d1) < 1e-9);
            const double x1 = r1.runs[0].slider_m[k] - r0.runs[0].slider_m[k], x2 = r2.runs[0].slider_m[k] - r0.runs[0].slider_m[k];
            QVERIFY(std::abs(x2 - 2.0 * x1) < 1e-15);
        }
        SynthOptions bad = small(4);
        bad.noiseScale = -1.0;
        const std::string m = formatIssues(bad.validate());
        QVERIFY2(m.find("noise_scale = -1") != std::string::npos, m.c_str());
    }

    // Wear accumulates over the runs in file order (pre-roll included): the second run starts
    // where the first ended.
    void slipCarriesOver() {
        const SynthResult r = synthesizeRigSet(small(5));
        QVERIFY(r.ok);
        QCOMPARE(r.runs[0].slipStart_m, 0.0);
        QVERIFY(r.runs[0].slipEnd_m > 1e-3);
        QCOMPARE(r.runs[1].slipStart_m, r.runs[0].slipEnd_m);
        QCOMPARE(double(r.answer["runs"][1]["accumulated_slip_start_m"]), r.runs[0].slipEnd_m);
    }

    // An effect switched on changes the measured force (same draws, same noise) and is stated in
    // the answer with its parameters under their catalogue names.
    void effectIsSimulatedAndStated() {
        SynthOptions o = small(11);
        const SynthResult plain = synthesizeRigSet(o);
        o.effects = {{"sensor_inertia", {0.08}}};
        const SynthResult with = synthesizeRigSet(o);
        QVERIFY(plain.ok && with.ok);
        QCOMPARE(plain.answer["baseline_params"].dump(), with.answer["baseline_params"].dump());
        QCOMPARE(with.answer["effects"].size(), size_t(1));
        QCOMPARE(std::string(with.answer["effects"][0]), std::string("sensor_inertia"));
        QCOMPARE(double(with.answer["effect_params"]["sensor_inertia"]["mass_kg"]), 0.08);
        QVERIFY(plain.answer["effects"].empty());
        // The sensed force is the contact force plus m_s ẍ: their difference follows the slider's
        // acceleration (noise on both channels aside), and not with the effect off.
        const SynthRun &p = plain.runs[0], &w = with.runs[0];
        double num = 0, den = 0;
        for (size_t i = 0; i < p.force_N.size(); ++i) {
            num += (w.force_N[i] - p.force_N[i]) * w.accel_mps2[i];
            den += w.accel_mps2[i] * w.accel_mps2[i];
        }
        QVERIFY2(std::abs(num / den - 0.08) < 0.02, qPrintable(QString::number(num / den)));
    }
};

QTEST_APPLESS_MAIN(TestSynthesize)
#include "tst_synthesize.moc"
