// What the parameter panel emits as one value: the parameters of a run and which model(s)
// to show. "Both" runs the rate-state law and the Coulomb law with the same parameters and
// overlays them.
#pragma once

#include <QMetaType>
#include <QString>

#include "core/params.hpp"

namespace stickslip::gui {

// One law alone (its LawKind index; the paper's two are named) or the paper's two overlaid.
enum class ModelChoice : int { Both = -1, RateState = 0, Coulomb = 1 };
// The choice of a law alone.
inline ModelChoice lawChoice(LawKind law) { return static_cast<ModelChoice>(static_cast<int>(law)); }
// Every choice the app offers: each registered law, then Both.
std::vector<ModelChoice> modelChoices();
QString toString(ModelChoice);
bool parseModelChoice(const QString&, ModelChoice&);

struct ModelSettings {
    SimParams params;                         // params.law follows `model` (RateState for Both)
    ModelChoice model = ModelChoice::RateState;
    QString preset;                           // preset the values came from ("" if none)
    // Stepping of the dynamics runs: 0 = the paper's fixed step dt; > 0 = the error-controlled
    // integrator with this relative displacement error target (IntegrationParams::tolerance,
    // 1e-5 … 0.5). The prescribed set-up always steps the measured grid (paramsFor sets 0).
    // The default is error-controlled at kDefaultTolerance (docs/adaptive.md, "The app's default").
    static constexpr double kDefaultTolerance = 1e-4;
    double tolerance = kDefaultTolerance;
    // The laws to run, primary first.
    std::vector<LawKind> laws() const;
    // The law the parameters follow: the choice's law, the rate-state law for Both.
    LawKind primaryLaw() const;
    // params with law = `law` and the stepping above (tolerance only in the dynamics set-up).
    SimParams paramsFor(LawKind law) const;
};

}  // namespace stickslip::gui

Q_DECLARE_METATYPE(stickslip::gui::ModelSettings)
