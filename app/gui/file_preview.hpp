// What the import dialog knows about one data file without loading it, read off the GUI
// thread by the files page's scan. Plain values (no Qt) so the validators can use them.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "core/io/csv_table.hpp"

namespace stickslip::gui {

// Header, the first rows for the preview, or the error that stops the file from loading.
struct FilePreview {
    std::string path;
    bool ok = false;
    io::CsvError error;                       // when !ok
    std::vector<std::string> header;
    std::vector<std::vector<double>> rows;    // first rows, row-major
    std::vector<long> rowLines;               // source line of each preview row
    std::vector<std::string> comments;
    long headerLine = 0;
    size_t rowCount = 0;
    // Per column: median step (> 0 only if the column increases) and the first data row
    // i >= 1 where it does not increase (0 if none) with the two values, to check a time column.
    std::vector<double> medianStep;
    std::vector<size_t> firstNonIncreasing;
    std::vector<long> firstNonIncreasingLine;
    std::vector<std::pair<double, double>> nonIncreasingValues;
};
// Reads `path` with the core CSV reader and keeps the first `maxRows` rows.
FilePreview readFilePreview(const std::string& path, int maxRows = 50);

}  // namespace stickslip::gui
