// Export of a QwtPlot as an image/document (PNG, SVG, PDF chosen by extension, rendered with
// QwtPlotRenderer) and of the plotted data as CSV. Every file is written atomically
// (QSaveFile: a temp file renamed over the target on commit); on failure the target is left
// as it was and `error` says why.
#pragma once

#include <QSize>
#include <vector>
#include <QString>

class QwtPlot;

namespace stickslip::widgets {

struct ExportOptions {
    QSizeF size_mm{160.0, 100.0};   // document size [mm]
    int resolution_dpi = 110;       // raster resolution for PNG [dots per inch]
};

// .png, .svg or .pdf (case-insensitive); anything else is an error.
bool exportPlot(const QwtPlot* plot, const QString& path, QString* error = nullptr,
                const ExportOptions& options = {});

// Several plots in one document, laid out row by row in `columns` columns (a multi-panel
// figure like the paper's); size_mm is the size of the whole page.
bool exportPlots(const std::vector<const QwtPlot*>& plots, int columns, const QString& path,
                 QString* error = nullptr, const ExportOptions& options = {});

// CSV of every curve (and spectrogram grid) attached to the plot, in display units:
//   # <plot title>
//   series,<x axis title>,<y axis title>
//   <curve title>,x,y
// (spectrograms: series,x,y,value rows). Values printed with 17 significant digits.
bool exportCsv(const QwtPlot* plot, const QString& path, QString* error = nullptr);

}  // namespace stickslip::widgets
