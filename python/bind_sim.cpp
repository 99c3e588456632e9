// presets(), params(), simulate(): the run options of `stickslip-cli simulate` as keyword arguments.
#include <stdexcept>

#include "bindings.hpp"
#include "convert.hpp"
#include "core/integrate/simulate.hpp"
#include "core/io/run_csv.hpp"
#include "core/presets.hpp"
#include "job.hpp"

namespace stickslip::python {

namespace {

py::list presets() {
    py::list out;
    for (const Preset& p : builtinPresets()) {
        py::dict d;
        d["name"] = p.name;
        d["description"] = p.description;
        d["params"] = paramsDict(p.params);
        out.append(d);
    }
    return out;
}

py::dict params(const std::string& preset, const py::kwargs& kw) {
    Kwargs k(kw);
    return paramsDict(simParams(k.simOptions(preset, "params", {})));
}

py::dict simulateRun(const std::string& preset, const py::kwargs& kw) {
    Kwargs k(kw);
    std::string input;
    k.takeText("input", input);
    SimOptions o = k.simOptions(preset, "simulate", {"input"});
    SlipHistory history;
    if (!input.empty()) {
        if (o.setup.empty()) o.setup = "prescribed";  // an input history implies the prescribed set-up
        if (o.setup != "prescribed") raise(PyExc_ValueError, "input needs setup='prescribed' (got setup='" + o.setup + "')");
    }
    const SimParams p = simParams(o);
    if (!input.empty()) {
        io::CsvError err;
        if (!io::readSlipHistoryCsv(input, history, err)) raise(PyExc_OSError, err.what());
    }
    const SlipHistory* h = input.empty() ? nullptr : &history;
    const RunResult r = runCancellable([&](const std::atomic<bool>& cancel) {
        RunControl ctl;
        ctl.cancel = &cancel;
        return simulate(p, ctl, h);
    });
    if (r.status == RunStatus::Failed) raise(PyExc_RuntimeError, "run failed: " + r.message);
    if (r.status == RunStatus::Cancelled) raise(PyExc_RuntimeError, "run cancelled: " + r.message);
    const auto values = io::runCsvValues(r);
    py::dict out;
    for (size_t j = 0; j < values.size(); ++j) out[py::str(io::runCsvColumns()[j])] = toArray(values[j]);
    return out;
}

}  // namespace

void bindSimulation(py::module_& m) {
    m.def("presets", &presets,
          "The built-in parameter sets: a list of dicts with name, description and params "
          "(every parameter key, model and setup), as `stickslip-cli presets NAME` shows them.");
    m.def("params", &params, py::arg("preset") = "default",
          "The validated parameters (dict by key, plus model and setup) that simulate() would run with the "
          "same arguments. Raises ValueError naming the field, value and allowed range.");
    m.def("simulate", &simulateRun, py::arg("preset") = "default",
          "simulate(preset='default', *, model=None, setup=None, input=None, cycles=None, transient=None, dt=None, "
          "output_every=None, **params) -> dict of numpy float64 arrays by the column names of "
          "`stickslip-cli simulate` (time_s, stage_disp_m, slider_disp_m, slider_vel_mps, rel_vel_mps, "
          "friction_force_N, friction_ratio, state_alpha, stuck).\n\n"
          "params: any parameter key (A, f, phase, tN, k, m, c, mu, eta, Dc, C1, r, vc, epsT, ...) as a number in SI "
          "units or a string with a unit ('0.4mm'), as `--set KEY=VALUE`. input: a prescribed slip history CSV. "
          "The run releases the GIL; Ctrl-C cancels it (KeyboardInterrupt). Bad arguments raise ValueError.");
}

}  // namespace stickslip::python
