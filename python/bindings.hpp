// The parts of the module, one register function per area.
#pragma once

#include <pybind11/pybind11.h>

namespace stickslip::python {

void bindSimulation(pybind11::module_& m);  // presets, params, simulate
void bindAnalysis(pybind11::module_& m);    // sweep, map, analyze
void bindIdentify(pybind11::module_& m);    // fit, identify

}  // namespace stickslip::python
