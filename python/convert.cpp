#include "convert.hpp"

#include <algorithm>
#include <cstdio>

namespace stickslip::python {

using namespace pybind11::literals;

void raise(PyObject* type, const std::string& message) {
    PyErr_SetString(type, message.c_str());
    throw py::error_already_set();
}

std::string valueText(py::handle value, const std::string& name) {
    if (py::isinstance<py::bool_>(value)) raise(PyExc_TypeError, name + ": expected a number or a string, got a bool");
    if (py::isinstance<py::int_>(value)) return py::str(value);
    if (py::isinstance<py::float_>(value)) {
        char buf[40];
        std::snprintf(buf, sizeof buf, "%.17g", value.cast<double>());
        return buf;
    }
    if (py::isinstance<py::str>(value)) return value.cast<std::string>();
    // numpy scalars and other numbers
    if (PyNumber_Check(value.ptr())) return valueText(py::float_(py::reinterpret_borrow<py::object>(value)), name);
    raise(PyExc_TypeError, name + ": expected a number or a string, got " +
                               std::string(py::str(value.get_type().attr("__name__"))));
}

std::vector<std::string> stringList(py::handle value, const std::string& name) {
    std::vector<std::string> out;
    if (value.is_none()) return out;
    if (py::isinstance<py::str>(value)) return {value.cast<std::string>()};
    if (py::hasattr(value, "__fspath__"))  // one os.PathLike (pathlib.Path)
        return {py::module_::import("os").attr("fspath")(value).cast<std::string>()};
    if (!py::isinstance<py::iterable>(value)) raise(PyExc_TypeError, name + ": expected a str or a list of str");
    for (py::handle item : value) {
        // os.PathLike (pathlib.Path) as well as str
        py::object s = py::module_::import("os").attr("fspath")(item);
        out.push_back(s.cast<std::string>());
    }
    return out;
}

Kwargs::Kwargs(const py::kwargs& kw) : d_(py::dict(kw)) {}

bool Kwargs::has(const char* name) const { return d_.contains(name); }

py::object Kwargs::take(const char* name) {
    if (!d_.contains(name)) return py::none();
    py::object v = d_[name];
    PyDict_DelItemString(d_.ptr(), name);
    return v;
}

void Kwargs::takeText(const char* name, std::string& out) {
    py::object v = take(name);
    if (v.is_none()) return;
    if (py::hasattr(v, "__fspath__")) v = py::module_::import("os").attr("fspath")(v);
    out = valueText(v, name);
}

void Kwargs::takeList(const char* name, std::vector<std::string>& out) {
    py::object v = take(name);
    if (!v.is_none()) out = stringList(v, name);
}

void Kwargs::rejectRest(const std::string& function, const std::vector<std::string>& known) const {
    if (d_.empty()) return;
    std::string names, list;
    for (auto item : d_) names += (names.empty() ? "'" : ", '") + item.first.cast<std::string>() + "'";
    for (const std::string& k : known) list += " " + k;
    raise(PyExc_ValueError, function + "(): unknown keyword argument(s) " + names + " (known:" + list + ")");
}

SimOptions Kwargs::simOptions(const std::string& preset, const std::string& function,
                              const std::vector<std::string>& functionOptions) {
    SimOptions o;
    o.preset = preset;
    takeText("model", o.model);
    takeText("setup", o.setup);
    takeText("dt", o.dt);
    takeText("cycles", o.cycles);
    takeText("transient", o.transient);
    takeText("output_every", o.outputEvery);
    takeText("tolerance", o.tolerance);
    const std::vector<std::string> keys = paramKeys();
    for (auto item : py::dict(d_)) {  // a copy: taking from d_ while iterating it
        const std::string key = item.first.cast<std::string>();
        if (std::find(keys.begin(), keys.end(), key) == keys.end()) continue;
        o.sets.push_back(key + "=" + valueText(item.second, key));
        take(key.c_str());
    }
    std::vector<std::string> known = functionOptions;
    for (const char* k : {"preset", "model", "setup"}) known.emplace_back(k);
    known.insert(known.end(), keys.begin(), keys.end());
    rejectRest(function, known);
    return o;
}

SimParams simParams(const SimOptions& o) {
    SimParams p;
    std::string error;
    if (!simParamsFromOptions(o, p, &error)) raise(PyExc_ValueError, error);
    return p;
}

py::array_t<double> toArray(const std::vector<double>& v) {
    py::array_t<double> a(static_cast<py::ssize_t>(v.size()));
    std::copy(v.begin(), v.end(), a.mutable_data());
    return a;
}

py::array_t<long long> toIntArray(const std::vector<long long>& v) {
    py::array_t<long long> a(static_cast<py::ssize_t>(v.size()));
    std::copy(v.begin(), v.end(), a.mutable_data());
    return a;
}

py::array stringArray(const std::vector<std::string>& v) {
    py::list l;
    for (const std::string& s : v) l.append(s);
    return py::module_::import("numpy").attr("array")(l, "dtype"_a = "str");
}

py::object jsonToPython(const nlohmann::json& j) {
    return py::module_::import("json").attr("loads")(j.dump());
}

py::dict paramsDict(const SimParams& p) {
    py::dict d;
    d["model"] = toString(p.law);
    d["setup"] = toString(p.setup);
    for (const std::string& key : paramKeys()) {
        double v = 0;
        if (!getParam(p, key, v)) continue;
        d[py::str(key)] = v;
    }
    return d;
}

}  // namespace stickslip::python
