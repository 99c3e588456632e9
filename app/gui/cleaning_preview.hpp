// The cleaning page's background job: one run loaded alone and cleaned, for the raw-versus-
// cleaned plot. Value in, value out, so it can run on any thread.
#pragma once

#include <QString>

#include "core/identify/preprocess.hpp"
#include "core/io/dataset.hpp"

namespace stickslip::gui {

// The raw and cleaned version of one run for the comparison plot.
struct CleaningPreview {
    quint64 generation = 0;
    QString file;
    bool ok = false;
    QString error;       // loading or cleaning failed (in words, file:line:column when known)
    io::Run raw;         // loaded with the dialog's mapping and settings
    identify::CleanRun clean;
};
// Loads `file` alone with `options` (run-sets that name other files are ignored) and cleans it.
CleaningPreview computeCleaningPreview(const QString& file, const io::DatasetOptions& options,
                                       const identify::PreprocessSettings& settings);

}  // namespace stickslip::gui
