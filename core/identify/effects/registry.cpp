#include "registry.hpp"

#include <functional>

namespace stickslip::identify {

namespace {

// One registration: description + how its parameters map into EffectSet.
struct Entry {
    EffectInfo info;
    std::function<void(EffectSet&, const std::vector<double>&)> set;
    std::function<bool(const EffectSet&, std::vector<double>&)> get;
    std::function<void(EffectSet&)> clear;
};

template <class E>
Entry entry(std::optional<E> EffectSet::*field, std::function<E(const std::vector<double>&)> make,
            std::function<std::vector<double>(const E&)> values) {
    return {E::info(), [field, make](EffectSet& s, const std::vector<double>& v) { s.*field = make(v); },
            [field, values](const EffectSet& s, std::vector<double>& out) {
                if (!(s.*field)) return false;
                out = values(*(s.*field));
                return true;
            },
            [field](EffectSet& s) { (s.*field).reset(); }};
}

std::vector<Entry> registry() {
    std::vector<Entry> r;
    r.push_back(entry<FrictionalLag>(&EffectSet::frictionalLag, [](const auto& v) { return FrictionalLag{v[0]}; },
                                     [](const auto& e) { return std::vector<double>{e.tau_s}; }));
    r.push_back(entry<NormalLoadMu>(&EffectSet::normalLoadMu, [](const auto& v) { return NormalLoadMu{v[0]}; },
                                    [](const auto& e) { return std::vector<double>{e.dmu_dtN_per_N}; }));
    r.push_back(entry<DirectionAsymmetry>(&EffectSet::directionAsymmetry,
                                          [](const auto& v) { return DirectionAsymmetry{v[0]}; },
                                          [](const auto& e) { return std::vector<double>{e.mu_pos_minus_mu_neg}; }));
    r.push_back(entry<WearDrift>(&EffectSet::wearDrift, [](const auto& v) { return WearDrift{v[0]}; },
                                 [](const auto& e) { return std::vector<double>{e.dmu_ds_per_m}; }));
    r.push_back(entry<StickHealing>(&EffectSet::stickHealing, [](const auto& v) { return StickHealing{v[0], v[1], v[2]}; },
                                    [](const auto& e) { return std::vector<double>{e.b_heal, e.tc_s, e.Dh_m}; }));
    r.push_back(entry<Backlash>(&EffectSet::backlash, [](const auto& v) { return Backlash{v[0]}; },
                                [](const auto& e) { return std::vector<double>{e.halfWidth_m}; }));
    r.push_back(entry<PreslidingCompliance>(&EffectSet::preslidingCompliance,
                                            [](const auto& v) { return PreslidingCompliance{v[0]}; },
                                            [](const auto& e) { return std::vector<double>{e.kt_N_per_m}; }));
    r.push_back(entry<ViscousDamping>(&EffectSet::viscousDamping, [](const auto& v) { return ViscousDamping{v[0]}; },
                                      [](const auto& e) { return std::vector<double>{e.zeta}; }));
    r.push_back(entry<SensorInertia>(&EffectSet::sensorInertia, [](const auto& v) { return SensorInertia{v[0]}; },
                                     [](const auto& e) { return std::vector<double>{e.mass_kg}; }));
    return r;
}

}  // namespace

std::vector<EffectInfo> effectCatalogue() {
    std::vector<EffectInfo> out;
    for (const Entry& e : registry()) out.push_back(e.info);
    return out;
}

bool findEffect(const std::string& name, EffectInfo& out) {
    for (const Entry& e : registry())
        if (e.info.name == name) { out = e.info; return true; }
    return false;
}

bool setEffect(EffectSet& set, const std::string& name, const std::vector<double>& values, std::string* error) {
    for (const Entry& e : registry()) {
        if (e.info.name != name) continue;
        if (values.size() != e.info.params.size()) {
            if (error) *error = "effect " + name + " takes " + std::to_string(e.info.params.size()) + " parameter(s), got " +
                                std::to_string(values.size());
            return false;
        }
        e.set(set, values);
        return true;
    }
    if (error) *error = "unknown effect '" + name + "'";
    return false;
}

void clearEffect(EffectSet& set, const std::string& name) {
    for (const Entry& e : registry())
        if (e.info.name == name) e.clear(set);
}

bool getEffect(const EffectSet& set, const std::string& name, std::vector<double>& values) {
    for (const Entry& e : registry())
        if (e.info.name == name) return e.get(set, values);
    return false;
}

std::vector<std::string> EffectSet::names() const {
    std::vector<std::string> out;
    for (const Entry& e : registry()) {
        std::vector<double> v;
        if (e.get(*this, v)) out.push_back(e.info.name);
    }
    return out;
}

}  // namespace stickslip::identify
