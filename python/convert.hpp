// Conversions between Python values and the engine's option text, arrays and JSON reports.
#pragma once

#include <initializer_list>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include "core/params.hpp"
#include "core/run_options.hpp"

namespace stickslip::python {

namespace py = pybind11;

// Raises the Python exception `type` (PyExc_ValueError, PyExc_OSError, ...) with `message`.
[[noreturn]] void raise(PyObject* type, const std::string& message);

// Option text of a value: a float as "%.17g" (reads back to the same double), an int in
// decimal, a str as is (units allowed, e.g. "0.4mm"). Anything else: TypeError naming `name`.
std::string valueText(py::handle value, const std::string& name);
// A str, or an iterable of str ("a.csv" or ["a.csv", "b.csv"]); None = empty.
std::vector<std::string> stringList(py::handle value, const std::string& name);

// Keyword arguments consumed by name; what is left goes to the run options.
class Kwargs {
public:
    explicit Kwargs(const py::kwargs& kw);
    bool has(const char* name) const;
    py::object take(const char* name);  // None when absent
    template <class T>
    void take(const char* name, T& out) {
        py::object v = take(name);
        if (!v.is_none()) out = v.cast<T>();
    }
    void takeText(const char* name, std::string& out);
    void takeList(const char* name, std::vector<std::string>& out);
    // Raises ValueError for every name left ("fn() got unexpected keyword 'x'"); `known` lists the accepted ones.
    void rejectRest(const std::string& function, const std::vector<std::string>& known) const;
    // The rest as run options on top of `preset` (parameter keys, model, setup, dt, cycles,
    // transient, output_every, tolerance); ValueError for anything else.
    SimOptions simOptions(const std::string& preset, const std::string& function,
                          const std::vector<std::string>& functionOptions);

private:
    py::dict d_;
};

// simParamsFromOptions, or ValueError with its message (key, value, allowed range).
SimParams simParams(const SimOptions& o);

py::array_t<double> toArray(const std::vector<double>& v);
py::array_t<long long> toIntArray(const std::vector<long long>& v);
py::array stringArray(const std::vector<std::string>& v);
// The JSON document as Python objects (json.loads of its text: null -> None).
py::object jsonToPython(const nlohmann::json& j);

// Every parameter of `p` by key (the Coulomb law's own mu and epsT when it is the law), plus
// "model" and "setup".
py::dict paramsDict(const SimParams& p);

}  // namespace stickslip::python
