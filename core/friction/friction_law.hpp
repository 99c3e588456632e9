// The registry of friction laws: one alternative per law. Adding a law is one new file
// (a value type with returnMap, slipFunction, steadyStateRatio, epsT) and one entry here.
#pragma once

#include <variant>

#include "../params.hpp"
#include "coulomb.hpp"
#include "rate_state.hpp"

namespace stickslip {

using FrictionLaw = std::variant<RateStateLaw, CoulombLaw>;

// The law selected by p.law with its parameters.
FrictionLaw makeLaw(const SimParams& p);

inline ReturnMapResult returnMap(const FrictionLaw& law, const LawState& s, double dg, double dt, double tN) {
    return std::visit([&](const auto& l) { return l.returnMap(s, dg, dt, tN); }, law);
}
inline double steadyStateRatio(const FrictionLaw& law, double v) {
    return std::visit([&](const auto& l) { return l.steadyStateRatio(v); }, law);
}

}  // namespace stickslip
