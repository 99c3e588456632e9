// Checks shared by the identify tests on self-generated runs (Qt Test macros: call from a test
// function, then `if (QTest::currentTestFailed()) return;`).
#pragma once

#include <QtTest/QtTest>

#include <cmath>

#include "core/identify/identify.hpp"

namespace synth {

// Every accepted candidate passed the selection's held-out and size tests, made over
// `heldOutRuns` runs (t(K−1, 0.975) for the size test; 3.182446 for K = 4).
inline void verifyAcceptedPassedSelection(const stickslip::identify::IdentifyResult& r, int heldOutRuns,
                                          double tCritical) {
    for (const stickslip::identify::CandidateScore& c : r.candidates) {
        if (!c.accepted) continue;
        QCOMPARE(c.heldOutUnits, heldOutRuns);
        QVERIFY2(c.heldOutP >= 0 && c.heldOutP < 0.05, qPrintable(QString("paired p %1").arg(c.heldOutP)));
        QVERIFY2(c.sizeStderr > 0 && std::abs(c.sizeCritical - tCritical) < 1e-4,
                 qPrintable(QString("%1: size %2 jackknife s.e. %3, critical t %4 (expected %5)")
                                .arg(QString::fromStdString(c.name)).arg(c.sizeValue).arg(c.sizeStderr).arg(c.sizeCritical)
                                .arg(tCritical)));
        QVERIFY(std::abs(c.sizeValue - c.sizeNull) > c.sizeCritical * c.sizeStderr);
        qInfo("%s: paired t %.2f p %.2g, size %.4g jackknife s.e. %.3g", c.name.c_str(), c.heldOutT, c.heldOutP,
              c.sizeValue, c.sizeStderr);
    }
}

// The report's timeline: consecutive stages from the baseline to the report, each with a
// non-negative wall time, whose fits add up to the loop's and whose times to its wall time.
inline void verifyTimeline(const stickslip::identify::IdentifyResult& r) {
    QVERIFY(r.timeline.size() >= 3);
    QCOMPARE(r.timeline.front().label, std::string("baseline"));
    QCOMPARE(r.timeline.back().label, std::string("report"));
    long fits = 0;
    double prevEnd = 0;
    for (const stickslip::identify::IdentifyStage& st : r.timeline) {
        QVERIFY(st.fits >= 0);
        QVERIFY(st.end_s >= st.start_s);
        QVERIFY(st.start_s >= prevEnd);
        QVERIFY(st.start_s - prevEnd < 1e-9 || &st == &r.timeline.front());
        prevEnd = st.end_s;
        fits += st.fits;
    }
    QCOMPARE(fits, r.fits);
    QVERIFY(r.timeline.front().fits >= 1);  // the baseline's own fit
    // Each candidate's own fit (its round's candidates share one stage): a wall time and the
    // fits it took, at most the loop's; every scored candidate took at least one.
    long candidateFits = 0;
    for (const stickslip::identify::CandidateScore& c : r.candidates) {
        QVERIFY(c.fitWall_s >= 0.0 && c.fitWall_s <= r.wallTime_s);
        QVERIFY(c.fits >= 0);
        if (std::isfinite(c.deltaBic) && c.deltaBic != 0.0) QVERIFY(c.fits >= 1);
        candidateFits += c.fits;
    }
    QVERIFY(candidateFits <= r.fits);
    QVERIFY(prevEnd <= r.wallTime_s);
    QVERIFY(r.wallTime_s - prevEnd < 0.01 * r.wallTime_s + 0.5);
    const auto j = toJson(r);
    QCOMPARE(j["timeline"].size(), r.timeline.size());
    QCOMPARE(j["timeline"][0]["stage"].get<std::string>(), std::string("baseline"));
    QCOMPARE(j["timeline"][0]["fits"].get<long>(), r.timeline.front().fits);
    for (size_t i = 0; i < r.candidates.size(); ++i)
        QCOMPARE(j["candidates"][i]["fit"]["fits"].get<long>(), r.candidates[i].fits);
}

}  // namespace synth
