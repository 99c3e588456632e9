// The Python module `stickslip`: the engine of StickSlip Lab (core/) with the options and
// results of stickslip-cli. See docs/python.md.
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "core/io/run_csv.hpp"
#include "core/params.hpp"
#include "core/version.hpp"

PYBIND11_MODULE(stickslip, m) {
    using namespace stickslip;
    m.doc() = "StickSlip Lab: friction stick-slip simulation, sweeps, maps, analyses, fits and effect identification "
              "(the engine of stickslip-cli; results match its CSV and JSON outputs).";
    m.attr("__version__") = kVersion;
    m.attr("PARAM_KEYS") = paramKeys();
    m.attr("RUN_COLUMNS") = io::runCsvColumns();
    python::bindSimulation(m);
    python::bindAnalysis(m);
    python::bindIdentify(m);
}
