// The registration of friction laws. A law is one file (a value type with its Params, key,
// label, parameter rows, return map, slip function and steady state; see rate_state.hpp) and
// one entry in RegisteredLaws below. Its index in the list is its LawKind and its colour slot;
// SimParams keeps one Params of every registered law (SimParams::lawSet).
#pragma once

#include <tuple>
#include <variant>

#include "coulomb.hpp"
#include "dieterich_ruina.hpp"
#include "rate_state.hpp"

namespace stickslip {

template <class... L>
struct LawList {
    using Variant = std::variant<L...>;
    using ParamTuple = std::tuple<typename L::Params...>;
    static constexpr int size = sizeof...(L);
};

using RegisteredLaws = LawList<RateStateLaw, CoulombLaw, DieterichRuinaLaw>;

// The paper's two laws are named; every law (these included) is also its index in RegisteredLaws.
enum class LawKind : int { RateState = 0, Coulomb = 1 };

template <class Law, class... L>
constexpr int lawIndex(LawList<L...>) {
    int i = 0, found = -1;
    ((std::is_same_v<Law, L> ? (found = i, ++i) : ++i), ...);
    return found;
}
template <class Law>
constexpr LawKind lawKindOf() {
    static_assert(lawIndex<Law>(RegisteredLaws{}) >= 0, "not a registered law");
    return static_cast<LawKind>(lawIndex<Law>(RegisteredLaws{}));
}
static_assert(lawKindOf<RateStateLaw>() == LawKind::RateState && lawKindOf<CoulombLaw>() == LawKind::Coulomb);

}  // namespace stickslip
