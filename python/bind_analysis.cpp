// sweep(), map(), analyze(): the options and outputs of `stickslip-cli sweep`, `map`, `analyze`.
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "convert.hpp"
#include "core/analysis/analyze_run.hpp"
#include "core/analysis/periodicity_map.hpp"
#include "core/analysis/sweep.hpp"
#include "core/io/csv_table.hpp"
#include "core/io/units.hpp"
#include "core/version.hpp"
#include "job.hpp"

namespace stickslip::python {

namespace {

// A value of parameter `key` given as a number (SI) or a string with a unit.
double keyValue(const std::string& key, py::handle v, const char* name) {
    if (v.is_none()) raise(PyExc_ValueError, std::string(name) + " is required");
    std::string unit;
    if (!io::paramUnit(key, unit)) {
        std::string keys;
        for (const std::string& k : paramKeys()) keys += " " + k;
        raise(PyExc_ValueError, "'" + key + "' is not a parameter key (known:" + keys + ")");
    }
    double x = 0;
    std::string error;
    if (!io::parseParamValue(key, valueText(v, name), x, &error)) raise(PyExc_ValueError, error);
    return x;
}

void raiseForStatus(RunStatus s, const std::string& what, const std::string& message) {
    if (s == RunStatus::Failed) raise(PyExc_RuntimeError, what + " failed: " + message);
    if (s == RunStatus::Cancelled) raise(PyExc_RuntimeError, what + " cancelled");
}

py::dict sweepTables(const SweepResult& r) {
    std::vector<double> value, slider, vel, ratio, svalue, stick, vmax, lyap;
    std::vector<long long> sample, period;
    std::vector<std::string> dir, sdir, cls;
    for (const SweepPoint& pt : r.points) {
        const std::string d = pt.direction > 0 ? "up" : "down";
        for (std::size_t i = 0; i < pt.section.size(); ++i) {
            value.push_back(pt.value);
            dir.push_back(d);
            sample.push_back(static_cast<long long>(i));
            slider.push_back(pt.section.slider_m[i]);
            vel.push_back(pt.section.relVel_mps[i]);
            ratio.push_back(pt.section.ratio[i]);
        }
        svalue.push_back(pt.value);
        sdir.push_back(d);
        cls.push_back(toString(pt.classification.motion));
        period.push_back(pt.classification.period);
        stick.push_back(pt.classification.stickFraction);
        vmax.push_back(pt.classification.maxRelVel_mps);
        lyap.push_back(pt.lyapunovPerSecond);
    }
    py::dict samples, summary, out;
    samples["param_value"] = toArray(value);
    samples["direction"] = stringArray(dir);
    samples["sample"] = toIntArray(sample);
    samples["slider_disp_m"] = toArray(slider);
    samples["rel_vel_mps"] = toArray(vel);
    samples["friction_ratio"] = toArray(ratio);
    summary["param_value"] = toArray(svalue);
    summary["direction"] = stringArray(sdir);
    summary["class"] = stringArray(cls);
    summary["period"] = toIntArray(period);
    summary["stick_fraction"] = toArray(stick);
    summary["max_rel_vel_mps"] = toArray(vmax);
    summary["lyapunov_per_s"] = toArray(lyap);
    out["samples"] = samples;
    out["summary"] = summary;
    return out;
}

py::dict sweep(const std::string& preset, const py::kwargs& kw) {
    Kwargs k(kw);
    SweepOptions so;
    std::string direction = "up", mode = "continuation";
    bool lyapunov = true;
    k.take("param", so.key);
    const py::object start = k.take("start"), stop = k.take("stop");
    k.take("steps", so.steps);
    k.take("direction", direction);
    k.take("mode", mode);
    k.take("settle", so.settleCycles);
    k.take("samples", so.sampleCycles);
    k.take("steps_per_period", so.stepsPerPeriod);
    k.take("threads", so.threads);
    k.take("concurrent_branches", so.concurrentBranches);
    k.take("phase", so.phase_rad);
    k.take("tol", so.classify.relTol);
    k.take("lyapunov", lyapunov);
    const SimParams p = simParams(k.simOptions(preset, "sweep",
        {"param", "start", "stop", "steps", "direction", "mode", "settle", "samples", "steps_per_period", "threads",
         "concurrent_branches", "phase", "tol", "lyapunov"}));
    so.from = keyValue(so.key, start, "start");
    so.to = keyValue(so.key, stop, "stop");
    if (!parseSweepDirection(direction, so.direction))
        raise(PyExc_ValueError, "direction '" + direction + "' is not one of: up, down, both");
    if (!parseSweepMode(mode, so.mode)) raise(PyExc_ValueError, "mode '" + mode + "' is not one of: continuation, independent");
    so.lyapunov = lyapunov;
    if (ParamIssues issues = so.validate(p); !issues.empty()) raise(PyExc_ValueError, formatIssues(issues));
    const SweepResult r = runCancellable([&](const std::atomic<bool>& cancel) {
        RunControl ctl;
        ctl.cancel = &cancel;
        return bifurcationSweep(p, so, ctl);
    });
    raiseForStatus(r.status, "sweep", r.message);
    py::dict out = sweepTables(r);
    out["steps_per_period"] = stepsPerPeriodFor(p, so.stepsPerPeriod);
    return out;
}

py::dict map(const std::string& preset, const py::kwargs& kw) {
    Kwargs k(kw);
    MapOptions mo;
    k.take("param", mo.key1);
    k.take("param2", mo.key2);
    const py::object s1 = k.take("start"), e1 = k.take("stop"), s2 = k.take("start2"), e2 = k.take("stop2");
    k.take("steps", mo.steps1);
    k.take("steps2", mo.steps2);
    k.take("settle", mo.settleCycles);
    k.take("samples", mo.sampleCycles);
    k.take("steps_per_period", mo.stepsPerPeriod);
    k.take("threads", mo.threads);
    k.take("tol", mo.classify.relTol);
    const SimParams p = simParams(k.simOptions(preset, "map",
        {"param", "start", "stop", "steps", "param2", "start2", "stop2", "steps2", "settle", "samples",
         "steps_per_period", "threads", "tol"}));
    mo.from1 = keyValue(mo.key1, s1, "start");
    mo.to1 = keyValue(mo.key1, e1, "stop");
    mo.from2 = keyValue(mo.key2, s2, "start2");
    mo.to2 = keyValue(mo.key2, e2, "stop2");
    if (ParamIssues issues = mo.validate(p); !issues.empty()) raise(PyExc_ValueError, formatIssues(issues));
    const PeriodicityMap m = runCancellable([&](const std::atomic<bool>& cancel) {
        RunControl ctl;
        ctl.cancel = &cancel;
        return periodicityMap(p, mo, ctl);
    });
    raiseForStatus(m.status, "map", m.message);
    std::vector<double> v1, v2, stick, vmax;
    std::vector<long long> period;
    std::vector<std::string> cls;
    for (std::size_t i2 = 0; i2 < m.values2.size(); ++i2)
        for (std::size_t i1 = 0; i1 < m.values1.size(); ++i1) {
            const std::size_t c = m.index(i1, i2);
            if (!m.done[c]) continue;
            v1.push_back(m.values1[i1]);
            v2.push_back(m.values2[i2]);
            cls.push_back(toString(m.motion[c]));
            period.push_back(m.period[c]);
            stick.push_back(m.stickFraction[c]);
            vmax.push_back(m.maxRelVel_mps[c]);
        }
    py::dict out;
    out["param_value"] = toArray(v1);
    out["param2_value"] = toArray(v2);
    out["class"] = stringArray(cls);
    out["period"] = toIntArray(period);
    out["stick_fraction"] = toArray(stick);
    out["max_rel_vel_mps"] = toArray(vmax);
    return out;
}

// A run given as a dict of columns (e.g. simulate()'s result) as a table.
io::CsvTable tableFromColumns(const py::dict& cols) {
    io::CsvTable t;
    t.path = "<dict>";
    for (auto item : cols) {
        t.header.push_back(item.first.cast<std::string>());
        t.columns.push_back(item.second.cast<std::vector<double>>());
    }
    return t;
}

py::object analyze(py::object input, double frequency, double naturalFrequency, double maxLag) {
    io::CsvTable t;
    std::string name;
    if (py::isinstance<py::dict>(input)) {
        t = tableFromColumns(input.cast<py::dict>());
        name = t.path;
    } else {
        name = py::module_::import("os").attr("fspath")(input).cast<std::string>();
        io::CsvError err;
        if (!io::readCsvTable(name, t, err)) raise(PyExc_OSError, err.what());
    }
    AnalyzeSettings s;
    s.frequency_Hz = frequency;
    s.naturalFrequency_rad_s = naturalFrequency;
    s.maxLag_s = maxLag;
    nlohmann::json j;
    std::string error;
    if (!analyzeRunTable(t, name, s, std::string("stickslip ") + kVersion + " (python)", j, &error))
        raise(PyExc_ValueError, error);
    return jsonToPython(j);
}

}  // namespace

void bindAnalysis(py::module_& m) {
    m.def("sweep", &sweep, py::arg("preset") = "default",
          "sweep(preset='default', *, param='A', start, stop, steps=50, direction='up', mode='continuation', "
          "settle=50, samples=100, steps_per_period=0, threads=0, concurrent_branches=False, phase=0.0, tol=1e-4, "
          "lyapunov=True, **params) -> {'samples': columns of `stickslip-cli sweep --out`, 'summary': columns of "
          "--summary, 'steps_per_period': int}. start/stop: numbers (SI) or strings with a unit. "
          "Numeric columns are numpy arrays; direction and class are arrays of str.");
    m.def("map", &map, py::arg("preset") = "default",
          "map(preset='default', *, param='A', start, stop, steps=20, param2='f', start2, stop2, steps2=20, "
          "settle=50, samples=64, steps_per_period=0, threads=0, tol=1e-4, **params) -> dict of the columns of "
          "`stickslip-cli map` (param_value, param2_value, class, period, stick_fraction, max_rel_vel_mps).");
    m.def("analyze", &analyze, py::arg("input"), py::kw_only(), py::arg("frequency") = 0.0,
          py::arg("natural_frequency") = 0.0, py::arg("max_lag") = 2.0,
          "analyze(input, *, frequency=0, natural_frequency=0, max_lag=2.0) -> the JSON report of "
          "`stickslip-cli analyze` as a dict. input: a run CSV path, or a dict of columns (simulate()'s result; "
          "without '#' lines the forcing frequency comes from the option or the stage spectrum).");
}

}  // namespace stickslip::python
