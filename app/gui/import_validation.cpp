#include "import_validation.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>

#include "import_signals.hpp"

namespace stickslip::gui {

namespace {

bool contains(const std::vector<std::string>& v, const std::string& s) {
    return std::find(v.begin(), v.end(), s) != v.end();
}

// As QString::number(v, 'g', 6), which the messages used before they were Qt-free.
std::string number6(double v) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.6g", v);
    return buf;
}

std::string joined(const std::vector<std::string>& parts, const char* sep) {
    std::string out;
    for (const std::string& p : parts) out += (out.empty() ? "" : sep) + p;
    return out;
}

// A column chosen explicitly (not the default name) must exist in the file; so must time.
std::string checkColumns(const std::string& path, const FilePreview& p, const SignalTexts& columns) {
    for (const SignalInfo& r : signalRows()) {
        const std::string& col = columns[idx(r.signal)];
        const bool explicitChoice = !col.empty() && col != io::defaultColumn(r.signal);
        if (!explicitChoice && r.signal != io::Signal::Time) continue;
        if (!contains(p.header, col))
            return path + ":" + std::to_string(p.headerLine) + ": no column '" + col + "' for signal " +
                   io::signalKey(r.signal) + " (columns: " + joined(p.header, ", ") + ")";
    }
    return {};
}

std::string checkFile(const std::string& path, const FilePreview& p, const SignalTexts& columns, double scale) {
    if (std::string err = checkColumns(path, p, columns); !err.empty()) return err;
    if (p.rowCount < 8)
        return path + ":" + std::to_string(p.headerLine) + ": too few data rows (" + std::to_string(p.rowCount) +
               "); need at least 8";
    const std::string& time = columns[idx(io::Signal::Time)];
    const auto j = static_cast<size_t>(std::find(p.header.begin(), p.header.end(), time) - p.header.begin());
    if (p.firstNonIncreasing[j] > 0)  // worded as the core's loadRun
        return path + ":" + std::to_string(p.firstNonIncreasingLine[j]) + ":" + std::to_string(j + 1) +
               ": time does not increase (" + std::to_string(p.nonIncreasingValues[j].first * scale) + " s then " +
               std::to_string(p.nonIncreasingValues[j].second * scale) + " s)";
    return {};
}

}  // namespace

std::vector<std::string> columnUnion(const Paths& files, const PreviewMap& previews) {
    std::vector<std::string> cols;
    for (const std::string& f : files) {
        const auto it = previews.find(f);
        if (it == previews.end() || !it->second.ok) continue;
        for (const std::string& h : it->second.header)
            if (!contains(cols, h)) cols.push_back(h);
    }
    return cols;
}

io::ColumnMapping buildMapping(const SignalTexts& columns, const SignalTexts& units,
                               const std::vector<std::string>& fileColumns, std::string* error) {
    io::ColumnMapping m;
    auto fail = [error](const std::string& why) {
        if (error && error->empty()) *error = why;
    };
    for (const SignalInfo& r : signalRows()) {
        const std::string& col = columns[idx(r.signal)];
        const std::string key = io::signalKey(r.signal);
        if (col.empty()) {
            // "(none)" although a file has the default column: do not read it (time must be read).
            if (r.signal != io::Signal::Time && contains(fileColumns, io::defaultColumn(r.signal)))
                m.columns[r.signal] = io::kNotMapped;
        } else if (col != io::defaultColumn(r.signal)) {
            std::string why;
            if (!m.addColumns(key + "=" + col, &why)) fail("Column of " + lowerLabel(r.signal) + ": " + why);
        }
        const std::string& u = units[idx(r.signal)];
        if (u.empty()) {
            fail("Unit of " + lowerLabel(r.signal) + " is empty");
        } else if (u != io::signalUnit(r.signal)) {
            std::string why;
            if (!m.addUnits(key + "=" + u, &why)) fail("Unit of " + lowerLabel(r.signal) + ": " + why);
        }
    }
    return m;
}

double timeScale(const io::ColumnMapping& m) {
    const auto it = m.scaleToSI.find(io::Signal::Time);
    return it == m.scaleToSI.end() ? 1.0 : it->second;
}

std::vector<io::Signal> unmappedSignals(const SignalTexts& columns, const std::vector<std::string>& fileColumns) {
    std::vector<io::Signal> out;
    for (const SignalInfo& r : signalRows())
        if (columns[idx(r.signal)].empty() && contains(fileColumns, io::defaultColumn(r.signal)))
            out.push_back(r.signal);
    std::sort(out.begin(), out.end());
    return out;
}

std::string validateFilesAndMapping(const Paths& files, const PreviewMap& previews, const SignalTexts& columns,
                                    const SignalTexts& units) {
    if (files.empty()) return "Add at least one data file (CSV with a header line of column names).";
    for (const std::string& path : files) {
        const auto it = previews.find(path);
        if (it != previews.end() && !it->second.ok) return it->second.error.what();
    }
    if (columns[idx(io::Signal::Time)].empty()) return "Choose the column that holds time: a time column is required.";
    std::string err;
    const io::ColumnMapping m = buildMapping(columns, units, columnUnion(files, previews), &err);
    if (!err.empty()) return err;
    for (const std::string& path : files) {
        const auto it = previews.find(path);
        if (it == previews.end()) continue;  // still being read
        if (std::string bad = checkFile(path, it->second, columns, timeScale(m)); !bad.empty()) return bad;
    }
    return {};
}

std::string validateRunSets(const Paths& files, const std::vector<std::string>& specs) {
    // applyRunSet checks the file names against runs: give it runs that carry only names.
    io::Dataset names;
    for (const std::string& f : files) {
        io::Run r;
        r.file = f;
        names.runs.push_back(std::move(r));
    }
    for (const std::string& spec : specs) {
        std::string why;
        if (!io::applyRunSet(names, spec, &why)) return "Per-run settings: " + why;
    }
    return {};
}

std::string validateCleaning(const Paths& files, const PreviewMap& previews, const std::string& timeColumn,
                             double scale, const identify::PreprocessSettings& settings) {
    double fsMin = 0.0;
    for (const std::string& f : files) {
        const auto it = previews.find(f);
        if (it == previews.end() || !it->second.ok) continue;
        const auto& h = it->second.header;
        const auto j = static_cast<size_t>(std::find(h.begin(), h.end(), timeColumn) - h.begin());
        if (j >= h.size() || !(it->second.medianStep[j] > 0)) continue;
        const double fs = 1.0 / (it->second.medianStep[j] * scale);
        fsMin = fsMin > 0 ? std::min(fsMin, fs) : fs;
    }
    if (!(fsMin > 0)) return {};
    const ParamIssues bad = settings.validate(fsMin);
    if (bad.empty()) return {};
    std::vector<std::string> lines;
    for (const ParamIssue& i : bad) lines.push_back(i.message());
    return "Cleaning (sampling at " + number6(fsMin) + " Hz): " + joined(lines, "; ");
}

SetupKind automaticSetup(const Paths& files, const PreviewMap& previews, const std::string& sliderColumn) {
    if (files.empty() || sliderColumn.empty()) return SetupKind::Prescribed;
    const auto it = previews.find(files.front());
    if (it == previews.end() || !it->second.ok) return SetupKind::Prescribed;
    return contains(it->second.header, sliderColumn) ? SetupKind::Dynamics : SetupKind::Prescribed;
}

std::string ManifestCheck::validate(const std::string& path, const Paths& files) {
    if (path.empty()) return {};
    if (path != readPath_) {
        readPath_ = path;
        data_ = io::Manifest{};
        error_ = io::DatasetError{};
        ok_ = io::readManifest(path, data_, error_);
    }
    if (!ok_) return "Manifest " + error_.what();
    for (const std::string& f : files) {
        const std::string name = std::filesystem::path(f).filename().string();
        if (!data_.runs.count(name)) return path + ": the manifest lists no run for data file '" + name + "'";
    }
    return {};
}

}  // namespace stickslip::gui
