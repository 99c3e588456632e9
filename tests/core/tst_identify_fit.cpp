// fitSpec (identify_fit.cpp), the identify loop's one fit of a model to runs: its second pass in
// the law's own coordinates C1, η, v_c is for fits in the steady-state curve's coordinates that
// never left their start at the edge of their feasible region, not for those that start at their
// optimum; errorsOf's held-out refits that met that edge are continued there. errorsOf's
// leave-one-run-out refits and the loop's parallelFor: the same numbers on any thread layout.
// Prescribed runs made by the project's own simulator (identify_synth.hpp).
#include <QtTest/QtTest>

#include <cmath>
#include <mutex>
#include <set>
#include <thread>

#include "core/identify/identify_internal.hpp"
#include "identify_synth.hpp"

using namespace stickslip;
using namespace stickslip::identify;
using namespace stickslip::identify::detail;

// Four prescribed runs of the project's own simulator, prepared as identify prepares them (the
// context points into the options and the runs, so the three live together and stay put).
struct PreparedRuns {
    IdentifyOptions opt = synth::testOptions();
    std::vector<IdentifyRun> runs = synth::makeRuns(synth::trueModel(), 2.0, 0.02, 1);
    Context cx;
    std::string why;
    bool ok = false;
    PreparedRuns() {
        int dec = 0;
        ok = prepareContext(runs, opt, cx, dec, why);
    }
    PreparedRuns(const PreparedRuns&) = delete;
    PreparedRuns& operator=(const PreparedRuns&) = delete;
};

class TestIdentifyFit : public QObject {
    Q_OBJECT
private slots:
    // A refit from the optimum a fit already reached ends where it started. Session 51 measured
    // 15 such fits on D13 and D05 each done a second time in C1, η, v_c, every one ending at
    // exactly the same sum of squares: at a stationary point a second coordinate system finds
    // nothing the first did not. It is one fit, and the curve coordinates never left C1's and
    // η's bounds.
    void aStartAtItsOptimumIsFittedOnce() {
        const PreparedRuns p;
        QVERIFY2(p.ok, p.why.c_str());
        const Context& cx = p.cx;
        QVERIFY(p.opt.curveCoordinates);
        const std::vector<size_t> idx = {0, 1, 2, 3};
        const Spec spec;
        long fits = 0;
        FitOutcome f = fitSpec(cx, spec, baselineStart(cx, idx), idx, 1, fits, true);
        QVERIFY2(f.ok, f.message.c_str());
        // Refit until a refit no longer moves (the optimum to the solver's tolerances).
        bool stalled = false;
        for (int k = 0; k < 6 && !stalled; ++k) {
            const long before = fits;
            FitOutcome g = fitSpec(cx, spec, f.values, idx, 1, fits);
            QVERIFY2(g.ok, g.message.c_str());
            stalled = neverMoved(g);
            qInfo("refit %d: ss %.9g -> %.9g, %ld fit(s), %ld outside the law's bounds, stalled %d", k, f.ss, g.ss,
                  fits - before, g.outsideLawBounds, int(stalled));
            if (stalled) {
                QCOMPARE(g.outsideLawBounds, 0L);
                QCOMPARE(fits - before, 1L);
                QCOMPARE(g.ss, f.ss);
            }
            QVERIFY(g.ss <= f.ss * (1.0 + 1e-12));
            f = std::move(g);
        }
        QVERIFY2(stalled, "no refit ended at its start: the premise of this test does not hold");
    }

    // IdentifyOptions::analyticJacobian: the baseline from its far start and a candidate
    // warm-started in the steady-state curve's coordinates (the chain rule through κ, s, v_c)
    // end where the differenced fits end, within the solver's tolerance, with standard errors
    // that agree; the sensitivities' fits take fewer residual vectors.
    void sensitivityJacobianReachesTheDifferencedOptimum() {
        PreparedRuns diff;
        PreparedRuns sens;
        QVERIFY2(diff.ok && sens.ok, (diff.why + sens.why).c_str());
        sens.opt.analyticJacobian = true;
        const std::vector<size_t> idx = {0, 1, 2, 3};
        long fits = 0;
        const FitOutcome d0 = fitSpec(diff.cx, Spec{}, baselineStart(diff.cx, idx), idx, 1, fits, true);
        const FitOutcome s0 = fitSpec(sens.cx, Spec{}, baselineStart(sens.cx, idx), idx, 1, fits, true);
        QVERIFY2(d0.ok && s0.ok, (d0.message + s0.message).c_str());
        Spec lag;
        lag.effects = {"frictional_lag"};
        std::map<std::string, double> start = d0.values;
        start["frictional_lag.tau_s"] = 2e-3;
        const FitOutcome d1 = fitSpec(diff.cx, lag, start, idx, 1, fits, false, FitStart::NearOptimum);
        const FitOutcome s1 = fitSpec(sens.cx, lag, start, idx, 1, fits, false, FitStart::NearOptimum);
        QVERIFY2(d1.ok && s1.ok, (d1.message + s1.message).c_str());
        for (const auto& [d, s] : {std::pair{&d0, &s0}, std::pair{&d1, &s1}}) {
            qInfo("ss differenced %.9g (%ld residual vectors), sensitivities %.9g (%ld)", d->ss, d->fit.residualEvaluations, s->ss,
                  s->fit.residualEvaluations);
            QVERIFY(std::abs(s->ss - d->ss) <= 1e-4 * d->ss);
            for (const ParamEstimate& e : d->estimates) {
                const auto it = std::find_if(s->estimates.begin(), s->estimates.end(),
                                             [&](const ParamEstimate& x) { return x.name == e.name; });
                QVERIFY(it != s->estimates.end());
                if (!std::isfinite(e.stderr_)) continue;  // not identifiable: no scale to compare on
                QVERIFY2(std::abs(it->value - e.value) <= 0.1 * e.stderr_ + 1e-9 * std::abs(e.value), e.name.c_str());
                QVERIFY2(std::abs(it->stderr_ / e.stderr_ - 1.0) < 0.05, e.name.c_str());
            }
            QVERIFY(s->fit.residualEvaluations < d->fit.residualEvaluations);
        }
    }

    // A parallelFor inside another's task runs on that task's thread (identify_internal.hpp):
    // every index once, and the caller's thread is outside any task again afterwards.
    void nestedParallelForRunsOnTheTasksThread() {
        constexpr size_t kOuter = 5, kInner = 7;
        std::vector<std::thread::id> outerId(kOuter);
        std::vector<std::vector<std::thread::id>> innerId(kOuter, std::vector<std::thread::id>(kInner));
        std::vector<int> hits(kOuter * kInner, 0);
        parallelFor(kOuter, [&](size_t i) {
            outerId[i] = std::this_thread::get_id();
            QVERIFY(tInParallelTask);
            parallelFor(kInner, [&](size_t j) {
                innerId[i][j] = std::this_thread::get_id();
                hits[i * kInner + j] += 1;
            });
        });
        QVERIFY(!tInParallelTask);
        for (int h : hits) QCOMPARE(h, 1);
        for (size_t i = 0; i < kOuter; ++i)
            for (size_t j = 0; j < kInner; ++j) QVERIFY(innerId[i][j] == outerId[i]);
        // Outside any task the loop still spreads over the cores (each index once).
        std::set<std::thread::id> ids;
        std::mutex m;
        std::vector<int> flat(64, 0);
        parallelFor(flat.size(), [&](size_t k) {
            flat[k] += 1;
            const std::lock_guard<std::mutex> lock(m);
            ids.insert(std::this_thread::get_id());
        });
        for (int h : flat) QCOMPARE(h, 1);
        QVERIFY(ids.size() >= 1 && ids.size() <= std::max(1u, std::thread::hardware_concurrency()));
    }

    // errorsOf runs its leave-one-run-out refits one per core; called from inside a task (where
    // everything runs on one thread) it gives the same numbers: held-out errors, refits and the
    // count of fits, bit for bit.
    void leaveOneRunOutErrorsDoNotDependOnTheThreads() {
        const PreparedRuns p;
        QVERIFY2(p.ok, p.why.c_str());
        const Context& cx = p.cx;
        const std::vector<size_t> idx = {0, 1, 2, 3};
        const Spec spec;
        long fits = 0;
        const FitOutcome f = fitSpec(cx, spec, baselineStart(cx, idx), idx, 1, fits, true);
        QVERIFY2(f.ok, f.message.c_str());
        long fitsSpread = 0, fitsOne = 0;
        std::vector<std::map<std::string, double>> looSpread, looOne;
        const ModelErrors spread = errorsOf(cx, spec, f, idx, {}, fitsSpread, &looSpread);
        ModelErrors one;
        parallelFor(1, [&](size_t) { one = errorsOf(cx, spec, f, idx, {}, fitsOne, &looOne); });
        QCOMPARE(fitsSpread, static_cast<long>(idx.size()) + spread.retriedRefits + spread.lawPasses);
        QCOMPARE(fitsOne, fitsSpread);
        QCOMPARE(looOne.size(), idx.size());
        QVERIFY(looOne == looSpread);
        QVERIFY(std::isfinite(spread.validationNrmse));
        QVERIFY(one.validationNrmse == spread.validationNrmse);  // bit for bit (QCOMPARE's is fuzzy)
        QVERIFY(one.fitNrmse == spread.fitNrmse);
        QCOMPARE(one.runs.size(), spread.runs.size());
        for (size_t i = 0; i < one.runs.size(); ++i) QVERIFY(one.runs[i].heldOutNrmse == spread.runs[i].heldOutNrmse);
    }

    // A leave-one-run-out refit that never left the full fit at IdentifyOptions::
    // looFunctionTolerance is done again at kLooRetryTolerance (ModelErrors::retriedRefits). At
    // the largest tolerance allowed, 1e-2, every refit's first step meets it (a left-out run
    // changes the cost by ~1e-7 of it) and every refit is retried; at kLooRetryTolerance itself
    // none is. Either way every refit then moves: unmovedRefits, the runs whose held-out error is
    // their in-sample one to kUnmovedRelative, is 0, and the pooled held-out error is above the
    // in-sample one.
    void refitsThatNeverMoveAreDoneAgainAtATighterTolerance() {
        for (double tol : {1e-2, 1e-6, kLooRetryTolerance}) {
            PreparedRuns p;
            QVERIFY2(p.ok, p.why.c_str());
            QVERIFY(p.cx.opt == &p.opt);
            p.opt.looFunctionTolerance = tol;
            const std::vector<size_t> idx = {0, 1, 2, 3};
            long fits = 0;
            const FitOutcome f = fitSpec(p.cx, Spec{}, baselineStart(p.cx, idx), idx, 1, fits, true);
            QVERIFY2(f.ok, f.message.c_str());
            const long before = fits;
            const ModelErrors e = errorsOf(p.cx, Spec{}, f, idx, {}, fits);
            QCOMPARE(fits - before, static_cast<long>(idx.size()) + e.retriedRefits + e.lawPasses);
            if (tol == 1e-2) QCOMPARE(e.retriedRefits, static_cast<int>(idx.size()));
            if (tol == kLooRetryTolerance) QCOMPARE(e.retriedRefits, 0);
            QCOMPARE(e.unmovedRefits, 0);
            for (const RunError& r : e.runs)
                QVERIFY2(std::abs(r.heldOutNrmse - r.nrmse) > kUnmovedRelative * r.nrmse,
                         qPrintable(QString("%1: %2 vs %3 (tolerance %4)").arg(r.file.c_str()).arg(r.heldOutNrmse).arg(r.nrmse).arg(tol)));
            QVERIFY2(e.validationNrmse > e.fitNrmse, qPrintable(QString("%1 vs %2").arg(e.validationNrmse).arg(e.fitNrmse)));
        }
    }
    // A warm-started fit whose optimum lies on C1's lower bound (runs made with C1 = 1e-5, below
    // the prescribed fit's bound 1e-4), started at three times the baseline's C1 without one run:
    // in the steady-state curve's coordinates it asks for points outside C1's bounds and stops
    // above where C1, η, v_c go; continued in C1, η, v_c from where it stopped (one more fit) it
    // ends lower, with C1 on its bound, in both outputs (ValuesOnly computes no sum of squares).
    // fitSpec itself keeps such a fit (it moved): only errorsOf's held-out refits are continued.
    // errorsOf on the four runs' fit from the same start in the curve coordinates (C1 0.021): a
    // refit without one run that meets the edge is continued, one more fit each, and no run's
    // held-out error is its in-sample one.
    void aFitThatMetTheEdgeIsContinuedInTheLawsCoordinates() {
        ExtendedModel truth = synth::trueModel();
        truth.law.C1 = 1e-5;
        IdentifyOptions opt = synth::testOptions();
        std::vector<IdentifyRun> runs = synth::makeRuns(truth, 2.0, 0.02, 1);
        Context cx;
        std::string why;
        int dec = 0;
        QVERIFY2(prepareContext(runs, opt, cx, dec, why), why.c_str());
        QVERIFY(opt.curveCoordinates);
        const std::vector<size_t> all = {0, 1, 2, 3};
        long fits = 0;
        const FitOutcome base = fitSpec(cx, Spec{}, baselineStart(cx, all), all, 1, fits, true);
        QVERIFY2(base.ok, base.message.c_str());
        std::map<std::string, double> start = base.values;
        start["C1"] = 3 * base.values.at("C1");
        const std::vector<size_t> idx = {0, 1, 2};
        for (FitOutput output : {FitOutput::ValuesOnly, FitOutput::Full}) {
            bool usedCurve = false;
            long once = 0;
            const FitOutcome c = fitSpecOnce(cx, Spec{}, start, idx, 1, once, false, FitStart::NearOptimum, output, 0, true,
                                             usedCurve);
            QVERIFY(usedCurve);
            QVERIFY2(c.ok, c.message.c_str());
            QVERIFY2(c.outsideLawBounds > 0, "the premise does not hold: the curve coordinates never met the edge");
            QVERIFY(!neverMoved(c));
            long n = 0;
            const FitOutcome kept = fitSpec(cx, Spec{}, start, idx, 1, n, false, FitStart::NearOptimum, output);
            QCOMPARE(n, 1L);
            QVERIFY(kept.fit.cost == c.fit.cost);
            const FitOutcome g = continueInLawCoordinates(cx, Spec{}, c, idx, n, FitStart::NearOptimum, output, 0);
            QVERIFY2(g.ok, g.message.c_str());
            qInfo("curve coordinates: cost %.9g, %ld points outside; continued: cost %.9g, C1 %g", c.fit.cost,
                  c.outsideLawBounds, g.fit.cost, g.values.at("C1"));
            QCOMPARE(n, 2L);
            QCOMPARE(g.outsideLawBounds, 0L);
            QVERIFY(lawFitIsBetter(c, g));
            QVERIFY(g.fit.cost < c.fit.cost * (1 - 1e-6));
            QCOMPARE(g.fit.initialCost, c.fit.initialCost);
            QVERIFY(std::abs(g.values.at("C1") - 1e-4) <= 1e-9);
            if (output == FitOutput::Full) QVERIFY(g.ss < c.ss);
        }
        bool usedCurve = false;
        const FitOutcome four = fitSpecOnce(cx, Spec{}, start, all, 1, fits, false, FitStart::NearOptimum, FitOutput::Full, 0, true, usedCurve);
        long before = fits;
        const ModelErrors e = errorsOf(cx, Spec{}, four, all, {}, fits);
        qInfo("errorsOf from C1 = %g: %d passes in C1, eta, v_c in %zu refits, %d retried, %d unmoved", four.values.at("C1"), e.lawPasses,
              all.size(), e.retriedRefits, e.unmovedRefits);
        QVERIFY2(e.lawPasses > 0, "the premise does not hold: no held-out refit met the edge");
        QCOMPARE(fits - before, static_cast<long>(all.size()) + e.retriedRefits + e.lawPasses);
        QCOMPARE(e.unmovedRefits, 0);
    }

    // lawFitIsBetter: the second pass replaces the first when it succeeded and the first failed
    // or it reached a lower solver cost, on that cost alone (ValuesOnly outcomes carry ss = NaN).
    void theSecondPassIsKeptOnItsCost() {
        FitOutcome curve, law;
        curve.ok = law.ok = true;
        curve.ss = law.ss = kNaN;
        curve.fit.cost = 2.0;
        law.fit.cost = 1.0;
        QVERIFY(lawFitIsBetter(curve, law));
        law.fit.cost = 2.0;
        QVERIFY(!lawFitIsBetter(curve, law));
        curve.ok = false;
        QVERIFY(lawFitIsBetter(curve, law));
        law.ok = false;
        QVERIFY(!lawFitIsBetter(curve, law));
    }
};

QTEST_APPLESS_MAIN(TestIdentifyFit)
#include "tst_identify_fit.moc"
