// dsp::smoothKinematics: the slider state from displacement and
// acceleration together, checked against a known motion with known noise; and the opt-in
// preprocessing step that uses it (PreprocessSettings::fuseSliderAcceleration).
#include <QtTest>

#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "core/dsp/kinematic_smoother.hpp"
#include "core/dsp/savitzky_golay.hpp"
#include "core/identify/preprocess.hpp"
#include "core/io/dataset.hpp"

using namespace stickslip::dsp;
using stickslip::io::Signal;

namespace {
const double kPi = std::numbers::pi;
const std::string kShared = STICKSLIP_SHARED_DIR;

// A stick–slip-like motion at 1 kHz: the slider's acceleration jumps (slip onsets and stops),
// so its position has kinks in the second derivative, as on the rig.
struct Motion {
    std::vector<double> x, v, a;
    double dt = 1e-3;
};
Motion stickSlipMotion(size_t n) {
    Motion m;
    double x = 1e-3, v = 0;
    for (size_t i = 0; i < n; ++i) {
        const double t = i * m.dt;
        // 20 Hz oscillation whose acceleration switches sign of an offset every 0.13 s.
        const double a = -std::pow(2 * kPi * 20, 2) * (x - 1e-3) + (std::fmod(t, 0.26) < 0.13 ? 3.0 : -3.0);
        m.x.push_back(x);
        m.v.push_back(v);
        m.a.push_back(a);
        // Semi-implicit Euler at a fine substep keeps x'' = a consistent with the samples.
        for (int s = 0; s < 100; ++s) {
            const double as = -std::pow(2 * kPi * 20, 2) * (x - 1e-3) + (std::fmod(t + s * m.dt / 100, 0.26) < 0.13 ? 3.0 : -3.0);
            v += as * m.dt / 100;
            x += v * m.dt / 100;
        }
    }
    return m;
}

double rms(const std::vector<double>& a, const std::vector<double>& b, size_t skip) {
    double s = 0;
    for (size_t i = skip; i + skip < a.size(); ++i) s += (a[i] - b[i]) * (a[i] - b[i]);
    return std::sqrt(s / static_cast<double>(a.size() - 2 * skip));
}
}  // namespace

class TstKinematicSmoother : public QObject {
    Q_OBJECT
private slots:
    // Noise as on the rig (10 µm, 0.05 m/s², and an accelerometer offset): the fused velocity
    // is an order of magnitude closer to the truth than central differences of the position
    // and several times closer than its Savitzky–Golay derivative (±7 samples), the position is closer than the measurement, and the noise levels and the
    // offset are estimated from the data.
    void fusesDisplacementAndAccelerationWithEstimatedNoise() {
        const Motion m = stickSlipMotion(20000);
        std::mt19937_64 rng(11);
        std::normal_distribution<double> nd;
        std::vector<double> xm = m.x, am = m.a;
        for (double& e : xm) e += 1e-5 * nd(rng);
        for (double& e : am) e += 0.05 + 0.05 * nd(rng);
        const KinematicEstimate k = smoothKinematics(xm, am, m.dt);
        QVERIFY2(k.ok, k.message.c_str());
        QCOMPARE(k.x.size(), m.x.size());
        const double vSg = rms(savitzkyGolay(xm, m.dt, 7, 3, 1), m.v, 50), vFused = rms(k.v, m.v, 50);
        const double xRaw = rms(xm, m.x, 50), xFused = rms(k.x, m.x, 50);
        std::vector<double> vCd(xm.size(), 0.0);
        for (size_t i = 1; i + 1 < xm.size(); ++i) vCd[i] = (xm[i + 1] - xm[i - 1]) / (2 * m.dt);
        const double vCentral = rms(vCd, m.v, 50);
        QVERIFY2(vFused < 0.1 * vCentral && vFused < 0.3 * vSg,
                 qPrintable(QString("velocity error %1 (central differences %2, SG %3)").arg(vFused).arg(vCentral).arg(vSg)));
        QVERIFY2(xFused < 0.7 * xRaw, qPrintable(QString("position error %1 (raw %2)").arg(xFused).arg(xRaw)));
        QVERIFY2(std::abs(k.dispNoise / 1e-5 - 1) < 0.1, qPrintable(QString::number(k.dispNoise)));
        // The acceleration's level is an effective one: its noise plus how far a departs from
        // linear between samples (here a jumps by 6 m/s² every 130 samples).
        QVERIFY2(k.accelNoise > 0.04 && k.accelNoise < 1.0, qPrintable(QString::number(k.accelNoise)));
        QVERIFY2(std::abs(k.accelOffset - 0.05) < 0.02, qPrintable(QString::number(k.accelOffset)));
        // Given levels are used as given.
        KinematicSmootherOptions o;
        o.dispNoise = 2e-5;
        o.accelNoise = 0.1;
        const KinematicEstimate g = smoothKinematics(xm, am, m.dt, o);
        QVERIFY(g.ok && g.dispNoise == 2e-5 && g.accelNoise == 0.1);
        // The likelihood is highest near the estimated level (it is the maximum over σ_a).
        o.dispNoise = k.dispNoise;
        o.accelNoise = 4 * k.accelNoise;
        QVERIFY(smoothKinematics(xm, am, m.dt, o).logLikelihood < k.logLikelihood);
        o.accelNoise = k.accelNoise / 4;
        QVERIFY(smoothKinematics(xm, am, m.dt, o).logLikelihood < k.logLikelihood);
    }

    void noiseFreeInputStaysWithinItsLevel() {
        const Motion m = stickSlipMotion(2000);
        const KinematicEstimate k = smoothKinematics(m.x, m.a, m.dt);
        QVERIFY2(k.ok, k.message.c_str());
        // The position's own third differences (x''' dt³) read as a noise of a few 0.1 µm here;
        // the smoother stays within that of the input.
        QVERIFY2(k.dispNoise < 1e-6 && rms(k.x, m.x, 0) < k.dispNoise,
                 qPrintable(QString("%1 (level %2)").arg(rms(k.x, m.x, 0)).arg(k.dispNoise)));
    }

    void badInputIsRefusedWithItsField() {
        const Motion m = stickSlipMotion(100);
        std::vector<double> x = m.x;
        x[37] = std::nan("");
        KinematicEstimate k = smoothKinematics(x, m.a, m.dt);
        QVERIFY(!k.ok && k.message.find("position sample 37") != std::string::npos && k.x.empty());
        k = smoothKinematics(m.x, std::vector<double>(99, 0.0), m.dt);
        QVERIFY(!k.ok && k.message.find("equal length") != std::string::npos);
        k = smoothKinematics(m.x, m.a, -1.0);
        QVERIFY(!k.ok && k.message.find("dt") != std::string::npos);
        KinematicSmootherOptions o;
        o.accelNoise = -1;
        QVERIFY(o.validate().find("accel_noise") != std::string::npos);
        QVERIFY(!smoothKinematics(m.x, m.a, m.dt, o).ok);
        o.accelNoise = 0;
        o.dispNoise = INFINITY;
        QVERIFY(o.validate().find("disp_noise") != std::string::npos);
        QVERIFY(KinematicSmootherOptions{}.validate().empty());
    }

    // The preprocessing step: off by default; on, it replaces the slider's displacement and
    // velocity of a spring–mass run (D05) and says so; a run without them is left as it is.
    void preprocessingFusesOnlyWhenAskedAndPossible() {
        using namespace stickslip::identify;
        stickslip::io::Run raw;
        stickslip::io::DatasetError err;
        QVERIFY(loadRun(kShared + "/data/synthetic/D05/run_02.csv", {}, raw, err));
        CleanRun off, on;
        std::string why;
        QVERIFY(preprocessRun(raw, PreprocessSettings{}, off, &why));
        PreprocessSettings s;
        s.fuseSliderAcceleration = true;
        QVERIFY2(preprocessRun(raw, s, on, &why), why.c_str());
        auto hasNote = [](const CleanRun& c, const char* text) {
            for (const auto& n : c.notes)
                if (n.find(text) != std::string::npos) return true;
            return false;
        };
        QVERIFY(!hasNote(off, "RTS smoother") && hasNote(on, "RTS smoother"));
        // What the smoother takes out of the displacement (before the filters) is the size of the
        // set's declared 10 µm noise, less the smoother's own error.
        QCOMPARE(on.unfilteredSlider_m.size(), off.unfilteredSlider_m.size());
        double ss = 0;
        for (size_t i = 0; i < on.unfilteredSlider_m.size(); ++i)
            ss += std::pow(on.unfilteredSlider_m[i] - off.unfilteredSlider_m[i], 2);
        const double removed = std::sqrt(ss / on.unfilteredSlider_m.size());
        QVERIFY2(removed > 5e-6 && removed < 1.2e-5, qPrintable(QString::number(removed)));
        QVERIFY(toJson(s)["fuse_slider_acceleration"].get<bool>());
        stickslip::io::Run damper;
        QVERIFY(loadRun(kShared + "/data/real/friction-damper/0.5Hz_36lb_1.5in.csv", {}, damper, err));
        CleanRun d;
        QVERIFY(preprocessRun(damper, s, d, &why));
        QVERIFY(hasNote(d, "fusion skipped"));
    }
};

QTEST_GUILESS_MAIN(TstKinematicSmoother)
#include "tst_kinematic_smoother.moc"
