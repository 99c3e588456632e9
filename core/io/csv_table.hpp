// Numeric CSV tables: reading with positioned errors, and atomic file writing.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace stickslip::io {

// A read or parse error, located in the input (1-based line and column; 0 when unknown).
struct CsvError {
    std::string file;
    long line = 0;
    long column = 0;
    std::string message;
    std::string what() const;  // "file:line:column: message"
};

// A table of numbers with named columns, stored column-major.
struct CsvTable {
    std::string path;
    std::vector<std::string> comments;          // '#' lines, without the '#'
    std::vector<std::string> header;            // column names, trimmed
    std::vector<std::vector<double>> columns;   // columns[j][i]: column j, data row i
    char delimiter = ',';
    long headerLine = 0;                        // 1-based source line of the header
    std::vector<long> rowLines;                 // 1-based source line of each data row
    // 1-based character column where each cell starts, row-major (row i, column j at
    // i * header.size() + j), so that a reader's range check can point at the cell; 32 bits
    // (0 beyond) to add half, not all, of the values' memory.
    std::vector<std::int32_t> cellColumns;
    int column(const std::string& name) const;  // index of the named column, -1 if absent
    long cellColumn(size_t row, size_t col) const;  // 0 when unknown
    size_t rows() const;                        // number of data rows
};

// Delimiter auto-detected (comma, semicolon, tab) from the header line; leading/inline '#'
// comment lines skipped; blank lines skipped; first non-comment line is the header; every
// cell numeric (NaN/Inf/empty -> error). On error returns false, fills err (file, 1-based
// line, 1-based column) and leaves `out` untouched (nothing half-loaded).
bool readCsvTable(const std::string& path, CsvTable& out, CsvError& err);
bool parseCsvTable(const std::string& text, const std::string& nameForErrors, CsvTable& out,
                   CsvError& err);

// Write-then-rename in the same directory; "-" means stdout. Returns false and a message on
// failure (the target is then left as it was).
bool writeFileAtomically(const std::string& path, const std::string& content, std::string* error);

}  // namespace stickslip::io
