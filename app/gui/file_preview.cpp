#include "file_preview.hpp"

#include <algorithm>

#include "core/dsp/stats.hpp"

namespace stickslip::gui {

namespace {

// The time check needs, per column, where it first fails to increase, and the sampling
// check its median step: both from the whole file, while only the first rows are kept.
void scanMonotony(const io::CsvTable& t, FilePreview& p) {
    const size_t nc = t.header.size();
    p.medianStep.assign(nc, 0.0);
    p.firstNonIncreasing.assign(nc, 0);
    p.firstNonIncreasingLine.assign(nc, 0);
    p.nonIncreasingValues.assign(nc, {0.0, 0.0});
    for (size_t j = 0; j < nc; ++j) {
        const std::vector<double>& c = t.columns[j];
        for (size_t i = 1; i < c.size(); ++i)
            if (!(c[i] > c[i - 1])) {
                p.firstNonIncreasing[j] = i;
                p.firstNonIncreasingLine[j] = i < t.rowLines.size() ? t.rowLines[i] : 0;
                p.nonIncreasingValues[j] = {c[i - 1], c[i]};
                break;
            }
        if (p.firstNonIncreasing[j] == 0 && c.size() > 1) {
            std::vector<double> d(c.size() - 1);
            for (size_t i = 1; i < c.size(); ++i) d[i - 1] = c[i] - c[i - 1];
            p.medianStep[j] = dsp::median(std::move(d));
        }
    }
}

}  // namespace

FilePreview readFilePreview(const std::string& path, int maxRows) {
    FilePreview p;
    p.path = path;
    io::CsvTable t;
    if (!io::readCsvTable(path, t, p.error)) {
        if (p.error.file.empty()) p.error.file = path;
        return p;
    }
    p.ok = true;
    p.header = t.header;
    p.comments = t.comments;
    p.headerLine = t.headerLine;
    p.rowCount = t.rows();
    const size_t shown = std::min(p.rowCount, static_cast<size_t>(std::max(0, maxRows)));
    p.rows.assign(shown, std::vector<double>(t.header.size()));
    for (size_t i = 0; i < shown; ++i) {
        for (size_t j = 0; j < t.header.size(); ++j) p.rows[i][j] = t.columns[j][i];
        p.rowLines.push_back(i < t.rowLines.size() ? t.rowLines[i] : 0);
    }
    scanMonotony(t, p);
    return p;
}

}  // namespace stickslip::gui
