#include "friction_law.hpp"

namespace stickslip {

FrictionLaw makeLaw(const SimParams& p) {
    if (p.law == LawKind::Coulomb) return CoulombLaw{p.coulomb};
    return RateStateLaw{p.rateState};
}

}  // namespace stickslip
