// Fuzz target: the dataset manifest JSON (core/io/dataset parseManifest). On success every
// setting is a finite number under a known key; on failure the error has a message and,
// for malformed JSON, a line and column inside the text.
#include <cmath>
#include <cstdint>
#include <set>
#include <string>

#include "core/io/dataset.hpp"
#include "fuzz_check.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace stickslip::io;
    const std::string text(reinterpret_cast<const char*>(data), size);
    Manifest m;
    DatasetError err;
    if (!parseManifest(text, "manifest.json", m, err)) {
        FUZZ_CHECK(!err.message.empty(), "error without a message");
        FUZZ_CHECK(err.file == "manifest.json", "error names '%s'", err.file.c_str());
        FUZZ_CHECK(err.line >= 0 && err.column >= 0, "negative position");
        return 0;
    }
    static const std::set<std::string> keys{"k", "A", "f", "tN", "m", "c", "phase"};
    for (const auto& [k, v] : m.common) {
        FUZZ_CHECK(keys.count(k) == 1, "unknown common key '%s'", k.c_str());
        FUZZ_CHECK(std::isfinite(v), "common %s is not finite", k.c_str());
    }
    for (const auto& [file, settings] : m.runs) {
        FUZZ_CHECK(file.find('/') == std::string::npos, "run name '%s' keeps a folder", file.c_str());
        for (const auto& [k, v] : settings) {
            FUZZ_CHECK(keys.count(k) == 1, "unknown key '%s'", k.c_str());
            FUZZ_CHECK(std::isfinite(v), "%s: %s is not finite", file.c_str(), k.c_str());
        }
    }
    return 0;
}
