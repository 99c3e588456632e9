// What the parameter panel emits as one value: the parameters of a run and which model(s)
// to show. "Both" runs the rate-state law and the Coulomb law with the same parameters and
// overlays them.
#pragma once

#include <QMetaType>
#include <QString>

#include "core/params.hpp"

namespace stickslip::gui {

enum class ModelChoice { RateState, Coulomb, Both };
QString toString(ModelChoice);
bool parseModelChoice(const QString&, ModelChoice&);

struct ModelSettings {
    SimParams params;                         // params.law follows `model` (RateState for Both)
    ModelChoice model = ModelChoice::RateState;
    QString preset;                           // preset the values came from ("" if none)
    // The laws to run, primary first.
    std::vector<LawKind> laws() const;
    // params with law = `law`.
    SimParams paramsFor(LawKind law) const;
};

}  // namespace stickslip::gui

Q_DECLARE_METATYPE(stickslip::gui::ModelSettings)
