// Fuzz target: a prescribed-slip run CSV (parseCsvTable + slipHistoryFromTable, as
// `stickslip-cli simulate --setup prescribed --input` reads it). On success the history
// passes its own check(): finite, time strictly increasing, columns of equal length.
#include <cmath>
#include <cstdint>
#include <string>

#include "core/io/run_csv.hpp"
#include "fuzz_check.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace stickslip;
    using namespace stickslip::io;
    const std::string text(reinterpret_cast<const char*>(data), size);
    CsvTable t;
    CsvError err;
    if (!parseCsvTable(text, "run.csv", t, err)) return 0;
    SlipHistory h;
    if (!slipHistoryFromTable(t, h, err)) {
        FUZZ_CHECK(!err.message.empty(), "error without a message");
        FUZZ_CHECK(err.file == "run.csv", "error names '%s', not the file", err.file.c_str());
        return 0;
    }
    FUZZ_CHECK(h.validate().empty(), "accepted history fails validate(): %s", formatIssues(h.validate()).c_str());
    FUZZ_CHECK(h.t_s.size() == t.rows(), "%zu samples from %zu rows", h.t_s.size(), t.rows());
    for (size_t i = 0; i < h.t_s.size(); ++i) {
        FUZZ_CHECK(std::isfinite(h.t_s[i]) && std::isfinite(h.slip_m[i]), "non-finite sample %zu", i);
        if (!h.velocity_mps.empty()) FUZZ_CHECK(std::isfinite(h.velocity_mps[i]), "non-finite velocity at %zu", i);
        if (!h.normalForce_N.empty())
            FUZZ_CHECK(std::isfinite(h.normalForce_N[i]) && h.normalForce_N[i] > 0, "normal force at %zu", i);
    }
    return 0;
}
