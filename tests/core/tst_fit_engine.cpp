// The generic least-squares engine: recovers known parameters within its reported standard
// errors, reports dependent parameters as not identifiable, and rejects bad set-ups.
#include <QtTest>

#include <cmath>
#include <limits>
#include <random>

#include "core/identify/fit.hpp"

using namespace stickslip::identify;

namespace {

// y = a exp(−b t) fitted to (t, y): a on a linear, b on a log scale.
FitProblem exponentialDecayFit(std::vector<double> t, std::vector<double> y) {
    FitProblem p;
    p.parameters = {{"a", 1.0, 0.1, 10.0, true, ParamScale::Linear}, {"b", 1.0, 0.01, 100.0, true, ParamScale::Log}};
    p.residualCount = t.size();
    p.residuals = [t = std::move(t), y = std::move(y)](const std::vector<double>& v, std::vector<double>& r) {
        for (size_t i = 0; i < t.size(); ++i) r[i] = v[0] * std::exp(-v[1] * t[i]) - y[i];
        return true;
    };
    return p;
}

// y = 2 exp(−3t) + noise (σ = 0.01) at 300 samples, fitted from a start far from the optimum
// (a = 7, b = 0.05), one start: a problem whose Jacobian matters. t: the sample times.
FitProblem farStartDecay(std::vector<double>& t) {
    std::mt19937_64 rng(11);
    std::normal_distribution<double> noise(0.0, 0.01);
    std::vector<double> y;
    t.clear();
    for (int i = 0; i < 300; ++i) {
        t.push_back(i * 0.01);
        y.push_back(2.0 * std::exp(-3.0 * t.back()) + noise(rng));
    }
    FitProblem p = exponentialDecayFit(t, y);
    p.parameters[0].value = 7.0;
    p.parameters[1].value = 0.05;
    p.multistarts = 1;
    return p;
}

}  // namespace

class TstFitEngine : public QObject {
    Q_OBJECT
private slots:
    // y = a exp(−b t) + noise (σ = 0.01): the classic well-posed problem.
    void recoversExponentialWithinStandardErrors() {
        const double aTrue = 2.0, bTrue = 3.0, sigma = 0.01;
        std::mt19937_64 rng(7);
        std::normal_distribution<double> noise(0.0, sigma);
        std::vector<double> t, y;
        for (int i = 0; i < 200; ++i) {
            t.push_back(i * 0.01);
            y.push_back(aTrue * std::exp(-bTrue * t.back()) + noise(rng));
        }
        FitProblem p = exponentialDecayFit(t, y);
        p.multistarts = 3;
        const FitResult res = fitLeastSquares(p);
        QVERIFY2(res.ok(), res.message.c_str());
        QVERIFY(res.identifiable);
        QCOMPARE(res.startsTried, 3);
        const double sa = res.stderrOf("a"), sb = res.stderrOf("b");
        QVERIFY(sa > 0 && sb > 0);
        QVERIFY2(std::abs(res.value("a") - aTrue) < 4 * sa, qPrintable(QString("a=%1±%2").arg(res.value("a")).arg(sa)));
        QVERIFY2(std::abs(res.value("b") - bTrue) < 4 * sb, qPrintable(QString("b=%1±%2").arg(res.value("b")).arg(sb)));
        // The standard error scales with the noise: σ_a of order σ/sqrt(n)·few.
        QVERIFY(sa < 0.01 && sa > 1e-4);
        // RMS of the residual ≈ noise level.
        QVERIFY(res.rms > 0.7 * sigma && res.rms < 1.3 * sigma);
        // a and b are positively correlated in this model.
        QCOMPARE(res.correlation.size(), size_t(4));
        QVERIFY(std::abs(res.correlation[0] - 1.0) < 1e-9);
        QVERIFY(res.correlation[1] > 0.3);
    }

    // Only the product a·b is seen: the fit must say so instead of quoting errors.
    void reportsDependentParametersAsNotIdentifiable() {
        std::vector<double> t, y;
        for (int i = 0; i < 50; ++i) {
            t.push_back(i * 0.1);
            y.push_back(6.0 * t.back() + 0.01 * std::sin(37.0 * i));
        }
        FitProblem p;
        p.parameters = {{"a", 1.0, 0.1, 10.0, true, ParamScale::Log}, {"b", 1.0, 0.1, 10.0, true, ParamScale::Log}};
        p.residualCount = t.size();
        p.residuals = [&](const std::vector<double>& v, std::vector<double>& r) {
            for (size_t i = 0; i < t.size(); ++i) r[i] = v[0] * v[1] * t[i] - y[i];
            return true;
        };
        const FitResult res = fitLeastSquares(p);
        QVERIFY(res.ok());
        QVERIFY(!res.identifiable);
        QVERIFY(std::isnan(res.stderrOf("a")));
        QVERIFY(res.identifiabilityMessage.find("not identifiable") != std::string::npos);
        QVERIFY(std::abs(res.value("a") * res.value("b") - 6.0) < 1e-3);
    }

    // a and b are seen only as their product, c and d are correlated but determined: the fit is
    // not identifiable, yet the (c, d) pair's correlation is defined with the undetermined a·b
    // direction held, and equals the correlation of the identifiable fit with b fixed; the
    // undetermined pair itself trades off completely.
    void pairCorrelationHoldsTheUndeterminedDirection() {
        std::vector<double> t, y;
        for (int i = 0; i < 80; ++i) {
            t.push_back(i * 0.05);
            const double g = std::sin(t.back()), h = std::sin(t.back()) + 0.3 * std::cos(t.back());
            y.push_back(6.0 * t.back() + 0.5 * g - 0.4 * h + 0.01 * std::sin(37.0 * i));
        }
        auto problem = [&](bool bFree) {
            FitProblem p;
            p.parameters = {{"a", 1.0, 0.1, 10.0, true, ParamScale::Log}, {"b", 2.0, 0.1, 10.0, bFree, ParamScale::Log},
                            {"c", 0.0, -5.0, 5.0, true, ParamScale::Linear}, {"d", 0.0, -5.0, 5.0, true, ParamScale::Linear}};
            p.residualCount = t.size();
            p.residuals = [&](const std::vector<double>& v, std::vector<double>& r) {
                for (size_t i = 0; i < t.size(); ++i)
                    r[i] = v[0] * v[1] * t[i] + v[2] * std::sin(t[i]) + v[3] * (std::sin(t[i]) + 0.3 * std::cos(t[i])) - y[i];
                return true;
            };
            return p;
        };
        const FitResult all = fitLeastSquares(problem(true)), held = fitLeastSquares(problem(false));
        QVERIFY(all.ok() && held.ok());
        QVERIFY(!all.identifiable);
        QVERIFY(held.identifiable);
        QVERIFY(std::isnan(all.correlation[2 * 4 + 3]));  // the matrix itself stays undefined
        const double rcd = pairCorrelation(all, 2, 3), rHeld = held.correlation[1 * 3 + 2];
        qInfo("corr(c, d): %.9f with a.b held; %.9f with b fixed", rcd, rHeld);
        QVERIFY(std::abs(rcd) > 0.9);
        QVERIFY(std::abs(rcd - rHeld) < 1e-6);
        QVERIFY(std::abs(pairCorrelation(all, 0, 1) + 1.0) < 1e-6);  // ln a + ln b is what is seen
        QCOMPARE(pairCorrelation(held, 1, 2), held.correlation[1 * 3 + 2]);  // identifiable: the matrix
        QVERIFY(std::isnan(pairCorrelation(all, 0, 9)));
    }

    // A fixed parameter is passed through, has zero standard error and is not in the correlation.
    void fixedParametersStayFixed() {
        FitProblem p;
        p.parameters = {{"a", 0.5, 0.0, 1.0, false, ParamScale::Linear}, {"b", 2.0, 0.0, 10.0, true, ParamScale::Linear}};
        p.residualCount = 3;
        p.residuals = [](const std::vector<double>& v, std::vector<double>& r) {
            r = {v[1] - 4.0 - v[0], 2 * (v[1] - 4.5), v[1] - 4.5};
            return true;
        };
        const FitResult res = fitLeastSquares(p);
        QVERIFY(res.ok());
        QCOMPARE(res.value("a"), 0.5);
        QCOMPARE(res.stderrOf("a"), 0.0);
        QCOMPARE(res.freeNames.size(), size_t(1));
        QVERIFY(std::abs(res.value("b") - 4.5) < 1e-6);
    }

    // A random start where the model cannot be evaluated is drawn again: with most of the box
    // where random starts fall infeasible (x > 0.4 of 0.1-0.9), every one of 4 starts still
    // begins at an evaluable point and converges.
    void infeasibleRandomStartsAreDrawnAgain() {
        FitProblem p;
        p.parameters = {{"x", 0.1, 0.0, 1.0, true, ParamScale::Linear}};
        p.residualCount = 2;
        p.residuals = [](const std::vector<double>& v, std::vector<double>& r) {
            if (v[0] > 0.4) return false;  // infeasible beyond 0.4
            r = {v[0] - 0.15, 0.1 * (v[0] - 0.15)};
            return true;
        };
        p.multistarts = 4;
        p.agreeingStarts = 0;
        const FitResult res = fitLeastSquares(p);
        QVERIFY(res.ok());
        QCOMPARE(res.startsTried, 4);
        for (double c : res.startCosts) QVERIFY2(std::isfinite(c) && c < 1e-12, res.solverSummary.c_str());
        QVERIFY(std::abs(res.value("x") - 0.15) < 1e-6);
    }

    // Failing evaluations are steps the solver refuses, not crashes.
    void failedEvaluationsAreAvoided() {
        FitProblem p;
        p.parameters = {{"x", 0.2, 0.0, 1.0, true, ParamScale::Linear}};
        p.residualCount = 2;
        p.residuals = [](const std::vector<double>& v, std::vector<double>& r) {
            if (v[0] > 0.6) return false;  // "simulation failed" beyond 0.6
            r = {v[0] - 0.5, 0.1 * (v[0] - 0.5)};
            return true;
        };
        const FitResult res = fitLeastSquares(p);
        QVERIFY(res.ok());
        QVERIFY(std::abs(res.value("x") - 0.5) < 1e-5);
    }

    void badProblemIsRejectedWithAllIssues() {
        FitProblem p;
        p.parameters = {{"eta", -1.0, -2.0, 1.0, true, ParamScale::Log}, {"mu", 3.0, 0.0, 2.0, true, ParamScale::Linear}};
        p.residualCount = 0;
        const FitResult res = fitLeastSquares(p);
        QVERIFY(!res.ok());
        QVERIFY(res.message.find("eta") != std::string::npos);
        QVERIFY(res.message.find("mu = 3") != std::string::npos);
        QVERIFY(res.message.find("residual callback") != std::string::npos);
    }

    void cancellationReturnsCancelled() {
        std::atomic<bool> cancel{true};
        FitProblem p;
        p.parameters = {{"x", 0.2, 0.0, 1.0, true, ParamScale::Linear}};
        p.residualCount = 2;
        p.residuals = [](const std::vector<double>& v, std::vector<double>& r) { r = {v[0] - 0.5, v[0] * v[0] - 0.3}; return true; };
        p.cancel = &cancel;
        const FitResult res = fitLeastSquares(p);
        QVERIFY(res.status == FitStatus::Cancelled);
        QCOMPARE(res.startsTried, 1);
    }

    // Cancel raised while residuals are being computed (Ctrl-C during a dynamics fit, whose
    // batches take seconds): no further batch is started, not even the Jacobian's points of
    // the same iteration; the fit ends Cancelled.
    void cancelDuringABatchStartsNoOther() {
        std::atomic<bool> cancel{false};
        FitProblem p;
        p.parameters = {{"x", 0.2, 0.0, 1.0, true, ParamScale::Linear}, {"y", 0.3, 0.0, 1.0, true, ParamScale::Linear}};
        p.residualCount = 3;
        long batches = 0;
        p.batchResiduals = [&](const std::vector<std::vector<double>>& pts, std::vector<std::vector<double>>& rs,
                               std::vector<char>& ok) {
            ++batches;
            ok.assign(pts.size(), 1);
            for (size_t k = 0; k < pts.size(); ++k) rs[k] = {pts[k][0] - 0.5, pts[k][1] - 0.1, pts[k][0] * pts[k][1]};
            cancel = true;
        };
        p.cancel = &cancel;
        const FitResult res = fitLeastSquares(p);
        QVERIFY(res.status == FitStatus::Cancelled);
        QCOMPARE(batches, 1L);
    }

    // The same problem through the batch callback gives the same fit bit for bit; the reported
    // evaluations are the residual vectors actually computed (repeated points are remembered).
    void batchCallbackAndEvaluationCount() {
        std::vector<double> t, y;
        for (int i = 0; i < 100; ++i) {
            t.push_back(i * 0.02);
            y.push_back(2.0 * std::exp(-3.0 * t.back()) + 0.01 * std::sin(17.0 * i));
        }
        FitProblem p = exponentialDecayFit(t, y);
        const auto model = p.residuals;
        long calls = 0;
        p.residuals = [&](const std::vector<double>& v, std::vector<double>& r) { ++calls; return model(v, r); };
        p.multistarts = 2;
        const FitResult single = fitLeastSquares(p);
        QVERIFY(single.ok());
        QCOMPARE(single.residualEvaluations, calls);
        long batched = 0, batches = 0;
        FitProblem b = p;
        b.residuals = nullptr;
        b.batchResiduals = [&](const std::vector<std::vector<double>>& pts, std::vector<std::vector<double>>& rs, std::vector<char>& ok) {
            ++batches;
            ok.assign(pts.size(), 0);
            for (size_t k = 0; k < pts.size(); ++k) {
                ++batched;
                QCOMPARE(rs[k].size(), t.size());
                ok[k] = model(pts[k], rs[k]) ? 1 : 0;
            }
        };
        QVERIFY(b.validate().empty());
        const FitResult viaBatch = fitLeastSquares(b);
        QVERIFY(viaBatch.ok());
        QVERIFY(viaBatch.values == single.values);
        QVERIFY(viaBatch.stderrs == single.stderrs);
        QVERIFY(viaBatch.startCosts == single.startCosts);
        QCOMPARE(viaBatch.residualEvaluations, batched);
        QVERIFY(batches < batched);  // Jacobian points come together
    }

    // JacobianKind::Forward: the same optimum and the same standard errors as central
    // differences (those are differenced centrally at the optimum either way), from about half
    // the residual vectors, on a problem whose Jacobian matters (start far from the optimum).
    void forwardJacobianReachesTheCentralOptimumForLess() {
        std::vector<double> t;
        FitProblem central = farStartDecay(t);
        FitProblem forward = central;
        forward.jacobian = JacobianKind::Forward;
        const FitResult c = fitLeastSquares(central), f = fitLeastSquares(forward);
        QVERIFY2(c.ok() && f.ok(), (c.message + " / " + f.message).c_str());
        QVERIFY2(std::abs(f.cost - c.cost) <= 1e-6 * c.cost, qPrintable(QString("cost %1 vs %2").arg(f.cost).arg(c.cost)));
        for (const char* k : {"a", "b"}) {
            QVERIFY2(std::abs(f.value(k) - c.value(k)) < 0.01 * c.stderrOf(k),
                     qPrintable(QString("%1: %2 vs %3 (s.e. %4)").arg(k).arg(f.value(k)).arg(c.value(k)).arg(c.stderrOf(k))));
            QVERIFY(std::abs(f.stderrOf(k) / c.stderrOf(k) - 1.0) < 1e-3);
        }
        qInfo("residual vectors: central %ld, forward %ld", c.residualEvaluations, f.residualEvaluations);
        QVERIFY(f.residualEvaluations < 0.75 * c.residualEvaluations);
    }

    // FitProblem::analyticJacobian: the same optimum and standard errors as central differences
    // (b on a log scale: the chain rule through the solver's mapping), with no residual vector
    // spent on a Jacobian; a callback that declines falls back to the differences.
    void analyticJacobianReachesTheCentralOptimumWithoutDifferences() {
        std::vector<double> t;
        FitProblem central = farStartDecay(t);
        FitProblem exact = central;
        long calls = 0;
        exact.analyticJacobian = [t, &calls](const std::vector<double>& v, std::vector<double>& J) {
            ++calls;
            const size_t P = 2;
            J.assign(t.size() * P, 0.0);
            for (size_t i = 0; i < t.size(); ++i) {
                const double e = std::exp(-v[1] * t[i]);
                J[i * P + 0] = e;
                J[i * P + 1] = -v[0] * t[i] * e;
            }
            return true;
        };
        FitProblem declined = central;
        declined.analyticJacobian = [](const std::vector<double>&, std::vector<double>&) { return false; };
        const FitResult c = fitLeastSquares(central), a = fitLeastSquares(exact), d = fitLeastSquares(declined);
        QVERIFY2(c.ok() && a.ok() && d.ok(), (c.message + " / " + a.message + " / " + d.message).c_str());
        QVERIFY2(std::abs(a.cost - c.cost) <= 1e-6 * c.cost, qPrintable(QString("cost %1 vs %2").arg(a.cost).arg(c.cost)));
        for (const char* k : {"a", "b"}) {
            QVERIFY2(std::abs(a.value(k) - c.value(k)) < 0.01 * c.stderrOf(k),
                     qPrintable(QString("%1: %2 vs %3 (s.e. %4)").arg(k).arg(a.value(k)).arg(c.value(k)).arg(c.stderrOf(k))));
            QVERIFY(std::abs(a.stderrOf(k) / c.stderrOf(k) - 1.0) < 1e-3);
        }
        qInfo("residual vectors: central %ld, analytic %ld (%ld Jacobians)", c.residualEvaluations, a.residualEvaluations, calls);
        QVERIFY(calls > 0);
        QVERIFY(a.residualEvaluations < c.residualEvaluations / 2);
        // Declined everywhere: exactly the differenced fit.
        QVERIFY(d.values == c.values);
        QCOMPARE(d.residualEvaluations, c.residualEvaluations);
    }

    void lineSearchStepsAreValidated() {
        FitProblem p = exponentialDecayFit({0, 1, 2}, {1, 0.5, 0.25});
        p.maxLineSearchSteps = 0;
        bool named = false;
        for (const auto& issue : p.validate()) named = named || issue.message().find("maxLineSearchSteps") != std::string::npos;
        QVERIFY(named);
    }

    // The solver differences its Jacobian only at points it has accepted (costs decreasing).
    // The projected line search Ceres runs on bounded problems interpolates cubically by
    // default, which asks for the gradient at every trial point: a whole Jacobian (p more
    // residual vectors) at each trial, most of them steps the trust region then rejects. On
    // the Rosenbrock valley from (-1.2, 1), where trials are rejected, every Jacobian's base
    // point must cost no more than the one before it.
    void jacobiansOnlyAtAcceptedPoints() {
        FitProblem p;
        p.parameters = {{"x", -1.2, -5.0, 5.0, true, ParamScale::Linear}, {"y", 1.0, -5.0, 5.0, true, ParamScale::Linear}};
        p.residualCount = 3;  // the third is 0: the engine needs more residuals than free parameters
        p.multistarts = 1;
        p.uncertainty = false;
        p.maxIterations = 200;
        p.jacobian = JacobianKind::Forward;
        auto cost = [](const std::vector<double>& v) {
            const double a = 10.0 * (v[1] - v[0] * v[0]), b = 1.0 - v[0];
            return 0.5 * (a * a + b * b);
        };
        std::vector<double> jacobianBaseCosts;
        int trialsAboveCurrent = 0;
        p.batchResiduals = [&](const std::vector<std::vector<double>>& pts, std::vector<std::vector<double>>& rs, std::vector<char>& ok) {
            ok.assign(pts.size(), 1);
            for (size_t k = 0; k < pts.size(); ++k) rs[k] = {10.0 * (pts[k][1] - pts[k][0] * pts[k][0]), 1.0 - pts[k][0], 0.0};
            if (pts.size() == 2) {  // forward differences in x and in y: base = (x of the y point, y of the x point)
                jacobianBaseCosts.push_back(cost({pts[1][0], pts[0][1]}));
            } else if (pts.size() == 1 && !jacobianBaseCosts.empty() && cost(pts[0]) > jacobianBaseCosts.back()) {
                ++trialsAboveCurrent;
            }
        };
        const FitResult r = fitLeastSquares(p);
        QVERIFY2(r.ok(), r.message.c_str());
        QVERIFY2(std::abs(r.value("x") - 1.0) < 1e-4 && std::abs(r.value("y") - 1.0) < 1e-4,
                 qPrintable(QString("optimum (%1, %2)").arg(r.value("x")).arg(r.value("y"))));
        QVERIFY2(trialsAboveCurrent > 0, "no trial point was worse than the current one: the test does not exercise rejection");
        QVERIFY(jacobianBaseCosts.size() >= 2);
        for (size_t i = 1; i < jacobianBaseCosts.size(); ++i)
            QVERIFY2(jacobianBaseCosts[i] <= jacobianBaseCosts[i - 1],
                     qPrintable(QString("Jacobian %1 at cost %2 after one at %3: differenced at a point the solver did not accept")
                                    .arg(i).arg(jacobianBaseCosts[i]).arg(jacobianBaseCosts[i - 1])));
        qInfo("%zu Jacobians, %d trial points worse than the current one, %ld residual vectors", jacobianBaseCosts.size(),
              trialsAboveCurrent, r.residualEvaluations);
    }

    // A start on a bound with the gradient pointing out of the box (x on its lower bound 0, its
    // residual 1000 (x + 5) pulling it to -5): every step Ceres proposes is mostly x, the bound
    // clips it, the decrease left is a sliver of the predicted one and the step is rejected; the
    // solve used to end where it began, y never moving from 10. x is then held on its bound and y
    // solved alone (fit.cpp, solveFrom).
    void aStartOnAnActiveBoundStillMovesTheOthers() {
        FitProblem p;
        p.parameters = {{"x", 0.0, 0.0, 10.0, true, ParamScale::Linear}, {"y", 10.0, 0.0, 20.0, true, ParamScale::Linear}};
        p.residualCount = 3;
        p.multistarts = 1;
        p.uncertainty = false;
        p.residuals = [](const std::vector<double>& v, std::vector<double>& r) {
            r = {1000.0 * (v[0] + 5.0), v[1] - 3.0, 0.1 * (v[1] - 3.0) * v[0]};
            return true;
        };
        const FitResult r = fitLeastSquares(p);
        QVERIFY2(r.ok(), r.message.c_str());
        qInfo("x %.6g, y %.6g, %s", r.value("x"), r.value("y"), r.solverSummary.c_str());
        QCOMPARE(r.value("x"), 0.0);
        // To the function tolerance, relative to a cost that x's residual dominates (seen 3.0007).
        QVERIFY2(std::abs(r.value("y") - 3.0) < 1e-2, qPrintable(QString("y = %1").arg(r.value("y"))));
        // The reported cost is the cost at the reported values.
        QVERIFY(std::abs(r.cost - 0.5 * (25e6 + std::pow(r.value("y") - 3.0, 2))) <= 1e-9 * r.cost);
    }

    // agreeingStarts: stop once that many starts ended at the same (best) cost.
    void multistartStopsWhenStartsAgree() {
        std::vector<double> t, y;
        for (int i = 0; i < 100; ++i) {
            t.push_back(i * 0.02);
            y.push_back(2.0 * std::exp(-3.0 * t.back()) + 0.01 * std::sin(17.0 * i));
        }
        FitProblem p = exponentialDecayFit(t, y);
        p.multistarts = 5;
        const FitResult all = fitLeastSquares(p);
        QVERIFY(all.ok());
        QCOMPARE(all.startsTried, 5);
        QVERIFY(!all.stoppedEarly);
        p.agreeingStarts = 2;
        const FitResult early = fitLeastSquares(p);
        QVERIFY(early.ok());
        QCOMPARE(early.startsTried, 2);
        QVERIFY(early.stoppedEarly);
        QVERIFY(early.solverSummary.find("stopped after 2 of 5 starts") != std::string::npos);
        QVERIFY(std::abs(early.cost - all.cost) <= 1e-6 * all.cost);
        QVERIFY(std::abs(early.value("b") - all.value("b")) < 1e-3 * all.stderrOf("b"));
    }

    // A model that cannot be evaluated beyond an edge inside the box: the data pull the slope
    // past the edge, and the fit ends on the edge with one-sided differences there, for the
    // solver's Jacobian (forward and central) and for the standard errors, instead of failing.
    // (On the edge the solver cannot slide along it: every step with a component across fails,
    // so b stops short of its optimum 0.55 given a = 2. That is why identify moves in the
    // steady-state curve's coordinates only from a start inside C1's and eta's bounds,
    // identify_fit.cpp.)
    void oneSidedDifferencesAtAnInfeasibleEdge() {
        std::vector<double> t, y;
        for (int i = 0; i < 50; ++i) {
            t.push_back(i / 49.0);
            y.push_back(2.5 * t.back() + 0.3 + 0.01 * std::sin(13.0 * i));
        }
        for (JacobianKind kind : {JacobianKind::Forward, JacobianKind::Central}) {
            FitProblem p;
            p.parameters = {{"a", 1.0, 0.0, 10.0, true, ParamScale::Linear}, {"b", 0.0, -5.0, 5.0, true, ParamScale::Linear}};
            p.residualCount = t.size();
            p.residuals = [t, y](const std::vector<double>& v, std::vector<double>& r) {
                if (v[0] > 2.0) return false;
                for (size_t i = 0; i < t.size(); ++i) r[i] = v[0] * t[i] + v[1] - y[i];
                return true;
            };
            p.multistarts = 1;
            p.jacobian = kind;
            const FitResult res = fitLeastSquares(p);
            QVERIFY2(res.ok(), res.message.c_str());
            qInfo("%s: a = %.6f, b = %.6f +- %.3g", kind == JacobianKind::Forward ? "forward" : "central", res.value("a"),
                  res.value("b"), res.stderrOf("b"));
            QVERIFY(res.value("a") <= 2.0);
            QVERIFY(res.value("a") > 1.98);
            QVERIFY(std::isfinite(res.stderrOf("a")) && res.stderrOf("a") > 0);
            QVERIFY(std::isfinite(res.stderrOf("b")) && res.stderrOf("b") > 0);
            // Lower than at the start (a = 1, b = 0: cost ½ Σ (1.5 t + 0.3)² ≈ 19.7).
            QVERIFY(res.cost < 5.0);
        }
    }

    // FitProblem::uncertainty = false returns the same optimum without the 2p-point Jacobian
    // after the solve: fewer residual evaluations, NaN standard errors, no correlations.
    void valuesOnlyFitSkipsTheCovariance() {
        std::vector<double> t, y;
        for (int i = 0; i < 60; ++i) {
            t.push_back(i / 59.0);
            y.push_back(std::exp(-1.7 * t.back()) * 3.0 + 0.02 * std::sin(17.0 * i));
        }
        for (JacobianKind kind : {JacobianKind::Forward, JacobianKind::Central}) {
            int calls = 0;
            FitProblem p;
            p.parameters = {{"A", 1.0, 0.1, 10.0, true, ParamScale::Log}, {"k", 0.5, 0.01, 10.0, true, ParamScale::Log}};
            p.residualCount = t.size();
            p.residuals = [t, y, &calls](const std::vector<double>& v, std::vector<double>& r) {
                ++calls;
                for (size_t i = 0; i < t.size(); ++i) r[i] = v[0] * std::exp(-v[1] * t[i]) - y[i];
                return true;
            };
            p.multistarts = 1;
            p.jacobian = kind;
            const FitResult full = fitLeastSquares(p);
            const int fullCalls = calls;
            calls = 0;
            p.uncertainty = false;
            const FitResult bare = fitLeastSquares(p);
            QVERIFY2(full.ok() && bare.ok(), (full.message + bare.message).c_str());
            QCOMPARE(bare.values, full.values);
            QCOMPARE(bare.cost, full.cost);
            QVERIFY(std::abs(bare.rms - full.rms) <= 1e-12 * full.rms);
            QVERIFY(std::isfinite(full.stderrOf("k")) && full.stderrOf("k") > 0);
            QVERIFY(std::isnan(bare.stderrOf("A")) && std::isnan(bare.stderrOf("k")));
            QVERIFY(bare.correlation.empty() && !bare.identifiable);
            // The covariance Jacobian is 2p = 4 points around the optimum; the solver's memory of
            // recent points serves those its last Jacobian already had (all of a central one, the
            // forward points of a forward one), so it saves the backward points of a forward fit.
            qInfo("%s: %d residual calls with the covariance, %d without", kind == JacobianKind::Forward ? "forward" : "central",
                  fullCalls, calls);
            QVERIFY(calls <= fullCalls);
            if (kind == JacobianKind::Forward) QVERIFY(calls < fullCalls);
        }
    }

    // A frequency fit y = sin(ω t) has a narrow valley at the true ω and many local minima: the
    // local solver from ω = 3 stays in a wrong one; a scan over a log grid of ω (more points
    // than the evaluator's memory holds: that crashed once) starts it in the right valley.
    void scanFindsTheNarrowValley() {
        std::vector<double> t, y;
        for (int i = 0; i < 400; ++i) {
            t.push_back(i * 0.01);
            y.push_back(std::sin(11.0 * t.back()));
        }
        FitProblem p;
        p.parameters = {{"omega", 3.0, 0.5, 50.0, true, ParamScale::Log}};
        p.residualCount = t.size();
        p.residuals = [t, y](const std::vector<double>& v, std::vector<double>& r) {
            for (size_t i = 0; i < t.size(); ++i) r[i] = std::sin(v[0] * t[i]) - y[i];
            return true;
        };
        p.multistarts = 1;
        const FitResult local = fitLeastSquares(p);
        QVERIFY2(local.ok(), local.message.c_str());
        qInfo("from omega = 3 without a scan: %.4f", local.value("omega"));
        QVERIFY(std::abs(local.value("omega") - 11.0) > 1.0);
        p.scans = {{"omega", logGrid(0.5, 50.0, 81)}};
        QCOMPARE(p.scans[0].values.size(), size_t(81));
        QCOMPARE(p.scans[0].values.front(), 0.5);
        QVERIFY(std::abs(p.scans[0].values.back() - 50.0) < 1e-12);
        const FitResult scanned = fitLeastSquares(p);
        QVERIFY2(scanned.ok(), scanned.message.c_str());
        qInfo("with the scan: %.6f; %s", scanned.value("omega"), scanned.solverSummary.c_str());
        QVERIFY(std::abs(scanned.value("omega") - 11.0) < 1e-6);
        QVERIFY(scanned.solverSummary.find("scan omega over 81 values") != std::string::npos);
        // A scan of a parameter that is not free is a set-up error, named.
        p.scans = {{"phase", {1.0, 2.0}}};
        const FitResult bad = fitLeastSquares(p);
        QVERIFY(!bad.ok());
        QVERIFY2(bad.message.find("scan of 'phase': not a free parameter") != std::string::npos, bad.message.c_str());
        QVERIFY(logGrid(0.0, 1.0, 5).empty());
        QVERIFY(logGrid(1.0, 10.0, 1).empty());
    }

    void defaultParametersHavePhysicalBounds() {
        FitParameter fp;
        QVERIFY(defaultParameter("eta", stickslip::SetupKind::Dynamics, fp));
        QVERIFY(fp.scale == ParamScale::Log && fp.lower > 0 && fp.upper > fp.lower);
        QVERIFY(defaultParameter("mu", stickslip::SetupKind::Prescribed, fp));
        QVERIFY(fp.upper > 10);
        QVERIFY(!defaultParameter("nonsense", stickslip::SetupKind::Dynamics, fp));
    }
};

QTEST_GUILESS_MAIN(TstFitEngine)
#include "tst_fit_engine.moc"
