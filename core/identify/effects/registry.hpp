// The catalogue of missing-effect candidates: the ONE place effects are registered.
// Adding an effect = its own file (value type + info()) + one field of EffectSet below +
// one entry in registry.cpp.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "backlash.hpp"
#include "direction_asymmetry.hpp"
#include "effect.hpp"
#include "frictional_lag.hpp"
#include "normal_load_mu.hpp"
#include "presliding_compliance.hpp"
#include "sensor_inertia.hpp"
#include "stick_healing.hpp"
#include "viscous_damping.hpp"
#include "wear_drift.hpp"

namespace stickslip::identify {

// A composition of effects: each is either off (empty) or on with its parameters.
struct EffectSet {
    std::optional<FrictionalLag> frictionalLag;
    std::optional<NormalLoadMu> normalLoadMu;
    std::optional<DirectionAsymmetry> directionAsymmetry;
    std::optional<WearDrift> wearDrift;
    std::optional<StickHealing> stickHealing;
    std::optional<Backlash> backlash;
    std::optional<PreslidingCompliance> preslidingCompliance;
    std::optional<ViscousDamping> viscousDamping;
    std::optional<SensorInertia> sensorInertia;

    std::vector<std::string> names() const;  // catalogue names of the effects switched on
};

// Every registered effect's description, in catalogue order.
std::vector<EffectInfo> effectCatalogue();
// The description of one effect; false if the name is not in the catalogue.
bool findEffect(const std::string& name, EffectInfo& out);

// Switch an effect on with parameter values in the order of its EffectInfo::params.
// Returns false with a message for an unknown name or a wrong number of values.
bool setEffect(EffectSet& set, const std::string& name, const std::vector<double>& values,
               std::string* error = nullptr);
// Switch an effect off (no-op when it is off).
void clearEffect(EffectSet& set, const std::string& name);
// The parameter values of an effect that is on (in EffectInfo::params order); false if off.
bool getEffect(const EffectSet& set, const std::string& name, std::vector<double>& values);

}  // namespace stickslip::identify
