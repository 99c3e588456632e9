#include "model_settings.hpp"

#include "core/friction/friction_law.hpp"

namespace stickslip::gui {

QString toString(ModelChoice m) {
    if (m == ModelChoice::Both) return QStringLiteral("both");
    return QString::fromUtf8(stickslip::toString(static_cast<LawKind>(static_cast<int>(m))));
}

std::vector<ModelChoice> modelChoices() {
    std::vector<ModelChoice> out;
    for (LawKind law : allLaws()) out.push_back(lawChoice(law));
    out.push_back(ModelChoice::Both);
    return out;
}

bool parseModelChoice(const QString& s, ModelChoice& out) {
    for (ModelChoice m : modelChoices()) {
        if (s == toString(m)) {
            out = m;
            return true;
        }
    }
    return false;
}

LawKind ModelSettings::primaryLaw() const {
    return model == ModelChoice::Both ? LawKind::RateState : static_cast<LawKind>(static_cast<int>(model));
}

std::vector<LawKind> ModelSettings::laws() const {
    if (model == ModelChoice::Both) return {LawKind::RateState, LawKind::Coulomb};
    return {primaryLaw()};
}

SimParams ModelSettings::paramsFor(LawKind law) const {
    SimParams p = params;
    p.law = law;
    p.integration.tolerance = p.setup == SetupKind::Dynamics ? tolerance : 0.0;
    return p;
}

}  // namespace stickslip::gui
