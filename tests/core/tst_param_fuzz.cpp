// Random-parameter fuzzing of the integrators: thousands of parameter sets drawn over every
// documented range and beyond (both laws, both set-ups, extreme ε_T, η, D_c, tiny and huge
// dt), each of which must end in `ok` or a clear failure — never NaN/Inf in the output,
// never more steps than the step budget, never a crash. Plus the step budget's own tests.
//
// STICKSLIP_PARAM_FUZZ_SEED sets the seed (printed on every run, so a failure can be
// replayed); STICKSLIP_PARAM_FUZZ_COUNT the number of draws (default 2000; the sanitizer
// build may lower it).
#include <QtTest>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <numbers>
#include <random>
#include <sstream>

#include "core/integrate/simulate.hpp"
#include "core/params.hpp"

using namespace stickslip;

namespace {

bool startsWith(const std::string& s, const std::string& p) { return s.rfind(p, 0) == 0; }

long envLong(const char* name, long fallback) {
    const char* v = std::getenv(name);
    if (!v || !*v) return fallback;
    char* end = nullptr;
    const long n = std::strtol(v, &end, 10);
    return end && *end == '\0' ? n : fallback;
}

// The step budget every fuzzed run gets: a few forcing cycles at up to 10 000 steps per
// period fit; a tiny dt does not, and must fail fast with "step budget exceeded".
constexpr long kFuzzBudget = 60000;

class Draw {
public:
    explicit Draw(std::uint64_t seed) : rng_(seed) {}
    double uniform(double lo, double hi) { return lo + (hi - lo) * unit(); }
    double logUniform(double lo, double hi) { return lo * std::pow(hi / lo, unit()); }
    bool chance(double p) { return unit() < p; }
    size_t pick(size_t n) { return static_cast<size_t>(unit() * static_cast<double>(n)) % n; }

private:
    double unit() { return static_cast<double>(rng_() >> 11) * 0x1.0p-53; }
    std::mt19937_64 rng_;
};

// A parameter set over the ranges of the parameter table (app/gui/param_specs.cpp, which
// covers MODEL.md's paper ranges with margin) and beyond them for ε_T, η, D_c and dt;
// log-uniform where a range spans decades. A few draws carry a deliberately invalid value.
SimParams drawParams(Draw& d) {
    SimParams p;
    p.law = d.chance(0.5) ? LawKind::RateState : LawKind::Coulomb;
    p.setup = d.chance(0.5) ? SetupKind::Dynamics : SetupKind::Prescribed;
    p.drive.amplitude_m = d.chance(0.03) ? 0.0 : d.chance(0.1) ? d.logUniform(2e-2, 1.0) : d.logUniform(1e-7, 2e-2);
    p.drive.frequency_Hz = d.chance(0.1) ? d.logUniform(1e-3, 1e3) : d.logUniform(0.5, 20.0);
    p.drive.phase_rad = d.uniform(-std::numbers::pi, std::numbers::pi);
    p.rig.normalForce_N = d.chance(0.1) ? d.logUniform(1e-4, 1e4) : d.logUniform(0.1, 50.0);
    p.rig.stiffness_N_per_m = d.chance(0.03) ? 0.0 : d.logUniform(100.0, 5e4);
    p.rig.mass_kg = d.chance(0.1) ? d.logUniform(1e-6, 1e4) : d.logUniform(0.01, 5.0);
    p.rig.damping_Ns_per_m = d.chance(0.1) ? 0.0 : d.logUniform(1e-4, 20.0);
    const double mu = d.uniform(0.0, 1.0);
    const double epsT = d.logUniform(1e1, 1e12);
    p.lawParams<RateStateParams>().mu = p.lawParams<CoulombParams>().mu = mu;
    p.lawParams<RateStateParams>().epsT_N_per_m = p.lawParams<CoulombParams>().epsT_N_per_m = epsT;
    p.lawParams<RateStateParams>().eta_s_per_m = d.logUniform(1e-6, 1e3);
    p.lawParams<RateStateParams>().Dc_m = d.logUniform(1e-10, 1e-1);
    p.lawParams<RateStateParams>().C1 = d.uniform(0.0, 3.0);
    p.lawParams<RateStateParams>().r = d.logUniform(0.01, 100.0);
    p.lawParams<RateStateParams>().vc_mps = d.logUniform(1e-5, 100.0);
    p.cycles = d.uniform(0.3, 3.0);
    p.transientCycles = d.chance(0.7) ? 0.0 : d.uniform(0.0, 1.0);
    p.integration.outputInterval_s = d.chance(0.05) ? d.logUniform(1e-12, 1e6) : d.logUniform(1e-5, 0.1);
    const double T = 1.0 / p.drive.frequency_Hz;
    const double mode = d.uniform(0.0, 1.0);
    if (mode < 0.82) p.integration.dt_s = T / d.logUniform(8.0, 10000.0);   // resolving the forcing
    else if (mode < 0.90) p.integration.dt_s = d.logUniform(1e-12, 1e-7);    // tiny: over the budget
    else p.integration.dt_s = d.logUniform(T / 8.0, 4.0 * T);                // huge: mostly rejected
    p.integration.maxSteps = kFuzzBudget;
    if (d.chance(0.03)) {
        // One parameter made invalid: negative, zero, NaN or infinite.
        const std::vector<std::string> keys = paramKeys();
        const double bad[] = {-1.0, 0.0, std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity(),
                              -std::numeric_limits<double>::infinity()};
        setParam(p, keys[d.pick(keys.size())], bad[d.pick(std::size(bad))]);
    }
    return p;
}

std::string describe(const SimParams& p) {
    std::ostringstream s;
    s.precision(17);
    s << "--model " << toString(p.law) << " --setup " << toString(p.setup);
    for (const std::string& k : paramKeys()) {
        double v = 0;
        getParam(p, k, v);
        if (p.law == LawKind::Coulomb && k == "mu") v = p.lawParams<CoulombParams>().mu;
        if (p.law == LawKind::Coulomb && k == "epsT") v = p.lawParams<CoulombParams>().epsT_N_per_m;
        s << " --set " << k << "=" << v;
    }
    return s.str();
}

// Empty when every output value is finite, else which sample and field is not.
std::string nonFinite(const RunResult& r) {
    for (size_t i = 0; i < r.samples.size(); ++i) {
        const Sample& x = r.samples[i];
        const double v[] = {x.t_s, x.stage_m, x.slider_m, x.sliderVel_mps, x.relVel_mps, x.force_N, x.ratio, x.alpha, x.slipRate_mps};
        for (size_t j = 0; j < std::size(v); ++j)
            if (!std::isfinite(v[j])) return "sample " + std::to_string(i) + " field " + std::to_string(j) + " = " + std::to_string(v[j]);
    }
    for (const Sample& x : r.period.samples)
        if (!std::isfinite(x.force_N) || !std::isfinite(x.slider_m) || !std::isfinite(x.alpha)) return "period sample not finite";
    if (!std::isfinite(r.period.maxRelVel_mps)) return "period maxRelVel not finite";
    return {};
}

// A measured-looking slip history: a random walk of the slip rate, 50–400 samples.
SlipHistory drawHistory(Draw& d) {
    const size_t n = 50 + d.pick(350);
    const double dt = d.logUniform(1e-4, 1e-2);
    const double vmax = d.logUniform(1e-6, 1e3);
    std::vector<double> t(n), v(n);
    double vel = 0.0;
    for (size_t i = 0; i < n; ++i) {
        t[i] = static_cast<double>(i) * dt;
        vel = std::clamp(vel + d.uniform(-0.3, 0.3) * vmax, -vmax, vmax);
        v[i] = vel;
    }
    SlipHistory h = SlipHistory::fromVelocity(t, v, 0.0);
    if (d.chance(0.5)) h.velocity_mps.clear();  // velocity then from the slip's differences
    return h;
}

}  // namespace

class TstParamFuzz : public QObject {
    Q_OBJECT
private slots:
    void budgetMessage() {
        QVERIFY(stepBudgetProblem(100.0, 100).empty());
        const std::string m = stepBudgetProblem(3e11, 2'000'000'000);
        QVERIFY2(startsWith(m, "step budget exceeded: the run needs 3e+11 steps, more than max_steps = 2e+09"), m.c_str());
        QVERIFY(!stepBudgetProblem(std::numeric_limits<double>::quiet_NaN(), 100).empty());
        QVERIFY(!stepBudgetProblem(std::numeric_limits<double>::infinity(), 100).empty());
    }

    void budgetValidated() {
        SimParams p;
        QVERIFY(p.validate().empty());
        QVERIFY(p.integration.maxSteps >= 100'000'000);  // a 10 000-cycle default run fits
        p.integration.maxSteps = 0;
        const std::string m = formatIssues(p.validate());
        QVERIFY2(m.find("max_steps = 0 is out of range: must be >= 1") != std::string::npos, m.c_str());
        QVERIFY(simulate(p).status == RunStatus::Failed);
    }

    // A tiny step over a few cycles would take hours: every set-up fails at once instead.
    void budgetStopsTinySteps_data() {
        QTest::addColumn<int>("setup");
        QTest::addColumn<int>("law");
        QTest::newRow("dynamics rate-state") << int(SetupKind::Dynamics) << int(LawKind::RateState);
        QTest::newRow("dynamics coulomb") << int(SetupKind::Dynamics) << int(LawKind::Coulomb);
        QTest::newRow("prescribed rate-state") << int(SetupKind::Prescribed) << int(LawKind::RateState);
        QTest::newRow("prescribed coulomb") << int(SetupKind::Prescribed) << int(LawKind::Coulomb);
    }
    void budgetStopsTinySteps() {
        QFETCH(int, setup);
        QFETCH(int, law);
        SimParams p;
        p.setup = static_cast<SetupKind>(setup);
        p.law = static_cast<LawKind>(law);
        p.integration.dt_s = 1e-12;
        p.cycles = 5;
        const RunResult r = simulate(p);
        QVERIFY2(r.status == RunStatus::Failed, r.message.c_str());
        QVERIFY2(startsWith(r.message, "step budget exceeded: the run needs 1.66667e+12 steps"), r.message.c_str());
        QCOMPARE(r.stats.steps, 0L);
        // An absurd cycle count is caught before any step count is converted to an integer.
        p.integration.dt_s = 1e-4;
        p.cycles = 1e300;
        QVERIFY(startsWith(simulate(p).message, "step budget exceeded"));
        // Within the budget the same set-up runs.
        p.cycles = 1;
        p.integration.maxSteps = 3334;
        const RunResult ok = simulate(p);
        QVERIFY2(ok.ok(), ok.message.c_str());
        QVERIFY(ok.stats.steps <= 3334);
        p.integration.maxSteps = 3332;
        QVERIFY(startsWith(simulate(p).message, "step budget exceeded"));
    }

    void budgetCountsHistorySubsteps() {
        SimParams p;
        p.setup = SetupKind::Prescribed;
        p.integration.dt_s = 1e-6;
        // 101 samples 0.01 s apart: 100 intervals of 10 000 substeps each.
        std::vector<double> t, v;
        for (int i = 0; i <= 100; ++i) { t.push_back(i * 0.01); v.push_back(0.01); }
        const SlipHistory h = SlipHistory::fromVelocity(t, v);
        p.integration.maxSteps = 999'999;
        const RunResult over = simulate(p, {}, &h);
        QVERIFY2(over.status == RunStatus::Failed, over.message.c_str());
        QVERIFY2(startsWith(over.message, "step budget exceeded: the run needs 1e+06 steps"), over.message.c_str());
        p.integration.maxSteps = 1'000'000;
        const RunResult ok = simulate(p, {}, &h);
        QVERIFY2(ok.ok(), ok.message.c_str());
        QCOMPARE(ok.samples.size(), size_t(101));
    }

    // outputInterval/dt beyond any integer (1e300 / 1e-300 = inf) converts to the budget, not
    // an undefined huge long.
    void outputEveryClampedForAbsurdRatios() {
        IntegrationParams ip;
        ip.dt_s = 1e-300;
        ip.outputInterval_s = 1e300;
        QCOMPARE(ip.outputEvery(), ip.maxSteps);
        ip.maxSteps = 1000;
        ip.outputInterval_s = 1e-290;  // 1e10 steps per output sample
        QCOMPARE(ip.outputEvery(), 1000L);
        ip.outputInterval_s = 5e-298;
        QCOMPARE(ip.outputEvery(), 500L);
    }

    void randomParameterSets() {
        const auto seed = static_cast<std::uint64_t>(envLong("STICKSLIP_PARAM_FUZZ_SEED", 20261124));
        const long count = envLong("STICKSLIP_PARAM_FUZZ_COUNT", 2000);
        qInfo("seed %llu (STICKSLIP_PARAM_FUZZ_SEED), %ld draws (STICKSLIP_PARAM_FUZZ_COUNT), budget %ld steps per run",
              static_cast<unsigned long long>(seed), count, kFuzzBudget);
        Draw d(seed);
        long ok = 0, rejected = 0, overBudget = 0, failed = 0, withHistory = 0;
        long okBy[2][2] = {{0, 0}, {0, 0}};  // [setup][law]
        long steps = 0;
        for (long i = 0; i < count; ++i) {
            const SimParams p = drawParams(d);
            SlipHistory h;
            const bool useHistory = p.setup == SetupKind::Prescribed && d.chance(0.3);
            if (useHistory) h = drawHistory(d);
            const bool valid = p.validate().empty();
            const RunResult r = simulate(p, {}, useHistory ? &h : nullptr);
            const std::string where = "draw " + std::to_string(i) + " (seed " + std::to_string(seed) + "): " + describe(p) +
                                      (useHistory ? " with a random slip history" : "") + "\n  -> " + toString(r.status) +
                                      ": " + r.message;
            QVERIFY2(r.status == RunStatus::Ok || r.status == RunStatus::Failed, where.c_str());
            if (!r.ok()) QVERIFY2(!r.message.empty(), where.c_str());
            if (!valid) QVERIFY2(!r.ok(), where.c_str());
            const std::string bad = nonFinite(r);
            QVERIFY2(bad.empty(), (where + "\n  non-finite output: " + bad).c_str());
            QVERIFY2(r.stats.steps <= kFuzzBudget, where.c_str());
            steps += r.stats.steps;
            withHistory += useHistory;
            if (r.ok()) {
                QVERIFY2(!r.samples.empty(), where.c_str());
                ++ok;
                ++okBy[static_cast<int>(p.setup)][static_cast<int>(p.law)];
            } else if (!valid) {
                ++rejected;
            } else if (startsWith(r.message, "step budget exceeded")) {
                ++overBudget;
            } else {
                ++failed;
                qInfo("clear failure: %s", where.c_str());
            }
        }
        qInfo("%ld draws: %ld ok, %ld rejected by validation, %ld over the step budget, %ld failed in the integrator; "
              "%ld with a slip history; %ld steps in all",
              count, ok, rejected, overBudget, failed, withHistory, steps);
        qInfo("ok per set-up/law: dynamics rate-state %ld, dynamics coulomb %ld, prescribed rate-state %ld, prescribed coulomb %ld",
              okBy[0][0], okBy[0][1], okBy[1][0], okBy[1][1]);
        // Most draws must reach the integrator and finish, in every set-up and law.
        QVERIFY2(ok >= count * 6 / 10, qPrintable(QString("only %1 of %2 draws ran ok").arg(ok).arg(count)));
        for (const auto& bySetup : okBy)
            for (long n : bySetup) QVERIFY(n >= count / 10);
    }
};

QTEST_APPLESS_MAIN(TstParamFuzz)
#include "tst_param_fuzz.moc"
