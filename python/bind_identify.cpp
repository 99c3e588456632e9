// fit() and identify(): the options of `stickslip-cli fit` / `identify` as keyword arguments
// (same names, '-' as '_'), returning the JSON report those commands write, as a dict.
#include <functional>
#include <map>

#include "bindings.hpp"
#include "convert.hpp"
#include "core/identify/pipeline.hpp"
#include "job.hpp"

namespace stickslip::python {

namespace {

using namespace stickslip::identify;

template <class Req>
using Setters = std::map<std::string, std::function<void(Req&, py::handle)>>;

// Setters of a field by keyword: the value converted to the field's type.
template <class Req, class T>
std::pair<const std::string, std::function<void(Req&, py::handle)>> opt(const char* name, T Req::*field) {
    return {name, [field](Req& r, py::handle v) { r.*field = v.cast<T>(); }};
}
template <class Req, class F>
std::pair<const std::string, std::function<void(Req&, py::handle)>> fn(const char* name, F f) {
    return {name, std::function<void(Req&, py::handle)>(f)};
}
std::string text(py::handle v) {
    if (py::isinstance<py::str>(v)) return v.cast<std::string>();
    return py::str(v).cast<std::string>();
}
std::vector<std::string> list(py::handle v, const char* name) {
    if (py::isinstance<py::str>(v)) return splitList(v.cast<std::string>());
    return stringList(v, name);
}

// The options both commands share: inputs and cleaning.
template <class Req>
void addInputOptions(Setters<Req>& s) {
    s.insert(fn<Req>("validate_on", [](Req& r, py::handle v) { r.in.validateOn = stringList(v, "validate_on"); }));
    s.insert(fn<Req>("columns", [](Req& r, py::handle v) { r.in.columns = stringList(v, "columns"); }));
    s.insert(fn<Req>("units", [](Req& r, py::handle v) { r.in.units = stringList(v, "units"); }));
    s.insert(fn<Req>("run_sets", [](Req& r, py::handle v) { r.in.runSets = stringList(v, "run_sets"); }));
    s.insert(fn<Req>("manifest", [](Req& r, py::handle v) { r.in.manifest = stringList(v, "manifest").at(0); }));
    s.insert(fn<Req>("setup", [](Req& r, py::handle v) { r.in.setup = v.cast<std::string>(); }));
    s.insert(fn<Req>("no_bandstop", [](Req& r, py::handle v) { r.cleaning.noBandStop = v.cast<bool>(); }));
    s.insert(fn<Req>("no_lowpass", [](Req& r, py::handle v) { r.cleaning.noLowPass = v.cast<bool>(); }));
    s.insert(fn<Req>("no_steady_trim", [](Req& r, py::handle v) { r.cleaning.noSteadyTrim = v.cast<bool>(); }));
    s.insert(fn<Req>("bandstop_hz", [](Req& r, py::handle v) { r.cleaning.pre.filters.bandStopCenter_Hz = v.cast<double>(); }));
    s.insert(fn<Req>("bandstop_width", [](Req& r, py::handle v) { r.cleaning.pre.filters.bandStopWidth_Hz = v.cast<double>(); }));
    s.insert(fn<Req>("bandstop_order", [](Req& r, py::handle v) { r.cleaning.pre.filters.bandStopOrder = v.cast<int>(); }));
    s.insert(fn<Req>("lowpass_hz", [](Req& r, py::handle v) { r.cleaning.pre.filters.lowPass_Hz = v.cast<double>(); }));
    s.insert(fn<Req>("lowpass_order", [](Req& r, py::handle v) { r.cleaning.pre.filters.lowPassOrder = v.cast<int>(); }));
    s.insert(fn<Req>("trim_start", [](Req& r, py::handle v) { r.cleaning.pre.trim.start_s = v.cast<double>(); }));
    s.insert(fn<Req>("trim_end", [](Req& r, py::handle v) { r.cleaning.pre.trim.end_s = v.cast<double>(); }));
    s.insert(fn<Req>("stage_harmonics", [](Req& r, py::handle v) { r.cleaning.pre.stageFourierOrder = v.cast<int>(); }));
    s.insert(fn<Req>("fuse_slider_acceleration", [](Req& r, py::handle v) { r.cleaning.pre.fuseSliderAcceleration = v.cast<bool>(); }));
    s.insert(fn<Req>("free", [](Req& r, py::handle v) {
        if (py::isinstance<py::str>(v)) r.free = v.cast<std::string>();
        else { r.free.clear(); for (const auto& n : stringList(v, "free")) r.free += (r.free.empty() ? "" : ",") + n; }
    }));
}

Setters<FitRequest> fitSetters() {
    using R = FitRequest;
    Setters<R> s = {
        opt("model", &R::model), opt("split_time", &R::splitTime), opt("multistarts", &R::multistarts),
        opt("max_iterations", &R::maxIterations), opt("agreeing_starts", &R::agreeingStarts),
        opt("initial_state", &R::initialState), opt("fd_step", &R::relativeStep), opt("jackknife", &R::jackknife),
        opt("coordinates", &R::coordinates), opt("robust", &R::robust), opt("robust_scale", &R::robustScale),
        opt("seed", &R::seed), opt("no_filter_prediction", &R::noFilterPrediction),
        fn<R>("set", [](R& r, py::handle v) {  // {"C1": 0.25} or ["C1=0.25"]
            r.sets.clear();
            if (py::isinstance<py::dict>(v))
                for (auto kv : v.cast<py::dict>()) r.sets.push_back(text(kv.first) + "=" + valueText(kv.second, text(kv.first)));
            else r.sets = stringList(v, "set");
        }),
        fn<R>("stride", [](R& r, py::handle v) { r.predict.stride = v.cast<int>(); }),
        fn<R>("substeps", [](R& r, py::handle v) { r.predict.substeps = v.cast<int>(); }),
        fn<R>("segment", [](R& r, py::handle v) { r.predict.segment_s = v.cast<double>(); }),
        fn<R>("segment_spacing", [](R& r, py::handle v) { r.predict.segmentSpacing_s = v.cast<double>(); }),
        fn<R>("dt", [](R& r, py::handle v) { r.predict.dt_s = v.cast<double>(); }),
        fn<R>("slip_start", [](R& r, py::handle v) { r.predict.slipStartFraction = v.cast<double>(); }),
    };
    addInputOptions(s);
    return s;
}

Setters<IdentifyRequest> identifySetters() {
    using R = IdentifyRequest;
    auto o = [](const char* name, auto IdentifyOptions::*field) {
        return fn<R>(name, [field](R& r, py::handle v) {
            r.options.*field = v.cast<std::remove_reference_t<decltype(r.options.*field)>>();
        });
    };
    Setters<R> s = {
        opt("dynamics_residual", &R::dynamicsResidual),
        fn<R>("candidates", [](R& r, py::handle v) { r.candidates = list(v, "candidates"); }),
        o("max_effects", &IdentifyOptions::maxEffects), o("bic_margin", &IdentifyOptions::bicMargin),
        o("restart_margin", &IdentifyOptions::restartMargin),
        o("null_alpha", &IdentifyOptions::nullAlpha), o("null_replicas", &IdentifyOptions::nullReplicas),
        o("null_numerics", &IdentifyOptions::nullNumerics),
        o("held_out_alpha", &IdentifyOptions::heldOutAlpha), o("held_out_mid_p", &IdentifyOptions::heldOutMidP), o("min_held_out_gain", &IdentifyOptions::minHeldOutGain),
        o("identifiability_alpha", &IdentifyOptions::identifiabilityAlpha), o("decimate", &IdentifyOptions::decimate),
        o("substeps", &IdentifyOptions::substeps), o("multistarts", &IdentifyOptions::multistarts),
        o("max_segments", &IdentifyOptions::maxSegmentsPerRun), o("seed", &IdentifyOptions::seed),
        o("confounded_vif", &IdentifyOptions::confoundedVif), o("held_out_restart", &IdentifyOptions::heldOutRestart),
        o("forward_jacobian", &IdentifyOptions::forwardJacobian), o("analytic_jacobian", &IdentifyOptions::analyticJacobian), o("line_search_steps", &IdentifyOptions::lineSearchSteps), o("loo_function_tolerance", &IdentifyOptions::looFunctionTolerance), o("curve_coordinates", &IdentifyOptions::curveCoordinates),
        o("exact_state_step", &IdentifyOptions::exactStateStep), o("recorded_step_slip", &IdentifyOptions::recordedStepSlip),
        fn<R>("self_test", [](R& r, py::handle v) { r.selfTest = v.cast<bool>(); }),
        fn<R>("self_test_replicas", [](R& r, py::handle v) { r.selfTestReplicas = v.cast<int>(); }),
        fn<R>("self_test_levels", [](R& r, py::handle v) {
            r.selfTestLevels.clear();
            if (py::isinstance<py::float_>(v) || py::isinstance<py::int_>(v)) r.selfTestLevels.push_back(v.cast<double>());
            else
                for (auto x : v) r.selfTestLevels.push_back(x.cast<double>());
        }),
        fn<R>("self_test_size", [](R& r, py::handle v) {  // {"backlash": 1e-4} or ["backlash=1e-4"]
            r.selfTestSizes.clear();
            if (py::isinstance<py::dict>(v))
                for (auto kv : v.cast<py::dict>()) r.selfTestSizes.push_back(text(kv.first) + "=" + valueText(kv.second, text(kv.first)));
            else r.selfTestSizes = stringList(v, "self_test_size");
        }),
        fn<R>("epsT", [](R& r, py::handle v) { r.options.start.epsT_N_per_m = v.cast<double>(); }),
        fn<R>("Dc", [](R& r, py::handle v) { r.options.start.Dc_m = v.cast<double>(); }),
    };
    addInputOptions(s);
    return s;
}

template <class Req>
void applyKwargs(Req& req, const Setters<Req>& setters, const py::kwargs& kw, const char* function) {
    for (auto item : kw) {
        const std::string name = item.first.cast<std::string>();
        const auto it = setters.find(name);
        if (it == setters.end()) {
            std::string known;
            for (const auto& [k, f] : setters) known += " " + k;
            raise(PyExc_ValueError, std::string(function) + "(): unknown keyword argument '" + name + "' (known:" + known + ")");
        }
        if (!item.second.is_none()) it->second(req, item.second);
    }
}

void raiseFor(const PipelineStatus& st) {
    switch (st.code) {
        case PipelineCode::Ok: return;
        case PipelineCode::BadArguments: raise(PyExc_ValueError, st.message);
        case PipelineCode::BadInput: raise(PyExc_OSError, st.message);
        case PipelineCode::Cancelled: raise(PyExc_KeyboardInterrupt, st.message);
        case PipelineCode::RunFailed: break;
    }
    raise(PyExc_RuntimeError, st.message);
}

py::object fit(py::object data, const py::kwargs& kw) {
    static const Setters<FitRequest> setters = fitSetters();
    FitRequest req;
    req.in.data = stringList(data, "data");
    applyKwargs(req, setters, kw, "fit");
    auto [ok, report, st] = runCancellable([&](const std::atomic<bool>& cancel) {
        FitRequest r = req;
        r.cancel = &cancel;
        FitOutcome out;
        PipelineStatus status;
        const bool good = runFitRequest(r, out, status);
        return std::tuple{good, std::move(out.report), status};
    });
    if (!ok) raiseFor(st);
    return jsonToPython(report);
}

py::object identify(py::object data, const py::kwargs& kw) {
    static const Setters<IdentifyRequest> setters = identifySetters();
    IdentifyRequest req;
    req.in.data = stringList(data, "data");
    applyKwargs(req, setters, kw, "identify");
    auto [ok, report, st] = runCancellable([&](const std::atomic<bool>& cancel) {
        IdentifyRequest r = req;
        r.options.cancel = &cancel;
        IdentifyResult res;
        nlohmann::json j;
        PipelineStatus status;
        const bool good = runIdentifyRequest(r, res, j, status);
        return std::tuple{good, std::move(j), status};
    });
    if (!ok) raiseFor(st);
    return jsonToPython(report);
}

}  // namespace

void bindIdentify(py::module_& m) {
    m.def("fit", &fit, py::arg("data"),
          "fit(data, *, validate_on=None, manifest=None, setup=None, columns=None, units=None, run_sets=None, "
          "model='rate-state', free='mu,eta,Dc,vc,epsT', set=None, split_time=0, multistarts=3, max_iterations=40, "
          "agreeing_starts=2, jackknife=False, seed=20260101, ...) -> the report of `stickslip-cli fit --report` as "
          "a dict. data: a CSV path or a list of them. Every option of `stickslip-cli fit` is a keyword "
          "('--max-iterations' -> max_iterations). Releases the GIL; Ctrl-C cancels (KeyboardInterrupt). "
          "ValueError for bad arguments, OSError for unreadable input, RuntimeError when the fit fails.");
    m.def("identify", &identify, py::arg("data"),
          "identify(data, *, validate_on=None, manifest=None, setup=None, free='mu,C1,eta,Dc,vc,epsT', "
          "candidates=None, max_effects=..., null_replicas=..., decimate=0, multistarts=..., ...) -> the report of "
          "`stickslip-cli identify --report` as a dict. Every option of the command is a keyword ('-' -> '_'). "
          "Releases the GIL; Ctrl-C cancels (KeyboardInterrupt).");
}

}  // namespace stickslip::python
