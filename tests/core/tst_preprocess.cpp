// Preprocessing as in the paper: Butterworth responses, zero-phase filtering, Savitzky–Golay
// differentiation, resampling, trimming of ramps, and the whole chain on measured runs.
#include <QtTest>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "core/dsp/iir.hpp"
#include "core/dsp/sampling.hpp"
#include "core/dsp/savitzky_golay.hpp"
#include "core/identify/identify.hpp"
#include "core/identify/preprocess.hpp"

using namespace stickslip::dsp;
using namespace stickslip::identify;
using stickslip::io::Signal;

namespace {
const double kPi = std::numbers::pi;
const std::string kShared = STICKSLIP_SHARED_DIR;

// Amplitude of the f-component of y (least-squares projection on sin and cos).
double toneAmplitude(const std::vector<double>& y, double f, double fs, size_t b, size_t e) {
    double s = 0, c = 0;
    for (size_t i = b; i < e; ++i) {
        s += y[i] * std::sin(2 * kPi * f * i / fs);
        c += y[i] * std::cos(2 * kPi * f * i / fs);
    }
    return 2.0 * std::hypot(s, c) / static_cast<double>(e - b);
}
}  // namespace

class TstPreprocess : public QObject {
    Q_OBJECT
private slots:
    void lowpassHasButterworthMagnitude() {
        const double fs = 1000, fc = 100;
        const Sos lp = butterworthLowpass(4, fc, fs);
        QCOMPARE(lp.size(), size_t(2));
        QVERIFY(std::abs(sosMagnitude(lp, 0, fs) - 1.0) < 1e-12);
        QVERIFY(std::abs(sosMagnitude(lp, fc, fs) - 1.0 / std::sqrt(2.0)) < 1e-9);  // −3 dB at the cut-off
        // Beyond the cut-off: 4th order, pre-warped: |H| = 1/sqrt(1 + (Ω/Ωc)^8).
        const double W = std::tan(kPi * 200 / fs) / std::tan(kPi * fc / fs);
        QVERIFY(std::abs(sosMagnitude(lp, 200, fs) - 1.0 / std::sqrt(1 + std::pow(W, 8))) < 1e-9);
        QCOMPARE(butterworthLowpass(3, fc, fs).size(), size_t(2));  // odd order: one first-order section
        QVERIFY(std::abs(sosMagnitude(butterworthLowpass(3, fc, fs), fc, fs) - 1.0 / std::sqrt(2.0)) < 1e-9);
        QVERIFY(butterworthLowpass(4, 600, fs).empty());  // above Nyquist: refused
    }

    void bandstopRemovesMainsOnly() {
        const double fs = 1000;
        const Sos bs = butterworthBandstop(2, 55, 65, fs);
        QCOMPARE(bs.size(), size_t(2));  // 4 poles from the order-2 prototype
        QVERIFY(sosMagnitude(bs, 60, fs) < 1e-6);
        QVERIFY(std::abs(sosMagnitude(bs, 55, fs) - 1.0 / std::sqrt(2.0)) < 0.03);
        QVERIFY(std::abs(sosMagnitude(bs, 65, fs) - 1.0 / std::sqrt(2.0)) < 0.03);
        QVERIFY(sosMagnitude(bs, 10, fs) > 0.999);
        QVERIFY(sosMagnitude(bs, 200, fs) > 0.99);
        QVERIFY(sosMagnitude(butterworthBandstop(3, 55, 65, fs), 60, fs) < 1e-6);
    }

    void filtfiltIsZeroPhase() {
        const double fs = 1000;
        std::vector<double> clean, noisy;
        for (int i = 0; i < 4000; ++i) {
            const double t = i / fs;
            clean.push_back(std::sin(2 * kPi * 3 * t + 0.3));
            noisy.push_back(clean.back() + 0.2 * std::sin(2 * kPi * 60 * t) + 0.1 * std::sin(2 * kPi * 180 * t));
        }
        Sos sos = butterworthBandstop(2, 55, 65, fs);
        const Sos lp = butterworthLowpass(4, 100, fs);
        sos.insert(sos.end(), lp.begin(), lp.end());
        const std::vector<double> y = filtfilt(sos, noisy);
        double worst = 0;
        for (size_t i = 200; i < 3800; ++i) worst = std::max(worst, std::abs(y[i] - clean[i]));
        QVERIFY2(worst < 2e-3, qPrintable(QString::number(worst)));  // no phase lag, no mains left
        std::vector<double> err(y.size());
        for (size_t i = 0; i < y.size(); ++i) err[i] = y[i] - clean[i];
        QVERIFY(toneAmplitude(err, 60, fs, 200, 3800) < 1e-4);
        // A causal pass would lag: compare.
        const std::vector<double> c = sosFilter(lp, clean);
        double lagErr = 0;
        for (size_t i = 200; i < 3800; ++i) lagErr = std::max(lagErr, std::abs(c[i] - clean[i]));
        QVERIFY(lagErr > 10 * worst);
    }

    // A short stretch filtered as if continued by zeros equals the middle of a long zero-padded
    // filtfilt, is linear, and the impulse response length grows with the band-stop's sharpness.
    void zeroExtendedFilteringOfAShortStretch() {
        const double fs = 1000;
        Sos sos = butterworthBandstop(2, 55, 65, fs);
        const Sos lp = butterworthLowpass(4, 100, fs);
        sos.insert(sos.end(), lp.begin(), lp.end());
        const size_t L = impulseResponseLength(sos);
        QVERIFY2(L > 50 && L < 5000, qPrintable(QString::number(L)));
        QVERIFY(impulseResponseLength(lp) < L);
        QCOMPARE(impulseResponseLength(Sos{}), size_t{0});
        std::vector<double> x, y;
        for (int i = 0; i < 51; ++i) {
            x.push_back(std::sin(0.3 * i) + 0.01 * i * i);
            y.push_back(std::cos(0.17 * i));
        }
        const std::vector<double> fx = filtfiltZeroExtended(sos, x);
        QCOMPARE(fx.size(), x.size());
        std::vector<double> longer(20000, 0.0);
        std::copy(x.begin(), x.end(), longer.begin() + 10000);
        const std::vector<double> ref = filtfilt(sos, longer);
        double worst = 0, scale = 0;
        for (size_t i = 0; i < x.size(); ++i) {
            worst = std::max(worst, std::abs(fx[i] - ref[10000 + i]));
            scale = std::max(scale, std::abs(ref[10000 + i]));
        }
        QVERIFY2(worst < 1e-5 * scale, qPrintable(QString::number(worst / scale)));
        std::vector<double> sum(x.size());
        for (size_t i = 0; i < x.size(); ++i) sum[i] = 2.0 * x[i] - 3.0 * y[i];
        const std::vector<double> fy = filtfiltZeroExtended(sos, y), fs2 = filtfiltZeroExtended(sos, sum);
        for (size_t i = 0; i < x.size(); ++i) QVERIFY(std::abs(fs2[i] - (2.0 * fx[i] - 3.0 * fy[i])) < 1e-9 * scale);
        QVERIFY(filtfiltZeroExtended(Sos{}, x) == x);
    }

    // filtfilt is exactly (bit for bit) the two-pass definition: odd reflection as long as the
    // impulse response, causal pass, reverse, causal pass, reverse; and the zero-extended form
    // exactly that definition on the zero-padded stretch with the short 3·(2·sections + 1)
    // reflection (its zero margins already hold the filter's memory).
    void filtfiltEqualsTheTwoPassDefinition() {
        const double fs = 1024;
        Sos sos = butterworthBandstop(2, 55, 65, fs);
        const Sos lp = butterworthLowpass(4, 100, fs);
        sos.insert(sos.end(), lp.begin(), lp.end());
        auto twoPass = [&](const std::vector<double>& x, size_t pad) {
            const size_t n = x.size();
            std::vector<double> ext;
            for (size_t i = pad; i >= 1; --i) ext.push_back(2.0 * x[0] - x[i]);
            ext.insert(ext.end(), x.begin(), x.end());
            for (size_t i = 1; i <= pad; ++i) ext.push_back(2.0 * x[n - 1] - x[n - 1 - i]);
            std::vector<double> y = sosFilter(sos, ext);
            std::reverse(y.begin(), y.end());
            y = sosFilter(sos, y);
            std::reverse(y.begin(), y.end());
            return std::vector<double>(y.begin() + static_cast<long>(pad), y.begin() + static_cast<long>(pad + n));
        };
        std::vector<double> x;
        for (int i = 0; i < 3000; ++i) x.push_back(std::sin(0.01 * i) + 0.3 * std::sin(2 * kPi * 60 * i / fs) + (i % 7) * 0.01);
        const size_t L = impulseResponseLength(sos);
        QCOMPARE(impulseResponseLength(sos), L);  // remembered: the same answer
        QVERIFY(L > 100 && L < x.size());
        QVERIFY(filtfilt(sos, x) == twoPass(x, L));
        // A record shorter than the filter's memory: the reflection takes all of it but one sample.
        const std::vector<double> shortX(x.begin(), x.begin() + 200);
        QVERIFY(filtfilt(sos, shortX) == twoPass(shortX, 199));
        std::vector<double> padded(200 + 2 * L, 0.0);
        std::copy(shortX.begin(), shortX.end(), padded.begin() + static_cast<long>(L));
        const std::vector<double> full = twoPass(padded, 3 * (2 * sos.size() + 1));
        QVERIFY(filtfiltZeroExtended(sos, shortX) == std::vector<double>(full.begin() + static_cast<long>(L), full.begin() + static_cast<long>(L + 200)));
        QVERIFY(filtfiltZeroExtended(sos, shortX, 37) != filtfiltZeroExtended(sos, shortX));  // the margin matters
    }

    void savitzkyGolayDifferentiates() {
        const double dt = 0.001;
        std::vector<double> cubic, sine;
        for (int i = 0; i < 200; ++i) {
            const double t = i * dt;
            cubic.push_back(2 + 3 * t - 4 * t * t + 5 * t * t * t);
            sine.push_back(std::sin(2 * kPi * 2 * t));
        }
        const std::vector<double> d = savitzkyGolay(cubic, dt, 7, 3, 1);
        for (int i = 0; i < 200; i += 13) {  // exact for a cubic, ends included
            const double t = i * dt;
            QVERIFY(std::abs(d[i] - (3 - 8 * t + 15 * t * t)) < 1e-8);
        }
        const std::vector<double> s0 = savitzkyGolay(cubic, dt, 7, 3, 0);
        QVERIFY(std::abs(s0[100] - cubic[100]) < 1e-12);
        const std::vector<double> ds = savitzkyGolay(sine, dt, 7, 3, 1);
        QVERIFY(std::abs(ds[100] - 4 * kPi * std::cos(4 * kPi * 0.1)) < 1e-3);
    }

    void resamplingAndPeriod() {
        std::vector<double> t, y;
        double tt = 0;
        for (int i = 0; i < 3000; ++i) {
            t.push_back(tt);
            y.push_back(std::sin(2 * kPi * 1.5 * tt));
            tt += (i % 3 == 0) ? 0.0015 : 0.0008;
        }
        QVERIFY(samplingIrregularity(t) > 0.5);
        const std::vector<double> lin = resampleLinear(t, t, 0.0, 0.001, 100);
        QVERIFY(std::abs(lin[57] - 0.057) < 1e-12);
        QVERIFY(std::abs(estimatePeriod(t, y) - 1.0 / 1.5) < 2e-3);
    }

    void steadyWindowDropsRamps() {
        // 1 Hz, ramp up over 2 s, hold 5 s, ramp down over 2 s, at 100 Hz.
        std::vector<double> y;
        for (int i = 0; i < 900; ++i) {
            const double t = i / 100.0;
            const double env = t < 2 ? t / 2 : (t < 7 ? 1.0 : (9 - t) / 2);
            y.push_back(env * std::sin(2 * kPi * t));
        }
        const auto [b, e] = steadyAmplitudeWindow(y, 100, 0.9);
        QVERIFY(b > 150 && b < 230);
        QVERIFY(e > 670 && e < 760);
    }

    void damperRunIsCleanedAndTrimmed() {
        stickslip::io::Run raw;
        stickslip::io::DatasetError err;
        QVERIFY(loadRun(kShared + "/data/real/friction-damper/0.5Hz_36lb_1.5in.csv", {}, raw, err));
        CleanRun c;
        std::string why;
        QVERIFY2(preprocessRun(raw, PreprocessSettings{}, c, &why), why.c_str());
        QVERIFY(std::abs(c.period_s - 2.0) < 0.02);  // 0.5 Hz drive found from the data
        QVERIFY(c.run.has(Signal::Slip) && c.run.has(Signal::RelVel));
        // The window holds only steady cycles: peak |g| in the window is ≥ 0.9 of the record's peak
        // at its start and end period, and it is several periods long but shorter than the record.
        const auto& g = c.run[Signal::Slip];
        double gmax = 0;
        for (double v : g) gmax = std::max(gmax, std::abs(v));
        double first = 0;
        for (size_t i = c.begin; i < c.begin + 2048; ++i) first = std::max(first, std::abs(g[i]));
        QVERIFY(first > 0.85 * gmax);
        const double len = (c.end - c.begin) * c.dt_s;
        QVERIFY(len > 3 * c.period_s && len < 13.0);
    }

    // The simulated null's replicas are cleaned by recordingPreparer exactly as the pipeline
    // cleans a measured run: preprocessRun, then makeIdentifyRun; its errors name the file.
    void recordingPreparerIsPreprocessThenIdentifyRun() {
        stickslip::io::Run raw;
        stickslip::io::DatasetError err;
        QVERIFY(loadRun(kShared + "/data/real/friction-damper/0.5Hz_36lb_1.5in.csv", {}, raw, err));
        CleanRun c;
        IdentifyRun direct, viaPreparer;
        std::string why;
        QVERIFY(preprocessRun(raw, PreprocessSettings{}, c, &why));
        QVERIFY(makeIdentifyRun(c, stickslip::SetupKind::Prescribed, direct, &why));
        QVERIFY2(recordingPreparer(PreprocessSettings{}, stickslip::SetupKind::Prescribed)(raw, viaPreparer, why), why.c_str());
        QCOMPARE(viaPreparer.t_s, direct.t_s);
        QCOMPARE(viaPreparer.force_N, direct.force_N);
        QCOMPARE(viaPreparer.slip_m, direct.slip_m);
        QCOMPARE(viaPreparer.frequency_Hz, direct.frequency_Hz);
        // The damper has no slider signals: the dynamics set-up refuses it and names the file.
        IdentifyRun dyn;
        QVERIFY(!recordingPreparer(PreprocessSettings{}, stickslip::SetupKind::Dynamics)(raw, dyn, why));
        QVERIFY2(why.find("0.5Hz_36lb_1.5in.csv") != std::string::npos && why.find("slider") != std::string::npos, why.c_str());
    }

    void syntheticRunLosesMainsKeepsSignal() {
        stickslip::io::Run raw;
        stickslip::io::DatasetError err;
        QVERIFY(loadRun(kShared + "/data/synthetic/D05/run_02.csv", {}, raw, err));
        CleanRun c;
        std::string why;
        QVERIFY(preprocessRun(raw, PreprocessSettings{}, c, &why));
        const double fs = 1.0 / c.dt_s;
        const double before = toneAmplitude(raw[Signal::Friction], 60, fs, 1000, 19000);
        const double after = toneAmplitude(c.run[Signal::Friction], 60, fs, 1000, 19000);
        QVERIFY2(before > 0.03 && after < 0.1 * before, qPrintable(QString("%1 -> %2").arg(before).arg(after)));
        // The 3 Hz drive passes untouched.
        QVERIFY(std::abs(toneAmplitude(c.run[Signal::StageDisp], 3, fs, 1000, 19000) -
                         toneAmplitude(raw[Signal::StageDisp], 3, fs, 1000, 19000)) < 1e-6);
        QVERIFY(c.run.has(Signal::SliderVel) && c.run.has(Signal::Slip) && c.run.has(Signal::RelVel));
        // Filters off: the signal is untouched.
        PreprocessSettings off;
        off.filters.bandStop = off.filters.lowPass = false;
        QVERIFY(preprocessRun(raw, off, c, &why));
        QCOMPARE(c.run[Signal::Friction][500], raw[Signal::Friction][500]);
        // Invalid settings are refused with every problem named.
        PreprocessSettings bad;
        bad.filters.lowPass_Hz = 700;
        bad.sgHalfWindow = 0;
        QVERIFY(!preprocessRun(raw, bad, c, &why));
        QVERIFY(why.find("low-pass") != std::string::npos && why.find("Savitzky") != std::string::npos);
    }
};

QTEST_GUILESS_MAIN(TstPreprocess)
#include "tst_preprocess.moc"
