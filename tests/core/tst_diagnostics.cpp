// Residual diagnostics: autocorrelation, Ljung–Box, spectrum, correlations with signals.
#include <QtTest/QtTest>

#include <cmath>
#include <random>

#include "core/identify/diagnostics.hpp"

using namespace stickslip::identify;

namespace {
std::vector<double> whiteNoise(size_t n, unsigned seed) {
    std::mt19937 rng(seed);
    std::normal_distribution<double> nd(0.0, 1.0);
    std::vector<double> x(n);
    for (double& v : x) v = nd(rng);
    return x;
}
}  // namespace

class TestDiagnostics : public QObject {
    Q_OBJECT
private slots:
    void chiSquareTail() {
        QVERIFY(std::abs(chiSquareSurvival(3.841458820694124, 1) - 0.05) < 1e-6);
        QVERIFY(std::abs(chiSquareSurvival(18.307038053275146, 10) - 0.05) < 1e-6);
        QVERIFY(std::abs(chiSquareSurvival(2.0, 2) - std::exp(-1.0)) < 1e-10);
        QCOMPARE(chiSquareSurvival(0.0, 5), 1.0);
    }
    void studentTDistribution() {
        // Table values (e.g. Abramowitz & Stegun 26.10): t_{0.95} and t_{0.975}.
        const struct { double p, dof, t; } table[] = {{0.95, 3, 2.353363434801823}, {0.975, 3, 3.182446305284263},
                                                      {0.95, 4, 2.131846786326649}, {0.975, 4, 2.776445105197793},
                                                      {0.975, 1, 12.70620473617471}, {0.975, 1e6, 1.959966},
                                                      {0.5, 7, 0.0}};
        for (const auto& c : table) {
            QVERIFY2(std::abs(studentTQuantile(c.p, c.dof) - c.t) < 1e-5 * std::max(1.0, c.t),
                     qPrintable(QString("p %1 dof %2: %3").arg(c.p).arg(c.dof).arg(studentTQuantile(c.p, c.dof))));
            QVERIFY(std::abs(studentTSurvival(c.t, c.dof) - (1.0 - c.p)) < 1e-6);
        }
        QVERIFY(std::abs(studentTSurvival(1.0, 1) - 0.25) < 1e-12);  // Cauchy: 1/2 − atan(1)/π
        QVERIFY(std::abs(studentTSurvival(-2.0, 5) + studentTSurvival(2.0, 5) - 1.0) < 1e-12);
        QVERIFY(std::isnan(studentTQuantile(1.0, 3)));
        QVERIFY(std::isnan(studentTSurvival(1.0, 0)));
    }
    void gammaDistribution() {
        // χ²_1 and χ²_2 are gammas of shape 1/2 and 1, scale 2: their 95 % points 3.841 and −2 ln 0.05.
        QVERIFY(std::abs(gammaQuantile(0.95, 0.5, 2.0) - 3.841458820694124) < 1e-8);
        QVERIFY(std::abs(gammaQuantile(0.95, 1.0, 2.0) + 2.0 * std::log(0.05)) < 1e-8);
        QVERIFY(std::abs(gammaQuantile(0.95, 5.0, 2.0) - 18.307038053275146) < 1e-7);  // χ²_10
        QVERIFY(std::abs(gammaCdf(2.0, 1.0, 1.0) - (1.0 - std::exp(-2.0))) < 1e-12);
        QVERIFY(std::abs(gammaCdf(30.0, 20.0, 1.0) - (1.0 - chiSquareSurvival(60.0, 40))) < 1e-9);  // continued fraction side
        for (double p : {0.01, 0.5, 0.99}) QVERIFY(std::abs(gammaCdf(gammaQuantile(p, 3.7, 0.2), 3.7, 0.2) - p) < 1e-10);
        QVERIFY(std::isnan(gammaQuantile(1.0, 1.0, 1.0)));
        QVERIFY(std::isnan(gammaCdf(1.0, 0.0, 1.0)));
    }
    void pairedTestAndJackknife() {
        // d = ln 2 in every unit: no spread, infinitely significant.
        const PairedTest same = pairedLogRatioTest({2, 4, 8}, {1, 2, 4});
        QCOMPARE(same.units, 3);
        QVERIFY(std::abs(same.meanLogRatio - std::log(2.0)) < 1e-12);
        QCOMPARE(same.pValue, 0.0);
        // d = ln(1.5), ln(1.1), ln(0.9), ln(1.2): mean 0.1133, sd 0.1986, t = 1.1410, 3 dof.
        const std::vector<double> b = {1.5, 1.1, 0.9, 1.2}, a = {1, 1, 1, 1};
        const PairedTest mixed = pairedLogRatioTest(b, a);
        double m = 0, ss = 0;
        for (double v : b) m += std::log(v) / 4;
        for (double v : b) ss += (std::log(v) - m) * (std::log(v) - m);
        const double t = m / std::sqrt(ss / 3 / 4);
        QVERIFY(std::abs(mixed.t - t) < 1e-12);
        QVERIFY(std::abs(mixed.pValue - studentTSurvival(t, 3)) < 1e-15);
        QVERIFY(mixed.pValue > 0.05);  // one worse unit out of four: not significant
        // Exact sign-flip test. The mixed case: |d| = ln1.5, ln1.1, ln(1/0.9), ln1.2; of the 16 sign
        // patterns, those whose sum is ≥ the observed one (only ln 0.9 negative) are counted
        // by brute force here.
        {
            const double ad[4] = {std::log(1.5), std::log(1.1), std::log(1.0 / 0.9), std::log(1.2)};
            const double obs = std::log(1.5) + std::log(1.1) + std::log(0.9) + std::log(1.2);
            int n = 0;
            for (int pat = 0; pat < 16; ++pat) {
                double sum = 0;
                for (int i = 0; i < 4; ++i) sum += ((pat >> i) & 1) ? -ad[i] : ad[i];
                if (sum >= obs - 1e-12) ++n;
            }
            QCOMPARE(mixed.exactP, n / 16.0);
            QCOMPARE(n, 3);  // all +, only the smallest flipped, only ln(1/0.9) flipped
            // The mid-p counts the observed pattern half: (2 + ½)/16.
            QCOMPARE(mixed.midP, 2.5 / 16.0);
        }
        // Every one of five runs better, by very different amounts (D03's frictional lag): the
        // t-test is not significant, the exact test gives its smallest p, 1/32.
        const PairedTest hetero = pairedLogRatioTest({std::exp(0.39), std::exp(0.11), std::exp(0.08), std::exp(1.39), std::exp(0.08)},
                                                     {1, 1, 1, 1, 1});
        QVERIFY(hetero.pValue > 0.05);
        QCOMPARE(hetero.exactP, 1.0 / 32.0);
        QCOMPARE(hetero.midP, 0.5 / 32.0);
        // Tied patterns count half with the observed one: |d| all equal, one of four negative; the
        // sums ≥ the observed are the all-positive pattern (above) and the four with one flip (tied).
        const PairedTest tied = pairedLogRatioTest({2, 2, 2, 1}, {1, 1, 1, 2});
        QCOMPARE(tied.exactP, 5.0 / 16.0);
        QCOMPARE(tied.midP, 3.0 / 16.0);
        // Under the null every sign pattern is equally likely: the mid-p averages ½ over them.
        {
            const double ad[5] = {0.3, 0.1, 0.7, 0.2, 0.05};
            double mean = 0;
            for (int pat = 0; pat < 32; ++pat) {
                std::vector<double> b, a;
                for (int i = 0; i < 5; ++i) {
                    b.push_back(std::exp(((pat >> i) & 1) ? -ad[i] : ad[i]));
                    a.push_back(1.0);
                }
                mean += pairedLogRatioTest(b, a).midP / 32.0;
            }
            QVERIFY2(std::abs(mean - 0.5) < 1e-12, qPrintable(QString::number(mean)));
        }
        // Beyond 20 units no enumeration: NaN.
        QVERIFY(std::isnan(pairedLogRatioTest(std::vector<double>(21, 2.0), std::vector<double>(21, 1.0)).exactP));
        // Missing units are skipped; fewer than two: no test.
        QCOMPARE(pairedLogRatioTest({1, 0, 2}, {0.5, 1, 1}).units, 2);
        QVERIFY(std::isnan(pairedLogRatioTest({1}, {0.5}).pValue));
        // Jackknife of the mean: the leave-one-out means give exactly sd/√K.
        const std::vector<double> x = {1.0, 2.0, 4.0, 7.0, 11.0};
        std::vector<double> loo;
        double sum = 0;
        for (double v : x) sum += v;
        for (double v : x) loo.push_back((sum - v) / 4.0);
        double mx = sum / 5, sx = 0;
        for (double v : x) sx += (v - mx) * (v - mx);
        QVERIFY(std::abs(jackknifeStderr(loo) - std::sqrt(sx / 4.0 / 5.0)) < 1e-12);
        QVERIFY(std::isnan(jackknifeStderr({1.0})));
    }
    void autocorrelationOfNoiseAndSine() {
        const auto w = whiteNoise(20000, 1);
        const auto acf = autocorrelation(w, 10);
        QCOMPARE(acf[0], 1.0);
        for (int k = 1; k <= 10; ++k) QVERIFY(std::abs(acf[k]) < 0.03);
        std::vector<double> s(20000);
        for (size_t i = 0; i < s.size(); ++i) s[i] = std::sin(2 * M_PI * i / 100.0);
        const auto as = autocorrelation(s, 50);
        QVERIFY(std::abs(as[25]) < 0.01);   // quarter period
        QVERIFY(as[50] < -0.98);             // half period
        QVERIFY(integratedAcfTime(acf) < 1.2);
        QVERIFY(integratedAcfTime(as) > 5.0);
    }
    void ljungBoxSeparatesWhiteFromCorrelated() {
        const auto w = whiteNoise(5000, 7);
        double Q = 0, p = 0;
        ljungBox(autocorrelation(w, 20), w.size(), 20, Q, p);
        QVERIFY(p > 0.01);
        std::vector<double> ar(5000);
        ar[0] = w[0];
        for (size_t i = 1; i < ar.size(); ++i) ar[i] = 0.5 * ar[i - 1] + w[i];
        ljungBox(autocorrelation(ar, 20), ar.size(), 20, Q, p);
        QVERIFY(p < 1e-6);
        QVERIFY(Q > 1000);
    }
    void spectrumFindsTheForcingHarmonics() {
        const double dt = 1e-3, f = 5.0;
        std::vector<double> x(8000);
        for (size_t i = 0; i < x.size(); ++i) x[i] = std::sin(2 * M_PI * f * i * dt) + 0.3 * std::sin(2 * M_PI * 3 * f * i * dt);
        const Spectrum sp = powerSpectrum(x, dt, f);
        size_t kmax = 1;
        for (size_t k = 1; k < sp.power.size(); ++k) if (sp.power[k] > sp.power[kmax]) kmax = k;
        QVERIFY(std::abs(sp.frequency_Hz[kmax] - f) < 0.2);
        QVERIFY(sp.harmonics_Hz.size() >= 3);
        QVERIFY(std::abs(sp.harmonics_Hz[2] - 15.0) < 1e-12);
        QVERIFY(sp.harmonicFraction > 0.95);
        const Spectrum sw = powerSpectrum(whiteNoise(8000, 3), dt, f);
        QVERIFY(sw.harmonicFraction < 0.2);
    }
    void pearsonBasics() {
        QVERIFY(std::abs(pearson({1, 2, 3, 4}, {2, 4, 6, 8}) - 1.0) < 1e-12);
        QVERIFY(std::abs(pearson({1, 2, 3, 4}, {8, 6, 4, 2}) + 1.0) < 1e-12);
        QCOMPARE(pearson({1, 1, 1}, {1, 2, 3}), 0.0);
    }
    void candidateSignalsOfASine() {
        DiagnosticRun r;
        const double dt = 1e-3, f = 2.0;
        for (int i = 0; i < 2000; ++i) {
            const double t = i * dt;
            r.t_s.push_back(t);
            r.slip_m.push_back(1e-3 * std::sin(2 * M_PI * f * t));
            r.relVel_mps.push_back(1e-3 * 2 * M_PI * f * std::cos(2 * M_PI * f * t));
            r.residual.push_back(0.0);
        }
        r.normalForce_N = 5.0;
        r.forcingFrequency_Hz = f;
        r.runIndex = 2;
        const auto names = candidateSignalNames();
        const auto s = candidateSignals(r, 1e-3);
        QCOMPARE(s.size(), names.size());
        QCOMPARE(names[6], std::string("time_since_reversal"));
        // V turns negative at t = 0.125 s and counts as sliding once |V| ≥ 1 mm/s, δ later:
        // at t = 0.175 s time_since_reversal = −(0.05 − δ) (signed by V).
        const double delta = std::asin(1e-3 / (1e-3 * 2 * M_PI * f)) / (2 * M_PI * f);
        QVERIFY(std::abs(s[6][175] + (0.05 - delta)) < 2e-3);
        QCOMPARE(s[9][175], -5.0);  // t_N signed by the slip direction
        QCOMPARE(s[11][1900], 3.0);  // fourth cycle, positive slip
        QVERIFY(s[8][1999] > 0.0155 && s[8][1999] < 0.0161);  // ≈ 4 cycles × 4 × 1 mm accumulated slip
    }
    void diagnosePointsToTheSignalInTheResidual() {
        std::vector<DiagnosticRun> runs(2);
        const auto noise = whiteNoise(8000, 11);
        for (int r = 0; r < 2; ++r) {
            for (int i = 0; i < 4000; ++i) {
                const double t = i * 1e-3;
                const double v = 0.05 * std::cos(2 * M_PI * 3 * t);
                runs[r].t_s.push_back(t);
                runs[r].relVel_mps.push_back(v);
                runs[r].slip_m.push_back(0.05 / (2 * M_PI * 3) * std::sin(2 * M_PI * 3 * t));
                runs[r].residual.push_back(0.3 * (v > 0 ? 1 : -1) + 0.1 * noise[r * 4000 + i]);
            }
            runs[r].forcingFrequency_Hz = 3;
            runs[r].runIndex = r;
        }
        const Diagnostics d = diagnose(runs, 5, 1e-3);
        double best = 0;
        std::string which;
        for (const auto& c : d.correlations)
            if (std::abs(c.correlation) > best) { best = std::abs(c.correlation); which = c.signal; }
        QCOMPARE(which, std::string("signV"));
        QVERIFY(best > 0.9);
        QVERIFY(!d.whiteness.white);
        QVERIFY(d.spectrum.harmonicFraction > 0.5);
        // The run-to-run structure test runs by default and only then: skipping it changes nothing else.
        QCOMPARE(d.structure.runs, 2);
        const Diagnostics skipped = diagnose(runs, 5, 1e-3, StructureCheck::Skip);
        QCOMPARE(skipped.structure.runs, 0);
        QVERIFY(skipped.structure.logRatios.empty());
        QCOMPARE(skipped.correlations.size(), d.correlations.size());
        for (size_t k = 0; k < d.correlations.size(); ++k) QCOMPARE(skipped.correlations[k].correlation, d.correlations[k].correlation);
        QCOMPARE(skipped.integratedAcfTime, d.integratedAcfTime);
        QCOMPARE(skipped.whiteness.pValue, d.whiteness.pValue);
        // Pure noise: white.
        for (int r = 0; r < 2; ++r)
            for (int i = 0; i < 4000; ++i) runs[r].residual[i] = noise[r * 4000 + i];
        QVERIFY(diagnose(runs, 1, 1e-3).whiteness.white);
    }
    // The ratio measures the slow part's size: near 0 for white noise, small for a slow model error
    // that Ljung–Box already flags (p ≈ 0) but that carries far less variance than the noise,
    // large for one as large as the noise. (No verdict rests on it: residualStructure's test.)
    void structureRatioMeasuresTheSizeOfTheStructure() {
        std::vector<DiagnosticRun> runs(2);
        const auto noise = whiteNoise(8000, 5);
        auto fill = [&](double slowAmp) {
            for (int r = 0; r < 2; ++r) {
                runs[r].t_s.clear(); runs[r].residual.clear(); runs[r].relVel_mps.clear(); runs[r].slip_m.clear();
                for (int i = 0; i < 4000; ++i) {
                    const double t = i * 1e-3;
                    runs[r].t_s.push_back(t);
                    runs[r].relVel_mps.push_back(std::cos(2 * M_PI * 3 * t));
                    runs[r].slip_m.push_back(std::sin(2 * M_PI * 3 * t));
                    runs[r].residual.push_back(noise[r * 4000 + i] + slowAmp * std::sin(2 * M_PI * 3 * t));
                }
                runs[r].forcingFrequency_Hz = 3;
            }
            return diagnose(runs, 1, 1e-3).whiteness;
        };
        const Whiteness w0 = fill(0.0);
        QVERIFY(std::abs(w0.structureRatio) < 0.1);
        const Whiteness wSmall = fill(0.3);  // slow error with 4.5 % of the noise variance
        QVERIFY(!wSmall.white);
        qInfo("structure ratio: noise %.4f, small %.4f, big %.4f", w0.structureRatio, wSmall.structureRatio, fill(1.5).structureRatio);
        QVERIFY(wSmall.structureRatio < 0.15);
        const Whiteness wBig = fill(1.5);    // as much slow variance as noise
        QVERIFY(!wBig.white);
        QVERIFY(wBig.structureRatio > 0.8);
    }
};

QTEST_GUILESS_MAIN(TestDiagnostics)
#include "tst_diagnostics.moc"
