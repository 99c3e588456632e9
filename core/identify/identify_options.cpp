// The identify loop's options and the self-test's: their checks (Options + validate(), named
// fields and allowed ranges) and the self-test's stated sizes.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <string>

#include "effects/registry.hpp"
#include "identify.hpp"
#include "self_test.hpp"

namespace stickslip::identify {

ParamIssues IdentifyOptions::validate() const {
    ParamIssues out;
    auto range = [&](const char* field, double v, bool ok, const char* allowed) {
        if (!ok) out.push_back({field, v, allowed, {}});
    };
    range("max_effects", maxEffects, maxEffects >= 0, ">= 0");
    range("multistarts", multistarts, multistarts >= 1, ">= 1");
    range("line_search_steps", lineSearchSteps, lineSearchSteps >= 1, ">= 1");
    range("loo_function_tolerance", looFunctionTolerance, looFunctionTolerance > 0 && looFunctionTolerance <= 1e-2,
          "in (0, 0.01]");
    range("confounded_vif", confoundedVif, confoundedVif > 1.0, "> 1");
    range("bic_margin", bicMargin, bicMargin >= 0, ">= 0");
    range("restart_margin", restartMargin, restartMargin >= 0, ">= 0");
    range("null_alpha", nullAlpha, nullAlpha > 0 && nullAlpha < 1, "in (0, 1)");
    range("null_replicas", nullReplicas, nullReplicas >= 0 && nullReplicas <= 100000, "in [0, 100000]");
    range("simulated_null_replicas", simulatedNullReplicas, simulatedNullReplicas >= 0 && simulatedNullReplicas <= 1000,
          "in [0, 1000]");
    range("simulated_null_steps_per_sample", simulatedNullStepsPerSample,
          simulatedNullStepsPerSample >= 1 && simulatedNullStepsPerSample <= 1000, "in [1, 1000]");
    range("simulated_null_bias_steps", simulatedNullBiasSteps, simulatedNullBiasSteps >= 0 && simulatedNullBiasSteps <= 20,
          "in [0, 20]");
    range("held_out_alpha", heldOutAlpha, heldOutAlpha > 0 && heldOutAlpha < 1, "in (0, 1)");
    range("min_held_out_gain", minHeldOutGain, minHeldOutGain >= 0 && minHeldOutGain < 1, "in [0, 1)");
    range("identifiability_alpha", identifiabilityAlpha, identifiabilityAlpha > 0 && identifiabilityAlpha < 1, "in (0, 1)");
    for (const ParamIssue& i : selfTest.validate()) out.push_back(i);
    return out;
}

ParamIssues SelfTestOptions::validate() const {
    ParamIssues out;
    auto note = [&](const char* field, std::string text) { out.push_back(ParamIssue::note(field, std::move(text))); };
    if (replicas < 0 || replicas > 10000)
        note("replicas", "self-test replicas = " + std::to_string(replicas) + " is outside the allowed range [0, 10000]");
    if (replicas > 0 && levels.empty() && sizes.empty()) note("levels", "self-test: no signal level and no stated size");
    for (double l : levels)
        if (!(l > 0 && l <= 100)) note("levels", "self-test level = " + std::to_string(l) + " is outside the allowed range (0, 100]");
    for (const auto& [name, v] : sizes) {
        EffectInfo info;
        if (!findEffect(name, info)) {
            note("sizes", "self-test size: unknown effect '" + name + "'");
            continue;
        }
        const EffectParam& q = info.params.front();
        if (!std::isfinite(v)) note("sizes", "self-test size of " + name + "." + q.name + " = " + std::to_string(v) + " is not finite");
    }
    for (const auto& [key, v] : shape) {
        const size_t dot = key.find('.');
        EffectInfo info;
        if (dot == std::string::npos || !findEffect(key.substr(0, dot), info)) {
            note("shape", "self-test parameter '" + key + "': expected EFFECT.PARAMETER with a catalogue effect");
            continue;
        }
        const std::string param = key.substr(dot + 1);
        const auto q = std::find_if(info.params.begin(), info.params.end(), [&](const EffectParam& e) { return e.name == param; });
        if (q == info.params.end()) {
            std::string names;
            for (size_t i = 1; i < info.params.size(); ++i) names += (i > 1 ? ", " : "") + info.params[i].name;
            note("shape", "self-test parameter '" + key + "': " + info.name + " has no parameter '" + param + "'" +
                              (names.empty() ? " (it has only its size parameter)" : " (its other parameters: " + names + ")"));
        } else if (q == info.params.begin()) {
            note("shape", "self-test parameter '" + key + "' is the size parameter: state it as " + info.name + "=VALUE");
        } else if (!std::isfinite(v)) {
            note("shape", "self-test parameter " + key + " = " + std::to_string(v) + " is not finite");
        }
    }
    return out;
}

bool SelfTestOptions::parseStated(const std::vector<std::string>& items, std::string& error) {
    for (const std::string& item : items) {
        const size_t eq = item.find('=');
        const std::string txt = eq == std::string::npos ? std::string() : item.substr(eq + 1);
        char* end = nullptr;
        const double v = txt.empty() ? 0.0 : std::strtod(txt.c_str(), &end);
        if (eq == std::string::npos || eq == 0 || txt.empty() || end == txt.c_str() || *end != '\0') {
            error = "'" + item + "': expected EFFECT=VALUE, e.g. backlash=1e-4 (the effect's size parameter in SI units), "
                    "or EFFECT.PARAMETER=VALUE for another of its parameters, e.g. stick_healing.tc_s=0.002";
            return false;
        }
        const std::string key = item.substr(0, eq);
        if (key.find('.') != std::string::npos) shape[key] = v;
        else sizes[key] = v;
    }
    return true;
}

}  // namespace stickslip::identify
