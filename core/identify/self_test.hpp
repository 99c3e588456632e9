// The recovery self-test of the missing-effect loop (issue 14, item 4): how often would the loop
// find each catalogue effect, at a stated size, in data like the user's, and how often does it
// name an effect when there is none?
//
// Replicas of the user's runs are made from the fitted baseline: the baseline's prediction, plus
// one catalogue effect at a stated size (simulated exactly: the extended model run over every
// run), plus noise with the level and colour of the baseline's residual (AR(1) per run and
// channel, as the noise null of noise_null.hpp). On each replica the selection's first two tests
// are applied to every candidate in the linearised refit around the baseline (the candidate's
// Jacobian columns, the baseline's refitted too): (1a) ΔBIC below −bicMargin with the loop's n_eff,
// (1b) the gain beyond the (1 − nullAlpha) quantile of the noise null. The candidate with the
// lowest ΔBIC among those that pass is the loop's pick. Per effect the table counts how often the
// pick is the injected effect (detected), another effect (confused) or none (missed); replicas
// without any effect count false alarms. The held-out and size tests (2, 3) need K refits per
// replica and are not part of it, so its detection rates are upper bounds for the full loop's,
// and its false-alarm rate on pure noise is a lower bound.
//
// Sizes: stated per effect (SelfTestOptions::sizes, in the size parameter's unit), or found for a
// signal level: the size whose injected signal has RMS = level × the baseline residual's RMS over
// the compared samples (bisection between the vanishing value and the physical bound). The
// effect's other parameters are injected at their starts, or as stated (SelfTestOptions::shape).
#pragma once

#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "../param_table.hpp"

namespace stickslip::identify {

struct SelfTestOptions {
    int replicas = 0;                       // noise replicas per effect and level (0: no self-test)
    std::vector<double> levels = {0.5};     // injected signal RMS / baseline residual RMS
    std::map<std::string, double> sizes;    // effect -> stated value of its size parameter (replaces the levels)
    // "effect.param" -> the value of one of its other parameters in the injection (default: the
    // effect's start), e.g. stick_healing.tc_s: an effect stated in full, as an answer key gives it.
    std::map<std::string, double> shape;
    // Every problem, each naming the field, the value and the allowed range; empty when valid.
    ParamIssues validate() const;
    // Reads stated injections into `sizes` (EFFECT=VALUE, the size parameter in SI units) and
    // `shape` (EFFECT.PARAMETER=VALUE), as the CLI's --self-test-size and the app's field give
    // them. False, with `error` naming the item, at the first item that is not of that form;
    // whether the names and values are allowed is validate()'s to say.
    bool parseStated(const std::vector<std::string>& items, std::string& error);
};

struct SelfTestRow {
    std::string effect, sizeParam, unit;
    double level = -1;        // requested signal level (−1: the size was stated)
    double size = 0;          // injected value of the size parameter
    double signalRms = 0;     // RMS of the injected signal over the compared samples (residual units)
    double snr = 0;           // signalRms / baseline residual RMS
    double visibleSnr = 0;    // the same for the part of the signal the baseline's (linearised) refit cannot mimic
    int replicas = 0, detected = 0, confused = 0, missed = 0;
    std::map<std::string, int> confusedWith;  // the effect picked instead, how often
    std::map<std::string, double> shape;      // the effect's other parameters as injected (SelfTestOptions::shape)
    std::string note;         // e.g. the level was not reached within the physical bounds
};

struct SelfTestResult {
    bool ran = false;          // requested (SelfTestOptions::replicas > 0)
    bool ok = false;
    std::string message;       // why it did not run to the end
    double noiseRms = 0;       // RMS of the baseline residual over the compared samples
    double numericsRms = -1;   // RMS of its numerical part, which every replica carries (−1: not used)
    double neff = 0;           // n_eff of the BIC
    int nullReplicas = 0;
    int falseAlarmReplicas = 0, falseAlarms = 0;     // replicas without an effect, and how many picked one
    std::map<std::string, int> falseAlarmsBy;        // effect picked on them, how often
    std::vector<SelfTestRow> rows;
    double wallTime_s = 0;
};

nlohmann::json toJson(const SelfTestResult& r);

}  // namespace stickslip::identify
