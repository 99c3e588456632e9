// 2-D periodicity map: class of the motion over a grid of two parameters, drawn as a
// QwtPlotSpectrogram with a discrete class colour map (stick grey, period-1 blue, higher
// periods greens/yellows, irregular red, missing white) and a legend of the classes.
#pragma once

#include <vector>

#include "core/analysis/periodicity_map.hpp"
#include "plot_widget.hpp"

class QwtPlotSpectrogram;

namespace stickslip::widgets {

// Class codes stored in the grid.
constexpr int kMapStick = 0;        // permanent stick
// 1..16: period-n
constexpr int kMapIrregular = -1;   // no period up to 16 (quasi-periodic or chaotic)
constexpr int kMapMissing = -2;     // not computed (cancelled / failed)

struct PeriodicityGrid {
    int nx = 0, ny = 0;               // cells along x and y
    double x0 = 0, x1 = 1;            // first and last x parameter value (cell centres, SI)
    double y0 = 0, y1 = 1;            // first and last y parameter value (cell centres, SI)
    std::vector<int> classes;         // row-major: classes[iy * nx + ix]
    int at(int ix, int iy) const { return classes[static_cast<size_t>(iy) * nx + ix]; }
};

// The core map as class codes (stick 0, period-n n, irregular −1, not computed −2).
PeriodicityGrid gridFromMap(const PeriodicityMap& map);

class PeriodicityMapPlot : public PlotWidget {
    Q_OBJECT
public:
    explicit PeriodicityMapPlot(QWidget* parent = nullptr);
    // Titles with units and display factors (shown = SI * factor).
    void setMap(const PeriodicityGrid& grid, const QString& xTitle, double xFactor, const QString& yTitle,
                double yFactor);
    QwtPlotSpectrogram* spectrogram() const { return spectrogram_; }
    const PeriodicityGrid& grid() const { return map_; }
    void clearAll() override;

    static QColor classColor(int classCode);

private:
    QwtPlotSpectrogram* spectrogram_ = nullptr;
    PeriodicityGrid map_;
};

}  // namespace stickslip::widgets
