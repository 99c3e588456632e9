#include "friction_law.hpp"

#include <algorithm>

namespace stickslip {

namespace {

template <class Law>
LawInfo infoOf() {
    LawInfo i{lawKindOf<Law>(), Law::kKey, Law::kLabel, Law::kViscous, Law::paramRows(), {},
              [](SimParams& p, const std::string& key) { return Law::field(p.lawParams<typename Law::Params>(), key); }};
    for (const ParamDef& d : i.paramRows) i.keys.emplace_back(d.key);
    return i;
}

template <class... L>
std::vector<LawInfo> registryOf(LawList<L...>) {
    return {infoOf<L>()...};
}

template <class... L>
FrictionLaw makeOf(const SimParams& p, LawList<L...>) {
    FrictionLaw law;
    const int k = static_cast<int>(p.law);
    ((lawIndex<L>(RegisteredLaws{}) == k ? (void)(law = L{p.lawParams<typename L::Params>()}) : (void)0), ...);
    return law;
}

}  // namespace

FrictionLaw makeLaw(const SimParams& p) { return makeOf(p, RegisteredLaws{}); }

const std::vector<LawInfo>& lawRegistry() {
    static const std::vector<LawInfo> r = registryOf(RegisteredLaws{});
    return r;
}

const LawInfo& lawInfo(LawKind k) {
    const auto& r = lawRegistry();
    const int i = static_cast<int>(k);
    return i >= 0 && i < static_cast<int>(r.size()) ? r[static_cast<size_t>(i)] : r.front();
}

double lawMu(const SimParams& p) {
    double v = 0;
    getParam(p, "mu", v);
    return v;
}
double lawEpsT(const SimParams& p) {
    double v = 0;
    getParam(p, "epsT", v);
    return v;
}

int lawCount() { return RegisteredLaws::size; }

std::vector<LawKind> allLaws() {
    std::vector<LawKind> out;
    for (const LawInfo& i : lawRegistry()) out.push_back(i.kind);
    return out;
}

bool lawHasParam(LawKind law, const std::string& key) {
    const auto& keys = lawInfo(law).keys;
    return std::find(keys.begin(), keys.end(), key) != keys.end();
}

}  // namespace stickslip
