// core/dsp pieces that became public when they moved out of the run pipeline: the one median
// and the one harmonic fit (the filters, Savitzky–Golay and resampling are in tst_preprocess);
// and the one FFTW planner lock of core/analysis.
#include <QtTest>

#include <random>

#include <Eigen/Dense>
#include <atomic>
#include <chrono>
#include <cmath>
#include <mutex>
#include <numbers>
#include <thread>
#include <vector>

#include "core/analysis/correlation.hpp"
#include "core/analysis/fftw_lock.hpp"
#include "core/analysis/spectrum.hpp"
#include "core/dsp/fourier.hpp"
#include "core/dsp/iir.hpp"
#include "core/dsp/stats.hpp"

using namespace stickslip::dsp;

namespace {
const double kPi = std::numbers::pi;

// The identify loop's stage fit as it was before it used dsp::harmonicFit (identify_prepare.cpp):
// u ≈ c0 + c1 cos ωt + c2 sin ωt by 3 × 3 normal equations; rss of the residual.
struct OldStageFit {
    double c0, c1, c2, rss;
};
OldStageFit oldStageFit(const std::vector<double>& t, const std::vector<double>& u, double f) {
    const double w = 2.0 * M_PI * f;
    Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
    Eigen::Vector3d b = Eigen::Vector3d::Zero();
    for (size_t i = 0; i < t.size(); ++i) {
        const Eigen::Vector3d phi(1.0, std::cos(w * t[i]), std::sin(w * t[i]));
        A += phi * phi.transpose();
        b += phi * u[i];
    }
    const Eigen::Vector3d c = A.ldlt().solve(b);
    double ss = 0;
    for (size_t i = 0; i < t.size(); ++i) {
        const double e = u[i] - (c[0] + c[1] * std::cos(w * t[i]) + c[2] * std::sin(w * t[i]));
        ss += e * e;
    }
    return {c[0], c[1], c[2], ss};
}

// A deterministic, zero-mean-ish disturbance (no random generator: the same numbers everywhere).
double wobble(size_t i) { return 1e-4 * std::sin(0.37 * static_cast<double>(i * i % 1013)); }
}  // namespace

class TstDsp : public QObject {
    Q_OBJECT
private slots:
    // fftwPlanMutex (core/analysis/fftw_lock.hpp) is one lock for the process: the same object
    // on every call and from every thread. The analyses plan under it: while this thread holds
    // it, a spectrum or an autocorrelation on another thread cannot finish; released, they do,
    // and they leave it free again.
    void fftwPlanMutexIsOneLock() {
        std::mutex& lock = stickslip::detail::fftwPlanMutex();
        QCOMPARE(&stickslip::detail::fftwPlanMutex(), &lock);
        std::mutex* fromThread = nullptr;
        std::thread([&] { fromThread = &stickslip::detail::fftwPlanMutex(); }).join();
        QCOMPARE(fromThread, &lock);
        std::vector<double> x(512);
        for (size_t i = 0; i < x.size(); ++i) x[i] = std::sin(2 * kPi * 5.0 * static_cast<double>(i) / 100.0) + wobble(i);
        for (int which = 0; which < 2; ++which) {
            std::atomic<bool> done{false};
            bool ok = false;
            bool finishedWhileHeld = true;
            {
                std::unique_lock<std::mutex> held(lock);
                std::thread worker([&] {
                    ok = which == 0 ? stickslip::powerSpectrum(x, 100.0).ok
                                    : std::abs(stickslip::autocorrelation(x, 100.0, 50).r.at(0) - 1.0) < 1e-12;
                    done = true;
                });
                std::this_thread::sleep_for(std::chrono::milliseconds(150));
                finishedWhileHeld = done.load();
                held.unlock();
                worker.join();  // before any QVERIFY can return
            }
            QVERIFY2(!finishedWhileHeld, which == 0 ? "spectrum" : "autocorrelation");
            QVERIFY(done.load() && ok);
            QVERIFY(lock.try_lock());  // released after planning and destroying
            lock.unlock();
        }
    }

    void groupDelayAtDcOfTheCleaningFilters() {
        // scipy.signal: butter(4, 100, fs=500, output='sos') has −dφ/dω(0) = 1.79833 samples.
        const Sos lp = butterworthLowpass(4, 100.0, 500.0);
        QVERIFY2(std::abs(groupDelayAtDc(lp) - 1.7983296) < 1e-5, qPrintable(QString::number(groupDelayAtDc(lp))));
        // A cascade delays by the sum of its parts; the narrow 60 Hz band-stop adds a third of a
        // sample at DC (scipy's butter(2, [55, 65], 'bandstop', fs=500): 0.330, whose edges are
        // pre-warped differently from this designer's).
        const Sos bs = butterworthBandstop(2, 55.0, 65.0, 500.0);
        Sos both = bs;
        both.insert(both.end(), lp.begin(), lp.end());
        QVERIFY(std::abs(groupDelayAtDc(both) - groupDelayAtDc(lp) - groupDelayAtDc(bs)) < 1e-12);
        QVERIFY2(groupDelayAtDc(bs) > 0.30 && groupDelayAtDc(bs) < 0.36, qPrintable(QString::number(groupDelayAtDc(bs))));
        QCOMPARE(groupDelayAtDc(Sos{}), 0.0);
        QCOMPARE(groupDelayAtDc(Sos{Biquad{0.0, 1.0, 0.0, 0.0, 0.0}}), 1.0);  // a pure delay of one sample
        QVERIFY(std::isnan(groupDelayAtDc(Sos{Biquad{1.0, -1.0, 0.0, 0.0, 0.0}})));  // blocks DC
    }

    void whiteNoiseRmsIgnoresASmoothSignalAndCorners() {
        // A 2 N, 5 Hz sine with a jump every 0.2 s (stick–slip corners) at 1 kHz, plus white noise
        // of 0.05 N: the estimate is the noise's RMS, not the signal's.
        std::mt19937_64 rng(7);
        std::normal_distribution<double> nd(0.0, 1.0);
        std::vector<double> x(20000), clean(20000);
        for (size_t i = 0; i < x.size(); ++i) {
            const double t = 1e-3 * static_cast<double>(i);
            clean[i] = 2.0 * std::sin(2.0 * std::numbers::pi * 5.0 * t) + ((i / 200) % 2 ? 0.5 : -0.5);
            x[i] = clean[i] + 0.05 * nd(rng);
        }
        QVERIFY2(std::abs(whiteNoiseRms(x) / 0.05 - 1.0) < 0.03, qPrintable(QString::number(whiteNoiseRms(x))));
        QVERIFY(whiteNoiseRms(clean) < 0.002);
        QCOMPARE(whiteNoiseRms({1.0, 2.0, 3.0}), 0.0);
    }

    void whiteNoiseRmsOfEveryDifferenceOrder() {
        // Orders 2–4 on a 3 Hz sine at 1 kHz plus 0.01 of white noise (the sine's own first
        // differences are not small, so order 1 is checked on the noise alone); the default
        // order is the third difference.
        std::mt19937_64 rng(7);
        std::normal_distribution<double> nd;
        std::vector<double> y, w;
        for (int i = 0; i < 20000; ++i) {
            w.push_back(0.01 * nd(rng));
            y.push_back(std::sin(2 * std::numbers::pi * 3 * i * 1e-3) + w.back());
        }
        for (int order = 2; order <= 4; ++order) {
            const double s = whiteNoiseRms(y, order);
            QVERIFY2(std::abs(s / 0.01 - 1) < 0.05, qPrintable(QString("order %1: %2").arg(order).arg(s)));
        }
        QVERIFY(std::abs(whiteNoiseRms(w, 1) / 0.01 - 1) < 0.05);
        QCOMPARE(whiteNoiseRms(y), whiteNoiseRms(y, 3));
        QVERIFY(std::isnan(whiteNoiseRms(y, 0)) && std::isnan(whiteNoiseRms(y, 5)));
        QCOMPARE(whiteNoiseRms({1.0, 2.0}, 2), 0.0);
    }

    void medianOddEvenEmpty() {
        QCOMPARE(median({3.0, 1.0, 2.0}), 2.0);
        QCOMPARE(median({5.0, -1.0, 4.0, 9.0, 0.5}), 4.0);
        // Even count: the upper of the two middle values (an element, not their mean).
        QCOMPARE(median({4.0, 1.0, 3.0, 2.0}), 3.0);
        QCOMPARE(median({10.0, 20.0}), 20.0);
        QCOMPARE(median({7.5}), 7.5);
        // Empty: 0 (documented; no exception).
        QCOMPARE(median({}), 0.0);
        // The argument is taken by value: the caller's order is untouched.
        const std::vector<double> v{9, 8, 7, 6, 5};
        QCOMPARE(median(v), 7.0);
        QCOMPARE(v, (std::vector<double>{9, 8, 7, 6, 5}));
    }

    // The unified fit gives the old identify stage fit's coefficients and residual on a drive
    // with an offset, a phase and a disturbance (to rounding: the column order differs).
    void harmonicFitAgreesWithOldStageFit() {
        const double f = 2.5, dt = 1e-3;
        std::vector<double> t, u;
        for (size_t i = 0; i < 4000; ++i) {
            t.push_back(0.2 + static_cast<double>(i) * dt);
            u.push_back(3e-3 + 1.2e-3 * std::cos(2 * kPi * f * t.back() + 0.7) + 2e-5 * std::sin(6 * kPi * f * t.back()) +
                        wobble(i) * 1e-2);
        }
        const OldStageFit old = oldStageFit(t, u, f);
        const HarmonicFit fit = harmonicFit(t, u, f, 1, 0, t.size());
        QCOMPARE(fit.order(), 1);
        QCOMPARE(fit.samples, t.size());
        QVERIFY(std::abs(fit.mean - old.c0) < 1e-15);
        QVERIFY(std::abs(fit.cosine[0] - old.c1) < 1e-15);
        QVERIFY(std::abs(fit.sine[0] - old.c2) < 1e-15);
        QVERIFY(std::abs(fit.rss - old.rss) < 1e-9 * old.rss);
        QVERIFY(std::abs(fit.omega - 2 * M_PI * f) < 1e-15);
        QVERIFY(std::abs(fit.amplitude(1) - std::hypot(old.c1, old.c2)) < 1e-15);
        QCOMPARE(fit.amplitude(2), 0.0);  // beyond the order
        QCOMPARE(fit.amplitude(0), 0.0);
    }

    // Several harmonics are recovered exactly from a noise-free series, over a sub-range; the
    // evaluated fourierFit is the fit's series at every sample and reports the same residual.
    void harmonicFitRecoversSeries() {
        const double f = 1.5;
        std::vector<double> t, y;
        for (size_t i = 0; i < 3000; ++i) {
            t.push_back(static_cast<double>(i) / 500.0);
            const double w = 2 * kPi * f * t.back();
            y.push_back(0.5 + 2.0 * std::cos(w) - 1.0 * std::sin(w) + 0.25 * std::cos(3 * w) + 0.1 * std::sin(2 * w));
        }
        const HarmonicFit fit = harmonicFit(t, y, f, 3, 500, 2500);
        QCOMPARE(fit.order(), 3);
        QVERIFY(std::abs(fit.mean - 0.5) < 1e-10);
        QVERIFY(std::abs(fit.cosine[0] - 2.0) < 1e-10 && std::abs(fit.sine[0] + 1.0) < 1e-10);
        QVERIFY(std::abs(fit.cosine[1]) < 1e-10 && std::abs(fit.sine[1] - 0.1) < 1e-10);
        QVERIFY(std::abs(fit.cosine[2] - 0.25) < 1e-10 && std::abs(fit.sine[2]) < 1e-10);
        QVERIFY(fit.rss < 1e-18);
        double rss = -1;
        const std::vector<double> ev = fourierFit(t, y, f, 3, 500, 2500, &rss);
        QCOMPARE(rss, fit.rss);
        for (size_t i = 0; i < t.size(); i += 97) QCOMPARE(ev[i], fit.at(t[i]));
        QVERIFY(std::abs(ev[10] - y[10]) < 1e-9);  // outside the fitted range too (exact series)
    }

    void refineFrequencyFindsTheDrive() {
        std::vector<double> t, y;
        for (size_t i = 0; i < 20000; ++i) {
            t.push_back(static_cast<double>(i) * 1e-3);
            y.push_back(std::sin(2 * kPi * 3.0012 * t.back()) + wobble(i));
        }
        QVERIFY(std::abs(refineFrequency(t, y, 3.0, 1) - 3.0012) < 1e-5);
    }
};

QTEST_GUILESS_MAIN(TstDsp)
#include "tst_dsp.moc"
