// Friction laws as one variant over RegisteredLaws (law_list.hpp), the law of a SimParams,
// and the run-time registry (key, label, parameter keys) that I/O, analyses, fit, GUI and
// CLI read instead of branching on the law.
#pragma once

#include <string>
#include <variant>
#include <vector>

#include "../params.hpp"
#include "law_list.hpp"

namespace stickslip {

using FrictionLaw = RegisteredLaws::Variant;

// The law selected by p.law with its parameters.
FrictionLaw makeLaw(const SimParams& p);

struct LawInfo {
    LawKind kind;
    const char* key;                  // "rate-state": --model, run files, sessions
    const char* label;                // "rate-state": legends and reports
    bool viscous;                     // slip rate follows the overstress (no sharp stick/slip switch)
    std::vector<ParamDef> paramRows;  // the law's rows as it declares them (shared keys without metadata)
    std::vector<std::string> keys;    // its parameter keys, in its order
    // The law's own field for `key` in p, or nullptr when the law has no such key.
    double* (*field)(SimParams& p, const std::string& key);
};

// Every registered law, in LawKind order.
const std::vector<LawInfo>& lawRegistry();
// The entry of a kind (the first law for an unknown kind).
const LawInfo& lawInfo(LawKind);
int lawCount();
// Every registered kind, in order.
std::vector<LawKind> allLaws();
// True when `law` has the parameter `key`.
bool lawHasParam(LawKind law, const std::string& key);

// The selected law's friction coefficient μ (static, or at the reference velocity) and
// penalty stiffness ε_T: every law has both keys (checked by tst_params), so analyses that
// scale by μ t_N or need the contact stiffness need not know the law.
double lawMu(const SimParams& p);
double lawEpsT(const SimParams& p);

inline ReturnMapResult returnMap(const FrictionLaw& law, const LawState& s, double dg, double dt, double tN) {
    return std::visit([&](const auto& l) { return l.returnMap(s, dg, dt, tN); }, law);
}
inline double steadyStateRatio(const FrictionLaw& law, double v) {
    return std::visit([&](const auto& l) { return l.steadyStateRatio(v); }, law);
}
// α in steady sliding at |V| (0 for laws without a state variable).
inline double steadyStateAlpha(const FrictionLaw& law, double v) {
    return std::visit(
        [&](const auto& l) {
            if constexpr (requires { l.steadyStateAlpha(v); }) return l.steadyStateAlpha(v);
            else return 0.0;
        },
        law);
}

}  // namespace stickslip
