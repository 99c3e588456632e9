#include "model_settings.hpp"

namespace stickslip::gui {

QString toString(ModelChoice m) {
    switch (m) {
    case ModelChoice::RateState: return QStringLiteral("rate-state");
    case ModelChoice::Coulomb: return QStringLiteral("coulomb");
    case ModelChoice::Both: return QStringLiteral("both");
    }
    return {};
}

bool parseModelChoice(const QString& s, ModelChoice& out) {
    for (ModelChoice m : {ModelChoice::RateState, ModelChoice::Coulomb, ModelChoice::Both}) {
        if (s == toString(m)) {
            out = m;
            return true;
        }
    }
    return false;
}

std::vector<LawKind> ModelSettings::laws() const {
    switch (model) {
    case ModelChoice::RateState: return {LawKind::RateState};
    case ModelChoice::Coulomb: return {LawKind::Coulomb};
    case ModelChoice::Both: return {LawKind::RateState, LawKind::Coulomb};
    }
    return {};
}

SimParams ModelSettings::paramsFor(LawKind law) const {
    SimParams p = params;
    p.law = law;
    return p;
}

}  // namespace stickslip::gui
