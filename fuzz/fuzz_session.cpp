// Fuzz target: GUI session files (app/gui/session Session::fromJson, the bytes loadSession
// reads). An accepted session has finite parameters, and writing it (toJson) and reading it
// back gives the same session (round trip).
#include <QCoreApplication>
#include <cmath>
#include <cstdint>

#include "core/params.hpp"
#include "fuzz_check.hpp"
#include "session.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace stickslip;
    using namespace stickslip::gui;
    const QByteArray json(reinterpret_cast<const char*>(data), static_cast<int>(size));
    Session s;
    QString why;
    if (!Session::fromJson(json, s, &why)) {
        FUZZ_CHECK(!why.isEmpty(), "rejected without a message");
        return 0;
    }
    for (const auto& key : paramKeys()) {
        double v = 0;
        FUZZ_CHECK(getParam(s.settings.params, key, v), "no value for %s", key.c_str());
        FUZZ_CHECK(std::isfinite(v), "%s is not finite", key.c_str());
    }
    FUZZ_CHECK(std::isfinite(s.settings.params.lawParams<CoulombParams>().mu) && std::isfinite(s.settings.params.lawParams<CoulombParams>().epsT_N_per_m),
               "Coulomb mu/epsT not finite");
    const QByteArray written = s.toJson();
    Session back;
    FUZZ_CHECK(Session::fromJson(written, back, &why), "written session does not load: %s", qPrintable(why));
    FUZZ_CHECK(back.toJson() == written, "session changes on a second write:\n%s\n---\n%s", written.constData(),
               back.toJson().constData());
    return 0;
}
