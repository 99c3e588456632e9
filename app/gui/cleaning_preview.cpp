#include "cleaning_preview.hpp"

namespace stickslip::gui {

CleaningPreview computeCleaningPreview(const QString& file, const io::DatasetOptions& options,
                                       const identify::PreprocessSettings& settings) {
    CleaningPreview out;
    out.file = file;
    io::DatasetOptions one = options;
    one.runSets.clear();
    io::Dataset ds;
    io::DatasetError err;
    if (!io::loadDataset({file.toStdString()}, one, ds, err)) {
        out.error = QString::fromStdString(err.what());
        return out;
    }
    for (const std::string& spec : options.runSets) {  // those naming other files do not apply
        std::string ignored;
        io::applyRunSet(ds, spec, &ignored);
    }
    out.raw = std::move(ds.runs.front());
    std::string why;
    if (!identify::preprocessRun(out.raw, settings, out.clean, &why)) {
        out.error = QString::fromStdString(why);
        return out;
    }
    out.ok = true;
    return out;
}

}  // namespace stickslip::gui
