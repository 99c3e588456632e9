// Parameters: every invalid value of every field is rejected with a message naming the key, the
// value and the allowed range; validate() returns all issues; keys round-trip; defaults are the
// paper's Fig. 20 set.
#include <QtTest>

#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <set>

#include "core/friction/friction_law.hpp"
#include "core/identify/fit.hpp"
#include "core/integrate/simulate.hpp"
#include "core/io/units.hpp"
#include "core/params.hpp"
#include "core/presets.hpp"
#include "physics_helpers.hpp"

using namespace stickslip;
using namespace stickslip::testing;

namespace {

const double kNaN = std::numeric_limits<double>::quiet_NaN();
const double kInf = std::numeric_limits<double>::infinity();

// One field of one struct: its key, how to set it on a default struct, one out-of-range finite
// value, and the validator of the struct it lives in.
struct FieldCase {
    const char* key;
    double badValue;  // finite and out of range
    std::function<ParamIssues(double)> validateWith;
};

template <class S>
std::function<ParamIssues(double)> with(double S::*field) {
    return [field](double v) {
        S s;
        s.*field = v;
        return s.validate();
    };
}

std::vector<FieldCase> fieldCases() {
    return {
        {"A", -1.5e-3, with(&DriveParams::amplitude_m)},
        {"f", 0.0, with(&DriveParams::frequency_Hz)},
        {"tN", -2.0, with(&RigParams::normalForce_N)},
        {"k", -100.0, with(&RigParams::stiffness_N_per_m)},
        {"m", 0.0, with(&RigParams::mass_kg)},
        {"c", -0.25, with(&RigParams::damping_Ns_per_m)},
        {"mu", -0.1, with(&RateStateParams::mu)},
        {"eta", 0.0, with(&RateStateParams::eta_s_per_m)},
        {"Dc", -2e-05, with(&RateStateParams::Dc_m)},
        {"C1", -0.5, with(&RateStateParams::C1)},
        {"r", 0.0, with(&RateStateParams::r)},
        {"vc", -0.1, with(&RateStateParams::vc_mps)},
        {"epsT", 0.0, with(&RateStateParams::epsT_N_per_m)},
        {"mu", -0.3, with(&CoulombParams::mu)},
        {"epsT", -1e6, with(&CoulombParams::epsT_N_per_m)},
        {"dt", 0.0, with(&IntegrationParams::dt_s)},
        {"output_every", -0.001, with(&IntegrationParams::outputInterval_s)},
    };
}

// The issue's message names the key, shows the value and states the allowed range.
void checkIssue(const ParamIssue& i, const std::string& key, double value) {
    const std::string msg = i.message();
    QCOMPARE(QString::fromStdString(i.field), QString::fromStdString(key));
    QVERIFY(std::isnan(value) ? std::isnan(i.value) : i.value == value);
    QVERIFY2(msg.rfind(key + " = ", 0) == 0, msg.c_str());
    QVERIFY2(!i.allowed.empty() && contains(msg, i.allowed), msg.c_str());
    QVERIFY2(contains(i.allowed, ">") || contains(i.allowed, "<") || contains(i.allowed, "finite"), msg.c_str());
    std::ostringstream v;
    v.precision(6);
    v << value;
    QVERIFY2(contains(msg, "= " + v.str()), qPrintable(QString::fromStdString(msg + " (value " + v.str() + ")")));
}

}  // namespace

class TstParams : public QObject {
    Q_OBJECT
private slots:
    // Defaults are the paper's Fig. 20 set (MODEL.md) and valid.
    void defaultsAreFig20() {
        const SimParams p;
        QCOMPARE(p.rig.normalForce_N, 6.2);
        QCOMPARE(p.rig.stiffness_N_per_m, 8446.0);
        QCOMPARE(p.rig.mass_kg, 0.53);
        QCOMPARE(p.drive.frequency_Hz, 3.0);
        QCOMPARE(p.lawParams<RateStateParams>().mu, 0.25);
        QCOMPARE(p.lawParams<RateStateParams>().C1, 0.25);
        QCOMPARE(p.lawParams<RateStateParams>().r, 1.0);
        QCOMPARE(p.lawParams<RateStateParams>().eta_s_per_m, 0.6);
        QCOMPARE(p.lawParams<RateStateParams>().Dc_m, 20e-6);
        QCOMPARE(p.lawParams<RateStateParams>().vc_mps, 0.1);
        QCOMPARE(p.lawParams<RateStateParams>().C2(), 10.0);
        QCOMPARE(p.lawParams<CoulombParams>().mu, 0.25);
        // 0.5 % of critical damping.
        QVERIFY(std::abs(p.rig.dampingRatio() - 0.005) < 1e-3 * 0.005);
        QVERIFY2(p.validate().empty(), formatIssues(p.validate()).c_str());
    }

    // Each field, set alone to an out-of-range value, to NaN, to +inf and to −inf, gives exactly
    // one issue from its struct's validate(), naming it with value and allowed range.
    void everyFieldRejected() {
        for (const FieldCase& c : fieldCases()) {
            for (double v : {c.badValue, kNaN, kInf, -kInf}) {
                const ParamIssues issues = c.validateWith(v);
                QVERIFY2(issues.size() == 1, qPrintable(QString("%1 = %2: %3 issues").arg(c.key).arg(v).arg(issues.size())));
                checkIssue(issues[0], c.key, v);
            }
        }
        // phase may be any finite number, but not NaN or inf.
        for (double v : {kNaN, kInf}) {
            DriveParams d;
            d.phase_rad = v;
            const ParamIssues issues = d.validate();
            QCOMPARE(issues.size(), size_t(1));
            checkIssue(issues[0], "phase", v);
        }
        DriveParams d;
        d.phase_rad = -7.0;
        QVERIFY(d.validate().empty());
    }

    // Boundary values that are allowed: A = 0 (no drive), k = 0 (no spring), c = 0, μ = 0, C1 = 0.
    void boundariesAccepted() {
        SimParams p;
        for (const char* key : {"A", "k", "c", "mu", "C1", "transient"}) QVERIFY(setParam(p, key, 0.0));
        QVERIFY2(p.validate().empty(), formatIssues(p.validate()).c_str());
        p.law = LawKind::Coulomb;
        QVERIFY2(p.validate().empty(), formatIssues(p.validate()).c_str());
    }

    // validate() returns ALL issues, not the first: every key bad at once → one issue per key.
    void allIssuesReturned() {
        SimParams p;
        const std::vector<std::pair<const char*, double>> bad = {
            {"A", -1}, {"f", -3}, {"phase", kNaN}, {"tN", 0}, {"k", -1}, {"m", -1}, {"c", -1}, {"mu", -1},
            {"eta", -1}, {"Dc", 0}, {"C1", -1}, {"r", -1}, {"vc", 0}, {"epsT", -5}, {"dt", -1},
            {"output_every", 0}, {"cycles", 0}, {"transient", -2}};
        for (const auto& [k, v] : bad) QVERIFY(setParam(p, k, v));
        const ParamIssues issues = p.validate();
        std::set<std::string> named;
        for (const auto& i : issues) named.insert(i.field);
        for (const auto& [k, v] : bad) QVERIFY2(named.count(k) == 1, k);
        QCOMPARE(issues.size(), bad.size());
        // One line per issue, each naming its key.
        const QStringList lines = QString::fromStdString(formatIssues(issues)).split('\n');
        QCOMPARE(lines.size(), int(issues.size()));
        for (size_t i = 0; i < issues.size(); ++i) QVERIFY(lines[int(i)].startsWith(QString::fromStdString(issues[i].field)));
        // The Coulomb law's fields are checked when it is selected.
        p.law = LawKind::Coulomb;
        std::set<std::string> namedC;
        for (const auto& i : p.validate()) namedC.insert(i.field);
        QVERIFY(namedC.count("mu") && namedC.count("epsT") && !namedC.count("eta") && !namedC.count("Dc"));
    }

    // Through SimParams and its keys: each key, alone bad, is named by SimParams::validate()
    // (the run-level checks cycles, transient and dt ≤ T/8 included), and simulate() refuses
    // to run, in both set-ups, with that message.
    void everyKeyThroughSimParams() {
        const std::vector<std::pair<const char*, double>> bad = {
            {"A", -1e-3}, {"f", 0}, {"phase", kInf}, {"tN", -6.2}, {"k", -1}, {"m", 0}, {"c", -1}, {"mu", -0.25},
            {"eta", 0}, {"Dc", 0}, {"C1", -1}, {"r", 0}, {"vc", 0}, {"epsT", 0}, {"dt", 0}, {"output_every", 0},
            {"cycles", 0}, {"transient", -1}, {"a", 0}, {"b", -1}, {"V0", 0}};
        QCOMPARE(bad.size(), paramKeys().size());
        for (const auto& [key, v] : bad) {
            for (LawKind law : allLaws()) {
                SimParams p = fig20Params();
                p.law = law;
                QVERIFY(setParam(p, key, v));
                const std::string k = key;
                const bool otherLaws = findParam(k)->group == ParamGroup::FrictionLaw && !lawHasParam(law, k);
                const ParamIssues issues = p.validate();
                if (otherLaws) {
                    QVERIFY(issues.empty());  // another law's fields do not concern this model
                    continue;
                }
                QVERIFY2(issues.size() == 1, qPrintable(QString("%1: %2").arg(key).arg(QString::fromStdString(formatIssues(issues)))));
                checkIssue(issues[0], key, v);
                for (SetupKind setup : {SetupKind::Dynamics, SetupKind::Prescribed}) {
                    p.setup = setup;
                    const RunResult r = simulate(p);
                    QVERIFY(r.status == RunStatus::Failed);
                    QVERIFY(r.samples.empty());
                    QVERIFY2(r.message.rfind(k + " = ", 0) == 0, r.message.c_str());
                }
            }
        }
        // The step must resolve the forcing: dt > T/8 is refused, naming dt and the bound.
        SimParams p = fig20Params();
        p.integration.dt_s = 0.05;  // T/8 = 0.0417 s at 3 Hz
        const ParamIssues issues = p.validate();
        QCOMPARE(issues.size(), size_t(1));
        checkIssue(issues[0], "dt", 0.05);
        QVERIFY(contains(issues[0].allowed, "T/8"));
    }

    // setParam/getParam round-trip every key; μ and ε_T set both laws; unknown keys are refused
    // with the list of known ones.
    void keysRoundTrip() {
        const std::vector<std::string> keys = paramKeys();
        const std::set<std::string> expected = {"A", "f", "phase", "tN", "k", "m", "c", "mu", "eta", "Dc",
                                                "C1", "r", "vc", "epsT", "dt", "output_every", "cycles", "transient",
                                                "a", "b", "V0"};
        QCOMPARE(std::set<std::string>(keys.begin(), keys.end()), expected);
        SimParams p;
        double x = 1.25;
        for (const auto& k : keys) {
            QVERIFY(setParam(p, k, x));
            double back = 0;
            QVERIFY(getParam(p, k, back));
            QCOMPARE(back, x);
            x += 0.5;
        }
        QCOMPARE(p.lawParams<CoulombParams>().mu, p.lawParams<RateStateParams>().mu);
        QCOMPARE(p.lawParams<CoulombParams>().epsT_N_per_m, p.lawParams<RateStateParams>().epsT_N_per_m);
        std::string err;
        QVERIFY(!setParam(p, "speed", 1.0, &err));
        QVERIFY2(contains(err, "speed") && contains(err, "epsT") && contains(err, "tN"), err.c_str());
        double v = 0;
        QVERIFY(!getParam(p, "speed", v));
    }

    // Derived quantities.
    // The parameter table (core/param_table.hpp): one row per key, each either a field of its
    // own or a key of at least one law; every law has μ and ε_T (the analyses scale by them);
    // defaults are the struct initialisers; the fit's ranges and the units come from the rows.
    void parameterTable() {
        std::set<std::string> seen;
        for (const ParamDef& d : paramTable()) {
            QVERIFY2(seen.insert(d.key).second, d.key);
            bool inLaw = false;
            for (LawKind law : allLaws()) inLaw = inLaw || lawHasParam(law, d.key);
            QVERIFY2((d.field != nullptr) != inLaw, d.key);
            QVERIFY2(*d.label && *d.doc && *d.quantity, d.key);
            QVERIFY2(d.sliderMax > d.sliderMin && d.displayScale > 0, d.key);
            std::string unit;
            QVERIFY(io::paramUnit(d.key, unit));
            QCOMPARE(unit, std::string(d.unit));
        }
        for (LawKind law : allLaws()) {
            QVERIFY(lawHasParam(law, "mu") && lawHasParam(law, "epsT"));
            for (const std::string& k : lawInfo(law).keys) QVERIFY2(findParam(k), k.c_str());
        }
        const SimParams p;
        QCOMPARE(paramDefault("mu"), p.lawParams<RateStateParams>().mu);
        QCOMPARE(paramDefault("Dc"), p.lawParams<RateStateParams>().Dc_m);
        QCOMPARE(paramDefault("m"), p.rig.mass_kg);
        QCOMPARE(paramDefault("b"), p.lawParams<DieterichRuinaParams>().b);
        QVERIFY(std::isnan(paramDefault("nope")));
        identify::FitParameter fp;
        QVERIFY(identify::defaultParameter("m", SetupKind::Dynamics, fp));
        QCOMPARE(fp.lower, findParam("m")->fit.lower);
        QCOMPARE(fp.upper, findParam("m")->fit.upper);
        QCOMPARE(fp.value, p.rig.mass_kg);
        QVERIFY(identify::defaultParameter("mu", SetupKind::Prescribed, fp));
        QCOMPARE(fp.upper, findParam("mu")->fitPrescribed.upper);
        QVERIFY(fp.scale == identify::ParamScale::Log);
        QVERIFY(!identify::defaultParameter("dt", SetupKind::Dynamics, fp));  // no fit range
        // A law key written once sets every law having it; getParam reads the selected law's.
        SimParams q;
        QVERIFY(setParam(q, "Dc", 5e-6));
        QCOMPARE(q.lawParams<DieterichRuinaParams>().Dc_m, 5e-6);
        q.lawParams<CoulombParams>().mu = 0.4;
        q.law = LawKind::Coulomb;
        double v = 0;
        QVERIFY(getParam(q, "mu", v));
        QCOMPARE(v, 0.4);
        QCOMPARE(lawMu(q), 0.4);
    }

    // checkParam (param_table.hpp): a value outside a row's bounds gives one issue naming the key,
    // the value and the bound (open or closed; the upper bound with its unit); in-range values,
    // both closed ends included, give none, and so does any value of an unknown key. Issues
    // are appended to what `out` already holds.
    void checkParamNamesKeyValueAndRange() {
        const struct {
            const char* key;
            double value;
            const char* message;
        } bad[] = {
            {"tN", -1.0, "tN = -1 is out of range: must be > 0"},
            {"tN", 0.0, "tN = 0 is out of range: must be > 0"},  // open lower bound
            {"k", -5.0, "k = -5 is out of range: must be >= 0"},
            {"A", 2.0, "A = 2 is out of range: must be <= 1 m"},
            {"A", -0.5, "A = -0.5 is out of range: must be >= 0"},
            {"Dc", -2e-5, "Dc = -2e-05 is out of range: must be > 0"},
            {"phase", kInf, "phase = inf is out of range: must be finite"},
            {"transient", -1.0, "transient = -1 is out of range: must be >= 0"},
        };
        for (const auto& c : bad) {
            ParamIssues out;
            checkParam(c.key, c.value, out);
            QVERIFY2(out.size() == 1, c.message);
            QCOMPARE(out[0].field, std::string(c.key));
            QCOMPARE(out[0].value, c.value);
            QCOMPARE(out[0].message(), std::string(c.message));
        }
        ParamIssues out;
        checkParam("tN", kNaN, out);  // NaN fails every comparison: out of range, not accepted
        QCOMPARE(out.size(), size_t(1));
        QVERIFY(std::isnan(out[0].value));
        for (const auto& [key, v] : std::vector<std::pair<const char*, double>>{
                 {"tN", 6.2}, {"A", 0.0}, {"A", 1.0}, {"k", 0.0}, {"phase", -7.0}, {"transient", 0.0}, {"dt", 1e-9}})
            checkParam(key, v, out);
        QVERIFY2(out.size() == 1, formatIssues(out).c_str());
        for (double v : {-1.0, kNaN, kInf}) checkParam("speed", v, out);  // unknown key: nothing to check
        checkParam("", -1.0, out);
        QCOMPARE(out.size(), size_t(1));
        checkParam("m", 0.0, out);  // appended after the NaN issue
        QCOMPARE(out.size(), size_t(2));
        QCOMPARE(out[1].field, std::string("m"));
        // Every row: its default is accepted; just past its lower bound (NaN when unbounded) is not.
        for (const ParamDef& d : paramTable()) {
            ParamIssues issues;
            checkParam(d.key, paramDefault(d.key), issues);
            QVERIFY2(issues.empty(), formatIssues(issues).c_str());
            const double below = !std::isfinite(d.lower) ? kNaN : d.lowerOpen ? d.lower : d.lower - 1.0;
            checkParam(d.key, below, issues);
            QVERIFY2(issues.size() == 1, d.key);
            checkIssue(issues[0], d.key, below);
        }
    }

    // fitParamKeys lists exactly the rows with a valid fit range, once each, in table order,
    // separated by single spaces; the help text's examples are among them and dt is not.
    void fitParamKeysAreTheFitRows() {
        const std::string listed = fitParamKeys();
        QVERIFY(!listed.empty() && listed.front() != ' ' && listed.back() != ' ');
        QVERIFY(!contains(listed, "  "));
        std::vector<std::string> keys;
        for (const QString& k : QString::fromStdString(listed).split(' ')) keys.push_back(k.toStdString());
        std::vector<std::string> expected;
        for (const ParamDef& d : paramTable())
            if (d.fit.valid()) expected.push_back(d.key);
        QCOMPARE(keys, expected);
        QCOMPARE(std::set<std::string>(keys.begin(), keys.end()).size(), keys.size());
        for (const std::string& k : keys) {
            const ParamDef* d = findParam(k);
            QVERIFY2(d && d->fit.valid() && d->fit.lower < d->fit.upper, k.c_str());
        }
        const std::set<std::string> set(keys.begin(), keys.end());
        for (const char* k : {"k", "m", "c", "tN", "mu", "eta", "Dc"}) QVERIFY2(set.count(k) == 1, k);
        for (const char* k : {"dt", "cycles", "A", "f", "phase"}) QVERIFY2(set.count(k) == 0, k);
    }

    // harmonicRunSteps = (transient + cycles)·T/dt: 140 cycles of 10 000 steps for fig22, 20 for
    // the default; a run without a transient takes that many steps, and a step budget below it
    // refuses the run before the first step.
    void harmonicRunStepsIsCyclesTimesStepsPerPeriod() {
        Preset fig22;
        QVERIFY(findPreset("fig22", fig22));
        QVERIFY(std::abs(harmonicRunSteps(fig22.params) - 140 * 10000.0) < 1e-6);
        SimParams p = fig20Params();
        QVERIFY(std::abs(harmonicRunSteps(p) - 20 * 10000.0) < 1e-6);
        p.drive.frequency_Hz = 5.0;  // T = 0.2 s
        p.integration.dt_s = 1e-4;
        p.transientCycles = 2.5;
        p.cycles = 1.5;
        QVERIFY(std::abs(harmonicRunSteps(p) - 8000.0) < 1e-6);
        p = fig20Params();
        p.cycles = 2;
        const RunResult r = simulate(p);
        QVERIFY2(r.ok(), r.message.c_str());
        QCOMPARE(r.stats.steps, std::lround(harmonicRunSteps(p)));
        p.integration.maxSteps = 19999;
        const RunResult refused = simulate(p);
        QVERIFY(refused.status == RunStatus::Failed && refused.samples.empty());
        QVERIFY2(refused.message.rfind("step budget exceeded: the run needs 20000 steps", 0) == 0, refused.message.c_str());
    }

    // paramKeysFor(law): the drive and rig keys first, the integration keys last, and between them
    // exactly the law's own keys (each law its own); every key is settable and reads back with
    // the law selected.
    void paramKeysForEachLaw() {
        const std::vector<std::string> head = {"A", "f", "phase", "tN", "k", "m", "c"};
        const std::vector<std::string> tail = {"dt", "output_every", "cycles", "transient"};
        const std::map<LawKind, std::set<std::string>> lawKeys = {
            {LawKind::RateState, {"mu", "eta", "Dc", "C1", "r", "vc", "epsT"}},
            {LawKind::Coulomb, {"mu", "epsT"}},
            {static_cast<LawKind>(lawIndex<DieterichRuinaLaw>(RegisteredLaws{})), {"mu", "a", "b", "Dc", "V0", "epsT"}},
        };
        QCOMPARE(lawKeys.size(), size_t(lawCount()));
        for (const auto& [law, own] : lawKeys) {
            const std::vector<std::string> keys = paramKeysFor(law);
            QVERIFY2(keys.size() == head.size() + own.size() + tail.size(), toString(law));
            QVERIFY(std::equal(head.begin(), head.end(), keys.begin()));
            QVERIFY(std::equal(tail.begin(), tail.end(), keys.end() - long(tail.size())));
            const std::set<std::string> middle(keys.begin() + long(head.size()), keys.end() - long(tail.size()));
            QVERIFY2(middle == own, toString(law));
            double x = 0.75;
            for (const std::string& k : keys) {
                SimParams p;
                p.law = law;
                std::string err;
                QVERIFY2(setParam(p, k, x, &err), err.c_str());
                double back = 0;
                QVERIFY(getParam(p, k, back));
                QCOMPARE(back, x);
                x += 0.25;
            }
        }
        // Rate-state and Coulomb differ, so the list is not the full key list.
        QVERIFY(paramKeysFor(LawKind::Coulomb) != paramKeysFor(LawKind::RateState));
        QVERIFY(paramKeysFor(LawKind::RateState).size() < paramKeys().size());
    }

    // The law registry (friction_law.hpp, law_list.hpp): one entry per RegisteredLaws type, in
    // LawKind order (lawIndex), with the law's key, label and viscous flag; makeLaw builds the
    // variant alternative of that index; lawMu/lawEpsT read the selected law's μ and ε_T.
    void lawRegistryInLawKindOrder() {
        static_assert(lawIndex<RateStateLaw>(RegisteredLaws{}) == 0 && lawIndex<CoulombLaw>(RegisteredLaws{}) == 1);
        static_assert(lawIndex<DieterichRuinaLaw>(RegisteredLaws{}) == 2);
        static_assert(lawIndex<int>(RegisteredLaws{}) == -1);  // not registered
        // lawKindOf: a law type's kind, the same index (used where a law's type is known).
        static_assert(lawKindOf<RateStateLaw>() == LawKind::RateState && lawKindOf<CoulombLaw>() == LawKind::Coulomb);
        static_assert(static_cast<int>(lawKindOf<DieterichRuinaLaw>()) == lawIndex<DieterichRuinaLaw>(RegisteredLaws{}));
        QCOMPARE(lawCount(), 3);
        QCOMPARE(lawCount(), RegisteredLaws::size);
        QCOMPARE(lawRegistry().size(), size_t(lawCount()));
        QCOMPARE(allLaws().size(), size_t(lawCount()));
        const struct {
            const char* key;
            const char* label;
            bool viscous;
        } expected[] = {{RateStateLaw::kKey, RateStateLaw::kLabel, true},
                        {CoulombLaw::kKey, CoulombLaw::kLabel, false},
                        {DieterichRuinaLaw::kKey, DieterichRuinaLaw::kLabel, true}};
        QCOMPARE(std::string(expected[0].key), std::string("rate-state"));
        QCOMPARE(std::string(expected[1].key), std::string("coulomb"));
        for (int i = 0; i < lawCount(); ++i) {
            const LawInfo& info = lawRegistry()[size_t(i)];
            QCOMPARE(static_cast<int>(info.kind), i);
            QCOMPARE(std::string(info.key), std::string(expected[i].key));
            QCOMPARE(std::string(info.label), std::string(expected[i].label));
            QCOMPARE(info.viscous, expected[i].viscous);
            QCOMPARE(&lawInfo(info.kind), &info);
            QVERIFY(allLaws()[size_t(i)] == info.kind);
            SimParams p;
            p.law = info.kind;
            QCOMPARE(int(makeLaw(p).index()), i);
        }
        QCOMPARE(&lawInfo(static_cast<LawKind>(lawCount())), &lawRegistry().front());  // unknown kind: the first
        QCOMPARE(&lawInfo(static_cast<LawKind>(-1)), &lawRegistry().front());
        // Each law its own μ and ε_T: the selected one is read.
        SimParams p;
        p.lawParams<RateStateParams>().mu = 0.31;
        p.lawParams<RateStateParams>().epsT_N_per_m = 2e5;
        p.lawParams<CoulombParams>().mu = 0.42;
        p.lawParams<CoulombParams>().epsT_N_per_m = 3e5;
        p.lawParams<DieterichRuinaParams>().mu = 0.53;
        p.lawParams<DieterichRuinaParams>().epsT_N_per_m = 4e5;
        const double mu[] = {0.31, 0.42, 0.53}, epsT[] = {2e5, 3e5, 4e5};
        for (int i = 0; i < lawCount(); ++i) {
            p.law = static_cast<LawKind>(i);
            QCOMPARE(lawMu(p), mu[i]);
            QCOMPARE(lawEpsT(p), epsT[i]);
            QCOMPARE(lawEpsT(p), std::visit([](const auto& l) { return l.epsT(); }, makeLaw(p)));
        }
        QVERIFY(setParam(p, "epsT", 7e5));  // written to every law
        for (LawKind law : allLaws()) {
            p.law = law;
            QCOMPARE(lawEpsT(p), 7e5);
        }
    }

    void derived() {
        DriveParams d;
        d.frequency_Hz = 4.0;
        QVERIFY(std::abs(d.omega() - 8.0 * std::numbers::pi) < 1e-12);
        QCOMPARE(d.period(), 0.25);
        RigParams r;
        r.stiffness_N_per_m = 400;
        r.mass_kg = 1;
        r.damping_Ns_per_m = 4;
        QCOMPARE(r.naturalFrequency_rad_s(), 20.0);
        QCOMPARE(r.dampingRatio(), 0.1);
        QCOMPARE(dampingFromRatio(0.1, 400, 1), 4.0);
        r.stiffness_N_per_m = 0;
        QCOMPARE(r.dampingRatio(), 0.0);  // no spring: no critical damping to refer to
        IntegrationParams i;
        i.dt_s = 1e-4;
        i.outputInterval_s = 5e-4;
        QCOMPARE(i.outputEvery(), 5L);
        i.outputInterval_s = 5.4e-4;  // rounded to a multiple of dt
        QCOMPARE(i.outputEvery(), 5L);
        i.outputInterval_s = 1e-5;  // finer than dt: every step
        QCOMPARE(i.outputEvery(), 1L);
        i.outputInterval_s = -1;
        QCOMPARE(i.outputEvery(), 1L);
        LawKind l;
        QVERIFY(parseLawKind(toString(LawKind::Coulomb), l) && l == LawKind::Coulomb);
        QVERIFY(parseLawKind(toString(LawKind::RateState), l) && l == LawKind::RateState);
        QVERIFY(!parseLawKind("lugre", l));
        SetupKind s;
        QVERIFY(parseSetupKind(toString(SetupKind::Prescribed), s) && s == SetupKind::Prescribed);
        QVERIFY(parseSetupKind(toString(SetupKind::Dynamics), s) && s == SetupKind::Dynamics);
        QVERIFY(!parseSetupKind("static", s));
        QVERIFY(formatIssues({}).empty());
    }

    // Every built-in preset is valid, named as documented and found by name.
    void presetsValid() {
        const auto all = builtinPresets();
        std::set<std::string> names;
        for (const Preset& p : all) {
            names.insert(p.name);
            QVERIFY2(p.params.validate().empty(), (p.name + ": " + formatIssues(p.params.validate())).c_str());
            QVERIFY(!p.description.empty());
            Preset q;
            QVERIFY(findPreset(p.name, q));
            QCOMPARE(QString::fromStdString(q.name), QString::fromStdString(p.name));
        }
        for (const char* n : {"default", "fig16", "fig17", "fig18", "fig19", "fig20", "fig22", "fig23"})
            QVERIFY2(names.count(n) == 1, n);
        Preset q;
        QVERIFY(!findPreset("fig99", q));
    }
};

QTEST_GUILESS_MAIN(TstParams)
#include "tst_params.moc"
