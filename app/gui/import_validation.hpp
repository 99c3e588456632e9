// The import dialog's checks as pure functions of plain values (no Qt): what keeps OK disabled
// can be read, and tested, apart from the widgets. Messages are worded as the core's loaders
// word theirs (file:line:column first), so the dialog and the command line read alike.
#pragma once

#include <array>
#include <map>
#include <string>
#include <vector>

#include "core/identify/preprocess.hpp"
#include "core/io/dataset.hpp"
#include "core/params.hpp"
#include "file_preview.hpp"

namespace stickslip::gui {

// Per signal (io::Signal order): the chosen column ("" when not mapped), or the unit text.
using SignalTexts = std::array<std::string, io::kSignalCount>;
// File previews by path; a file still being read has none.
using PreviewMap = std::map<std::string, FilePreview>;
using Paths = std::vector<std::string>;

// The header names of all readable files, in first-seen order.
std::vector<std::string> columnUnion(const Paths& files, const PreviewMap& previews);

// The core's mapping for the chosen columns and units: only columns differing from the default
// names and non-SI units; "(none)" where a file has the default column becomes io::kNotMapped.
// The first problem goes to *error when it is given and still empty.
io::ColumnMapping buildMapping(const SignalTexts& columns, const SignalTexts& units,
                               const std::vector<std::string>& fileColumns, std::string* error);
// The factor taking the time column to seconds.
double timeScale(const io::ColumnMapping& m);
// Signals set to "(none)" although the files carry their default column (sorted).
std::vector<io::Signal> unmappedSignals(const SignalTexts& columns, const std::vector<std::string>& fileColumns);

// Files readable, a time column, a valid mapping, mapped columns present, enough rows, time
// increasing. Files still being read are skipped (the dialog waits for them anyway).
std::string validateFilesAndMapping(const Paths& files, const PreviewMap& previews, const SignalTexts& columns,
                                    const SignalTexts& units);
// Every per-run setting ("FILE:KEY=VALUE") applies to one of the files.
std::string validateRunSets(const Paths& files, const std::vector<std::string>& specs);
// The cleaning settings at the lowest sampling rate of the files ("" when none is known).
std::string validateCleaning(const Paths& files, const PreviewMap& previews, const std::string& timeColumn,
                             double timeScale, const identify::PreprocessSettings& settings);
// "Automatic" set-up as the command line decides it: dynamics when the first file has the
// slider displacement column.
SetupKind automaticSetup(const Paths& files, const PreviewMap& previews, const std::string& sliderColumn);

// The manifest check; the file (a tiny JSON) is read once per path, not on every keystroke
// elsewhere in the dialog.
class ManifestCheck {
public:
    // "" when `path` is empty or lists a run for every file.
    std::string validate(const std::string& path, const Paths& files);

private:
    std::string readPath_;
    bool ok_ = false;
    io::Manifest data_;
    io::DatasetError error_;
};

}  // namespace stickslip::gui
