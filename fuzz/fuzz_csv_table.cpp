// Fuzz target: the numeric CSV table reader (core/io/csv_table parseCsvTable).
// On success the table is consistent (one name per column, equal column lengths, source
// lines rising) and every cell is finite; on failure the error has a message and a line.
#include <cmath>
#include <cstdint>
#include <string>

#include "core/io/csv_table.hpp"
#include "fuzz_check.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    using namespace stickslip::io;
    const std::string text(reinterpret_cast<const char*>(data), size);
    CsvTable t;
    CsvError err;
    if (!parseCsvTable(text, "fuzz.csv", t, err)) {
        FUZZ_CHECK(!err.message.empty(), "error without a message");
        FUZZ_CHECK(err.line >= 0 && err.column >= 0, "negative position %ld:%ld", err.line, err.column);
        FUZZ_CHECK(err.what().rfind("fuzz.csv", 0) == 0, "error does not name the file: %s", err.what().c_str());
        return 0;
    }
    FUZZ_CHECK(!t.header.empty(), "table without columns");
    FUZZ_CHECK(t.columns.size() == t.header.size(), "%zu columns, %zu names", t.columns.size(), t.header.size());
    FUZZ_CHECK(t.rowLines.size() == t.rows(), "%zu row lines for %zu rows", t.rowLines.size(), t.rows());
    for (size_t j = 0; j < t.columns.size(); ++j) {
        FUZZ_CHECK(t.columns[j].size() == t.rows(), "column %zu has %zu rows, not %zu", j, t.columns[j].size(), t.rows());
        FUZZ_CHECK(t.column(t.header[j]) >= 0, "column '%s' not found by name", t.header[j].c_str());
        for (double v : t.columns[j]) FUZZ_CHECK(std::isfinite(v), "non-finite cell in column %zu", j);
    }
    long prev = t.headerLine;
    for (long l : t.rowLines) {
        FUZZ_CHECK(l > prev, "row line %ld after line %ld", l, prev);
        prev = l;
    }
    FUZZ_CHECK(t.delimiter == ',' || t.delimiter == ';' || t.delimiter == '\t', "delimiter %d", t.delimiter);
    return 0;
}
