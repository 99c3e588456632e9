// Signal analyses on signals with known answers: PSD (Welch/FFTW), autocorrelation and its
// decay time, cross-correlation phase lag, the 0–1 test, friction-loop orientation.
#include <QtTest>

#include <cmath>
#include <numbers>
#include <random>
#include <thread>

#include "core/analysis/correlation.hpp"
#include "core/analysis/loop_orientation.hpp"
#include "core/analysis/spectrum.hpp"
#include "core/analysis/zero_one_test.hpp"

using namespace stickslip;
constexpr double kPi = std::numbers::pi;

class TstAnalysisSignals : public QObject {
    Q_OBJECT
private slots:
    void psdFindsTonesAndKeepsVariance() {
        const double fs = 1000;
        std::mt19937 rng(7);
        std::normal_distribution<double> noise(0.0, 0.1);
        std::vector<double> x(20000);
        for (std::size_t i = 0; i < x.size(); ++i) {
            const double t = i / fs;
            x[i] = 2.0 + 1.0 * std::sin(2 * kPi * 3.0 * t) + 0.3 * std::sin(2 * kPi * 7.7 * t) + noise(rng);
        }
        const PowerSpectrum s = powerSpectrum(x, fs, {4096, 0.5});
        QVERIFY2(s.ok, s.message.c_str());
        QCOMPARE(s.frequency_Hz.size(), std::size_t(2049));
        QVERIFY(s.segments >= 8);
        // Parseval: Σ psd Δf = variance (0.5 + 0.045 + 0.01, mean removed).
        double power = 0;
        for (std::size_t k = 1; k < s.psd.size(); ++k) power += s.psd[k] * s.resolution_Hz;
        QVERIFY2(std::abs(power - 0.555) < 0.03, qPrintable(QString::number(power)));
        const auto peaks = spectrumPeaks(s, 2);
        QCOMPARE(peaks.size(), std::size_t(2));
        QVERIFY(std::abs(peaks[0].frequency_Hz - 3.0) < s.resolution_Hz);
        QVERIFY(std::abs(peaks[1].frequency_Hz - 7.7) < s.resolution_Hz);
        // Two tones, no broad band: little power off the harmonic lines of 3 Hz.
        // (the 7.7 Hz tone is off the lines of 3 Hz, so it counts as broad band here.)
        const double bb = broadbandFraction(s, 3.0, 1, 3);
        QVERIFY(bb > 0.05 && bb < 0.2);
    }
    void psdRejectsBadInput() {
        QVERIFY(!powerSpectrum({1, 2, 3}, 1000).ok);
        QVERIFY(!powerSpectrum(std::vector<double>(100, 1.0), -1).ok);
        std::vector<double> x(100, 1.0);
        x[5] = std::nan("");
        const PowerSpectrum s = powerSpectrum(x, 1000);
        QVERIFY(!s.ok);
        QVERIFY(!s.message.empty());
    }
    void psdIsThreadSafe() {
        std::vector<double> x(8192);
        for (std::size_t i = 0; i < x.size(); ++i) x[i] = std::sin(0.1 * i);
        const PowerSpectrum ref = powerSpectrum(x, 100.0);
        std::vector<PowerSpectrum> out(4);
        std::vector<std::thread> th;
        for (int k = 0; k < 4; ++k) th.emplace_back([&, k] { out[k] = powerSpectrum(x, 100.0); });
        for (auto& t : th) t.join();
        for (const auto& o : out) QVERIFY(o.psd == ref.psd);
    }
    void autocorrelationOfSineDoesNotDecay() {
        const double fs = 200;
        std::vector<double> x(4000);
        for (std::size_t i = 0; i < x.size(); ++i) x[i] = std::sin(2 * kPi * 3.0 * i / fs);
        const Correlation ac = autocorrelation(x, fs, 400);
        QCOMPARE(ac.r.size(), std::size_t(401));
        QCOMPARE(ac.r[0], 1.0);
        // One period later (lag 1/3 s ≈ 66.7 samples) the biased estimate is ≈ (1 − lag/n).
        QVERIFY(ac.r[67] > 0.95);
        QVERIFY(std::isnan(correlationDecayTime(ac)));
    }
    void autocorrelationOfAr1DecaysAtItsTime() {
        // x_i = a x_{i−1} + e_i: r(k) = a^k, decay to 1/e at k = −1/ln a.
        const double a = 0.95, fs = 100;
        std::mt19937 rng(3);
        std::normal_distribution<double> e(0.0, 1.0);
        std::vector<double> x(200000);
        for (std::size_t i = 1; i < x.size(); ++i) x[i] = a * x[i - 1] + e(rng);
        const Correlation ac = autocorrelation(x, fs, 500);
        const double tau = correlationDecayTime(ac);
        const double expected = -1.0 / std::log(a) / fs;  // 0.195 s
        QVERIFY2(std::abs(tau - expected) < 0.15 * expected, qPrintable(QString::number(tau)));
        QVERIFY(autocorrelation(std::vector<double>(10, 2.0), fs, 5).r.empty());
    }
    void crossCorrelationAndPhaseLag() {
        const double fs = 1000, f = 3.0, tau = 0.02, wn = 126.0;
        std::vector<double> u(6000), x(6000);
        for (std::size_t i = 0; i < u.size(); ++i) {
            const double t = i / fs;
            u[i] = 1e-3 * std::sin(2 * kPi * f * t);
            x[i] = 0.4e-3 * std::sin(2 * kPi * f * (t - tau));  // slider lags by 20 ms
        }
        const Correlation c = crossCorrelation(u, x, fs, 100);
        QCOMPARE(c.r.size(), std::size_t(201));
        QCOMPARE(c.lag_s.front(), -0.1);
        const PhaseLag lag = stageSliderPhaseLag(u, x, fs, f, wn);
        QVERIFY(lag.ok);
        QVERIFY2(std::abs(lag.lag_s - tau) < 0.5 / fs, qPrintable(QString::number(lag.lag_s)));
        QVERIFY(std::abs(lag.nondimensional - tau * wn) < 0.5 / fs * wn);
        QVERIFY(std::abs(lag.fractionOfPeriod - tau * f) < 0.01);
        QVERIFY(lag.peak > 0.95);
        // Slider leading: negative lag.
        const PhaseLag lead = stageSliderPhaseLag(x, u, fs, f, wn);
        QVERIFY(std::abs(lead.lag_s + tau) < 0.5 / fs);
    }
    void zeroOneTestSeparatesChaosFromOrder() {
        std::vector<double> logistic(2000), periodic(2000), quasi(2000);
        double v = 0.3;
        for (auto& s : logistic) { v = 3.97 * v * (1 - v); s = v; }
        for (std::size_t i = 0; i < periodic.size(); ++i) periodic[i] = (i % 3 == 0) ? 0.2 : (i % 3 == 1 ? 0.5 : 0.9);
        for (std::size_t i = 0; i < quasi.size(); ++i) quasi[i] = std::cos(2 * kPi * 0.6180339887 * i);
        const ZeroOneResult zc = zeroOneTest(logistic), zp = zeroOneTest(periodic), zq = zeroOneTest(quasi);
        QVERIFY(zc.ok && zp.ok && zq.ok);
        QVERIFY2(zc.K > 0.9, qPrintable(QString::number(zc.K)));
        QVERIFY2(std::abs(zp.K) < 0.1, qPrintable(QString::number(zp.K)));
        QVERIFY2(std::abs(zq.K) < 0.1, qPrintable(QString::number(zq.K)));
        QCOMPARE(int(zc.Kc.size()), ZeroOneOptions{}.nc);
        // A fixed point (period-1 section with rounding noise) is regular by definition.
        std::vector<double> fixed(500, 1.234e-3);
        for (std::size_t i = 0; i < fixed.size(); ++i) fixed[i] += 1e-15 * ((i * 7919) % 13);
        const ZeroOneResult zf = zeroOneTest(fixed);
        QVERIFY(zf.ok);
        QCOMPARE(zf.K, 0.0);
        QVERIFY(!zeroOneTest(std::vector<double>(20, 1.0)).ok);
    }
    void loopOrientationCountsBothSenses() {
        // V = cos, ρ = sin traces a counter-clockwise circle; ρ = −sin a clockwise one.
        const double T = 0.5, fs = 400;
        std::vector<double> t, V, ccw, cw, flat;
        for (int i = 0; i < 5 * 200 + 1; ++i) {
            const double ti = i / fs;
            t.push_back(ti);
            V.push_back(std::cos(2 * kPi * ti / T));
            ccw.push_back(std::sin(2 * kPi * ti / T));
            cw.push_back(-std::sin(2 * kPi * ti / T));
            flat.push_back(0.25);
        }
        const LoopOrientation a = frictionLoopOrientation(t, V, ccw, T);
        QCOMPARE(a.counterClockwise, 5);
        QCOMPARE(a.clockwise, 0);
        QVERIFY(std::abs(a.signedArea[0] - kPi) < 1e-3);
        const LoopOrientation b = frictionLoopOrientation(t, V, cw, T);
        QCOMPARE(b.clockwise, 5);
        QCOMPARE(b.counterClockwise, 0);
        const LoopOrientation c = frictionLoopOrientation(t, V, flat, T);
        QCOMPARE(c.degenerate, 5);
        QCOMPARE(frictionLoopOrientation(t, V, ccw, -1.0).signedArea.size(), std::size_t(0));
    }
};

QTEST_GUILESS_MAIN(TstAnalysisSignals)
#include "tst_analysis_signals.moc"
