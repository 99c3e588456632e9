#include "periodicity_map_plot.hpp"

#include <qwt_color_map.h>
#include <qwt_legend.h>
#include <qwt_matrix_raster_data.h>
#include <qwt_plot.h>
#include <qwt_plot_spectrogram.h>
#include <qwt_plot_textlabel.h>
#include <qwt_plot_grid.h>
#include <qwt_plot_zoomer.h>

#include <cmath>

namespace stickslip::widgets {

namespace {

// Discrete colours per class code (the spectrogram value is the code itself).
class ClassColorMap : public QwtColorMap {
public:
    ClassColorMap() : QwtColorMap(QwtColorMap::RGB) {}
    QRgb rgb(const QwtInterval&, double value) const override {
        if (std::isnan(value)) return qRgb(255, 255, 255);
        return PeriodicityMapPlot::classColor(static_cast<int>(std::lround(value))).rgb();
    }
    unsigned char colorIndex(const QwtInterval&, double) const override { return 0; }
};

}  // namespace

PeriodicityGrid gridFromMap(const PeriodicityMap& map) {
    PeriodicityGrid g;
    g.nx = static_cast<int>(map.values1.size());
    g.ny = static_cast<int>(map.values2.size());
    if (g.nx > 0) {
        g.x0 = map.values1.front();
        g.x1 = map.values1.back();
    }
    if (g.ny > 0) {
        g.y0 = map.values2.front();
        g.y1 = map.values2.back();
    }
    g.classes.assign(static_cast<size_t>(g.nx) * static_cast<size_t>(g.ny), kMapMissing);
    for (size_t k = 0; k < g.classes.size() && k < map.motion.size(); ++k) {
        if (k < map.done.size() && !map.done[k]) continue;
        switch (map.motion[k]) {
            case MotionClass::Stick: g.classes[k] = kMapStick; break;
            case MotionClass::Periodic: g.classes[k] = k < map.period.size() ? map.period[k] : kMapIrregular; break;
            case MotionClass::Irregular: g.classes[k] = kMapIrregular; break;
        }
    }
    return g;
}

QColor PeriodicityMapPlot::classColor(int code) {
    if (code == kMapStick) return QColor(190, 190, 190);
    if (code == kMapIrregular) return QColor(214, 39, 40);
    if (code == 1) return QColor(31, 119, 180);
    if (code == 2) return QColor(44, 160, 44);
    if (code == 3) return QColor(188, 189, 34);
    if (code == 4) return QColor(255, 187, 120);
    // Periods 5–16: one hue, light (5) to dark (16). Hues spread over 280°–148° made period 11
    // a light blue that read as period 1 and period 16 a cyan that matched no legend entry.
    if (code >= 5 && code <= 16) return QColor::fromHsl(285, 200, 190 - (code - 5) * 10);
    return QColor(255, 255, 255);  // missing
}

PeriodicityMapPlot::PeriodicityMapPlot(QWidget* parent) : PlotWidget(parent) {
    plot_->setTitle(QStringLiteral("Periodicity map"));
    spectrogram_ = new QwtPlotSpectrogram(QStringLiteral("class"));
    spectrogram_->setRenderThreadCount(1);
    spectrogram_->setColorMap(new ClassColorMap);
    spectrogram_->setItemAttribute(QwtPlotItem::Legend, false);
    spectrogram_->attach(plot_);
    grid_->setZ(spectrogram_->z() + 1);

    // Class legend as coloured text under the title (the spectrogram has no legend entries).
    QStringList parts;
    const std::pair<int, QString> items[] = {{kMapStick, QStringLiteral("stick")},    {1, QStringLiteral("period 1")},
                                             {2, QStringLiteral("2")},                {3, QStringLiteral("3")},
                                             {4, QStringLiteral("4")},                {5, QStringLiteral("5–16 (light to dark)")},
                                             {kMapIrregular, QStringLiteral("irregular")}};
    for (const auto& [code, name] : items) {
        QString swatch = QStringLiteral("<span style='color:%1'>&#9632;</span>").arg(classColor(code).name());
        if (code == 5)  // the range's ends: 5 and 16
            swatch += QStringLiteral("<span style='color:%1'>&#9632;</span>").arg(classColor(16).name());
        parts << swatch + QLatin1Char(' ') + name;
    }
    QwtText footer(parts.join(QStringLiteral("&nbsp;&nbsp;")), QwtText::RichText);
    plot_->setFooter(footer);
    if (plot_->legend()) plot_->insertLegend(nullptr);
}

void PeriodicityMapPlot::setMap(const PeriodicityGrid& grid, const QString& xTitle, double xFactor,
                                const QString& yTitle, double yFactor) {
    map_ = grid;
    setAxisTitles(xTitle, yTitle);
    applyFonts();  // the other views' fonts (rescale() applies them there; the map sets its scales itself)
    setFactors(xFactor, yFactor);
    auto* data = new QwtMatrixRasterData;
    QVector<double> values;
    values.reserve(grid.nx * grid.ny);
    for (int iy = 0; iy < grid.ny; ++iy)
        for (int ix = 0; ix < grid.nx; ++ix) values.append(static_cast<double>(grid.at(ix, iy)));
    data->setValueMatrix(values, grid.nx);
    // Cells are centred on the parameter values: extend half a cell beyond first and last.
    const double hx = grid.nx > 1 ? (grid.x1 - grid.x0) / (grid.nx - 1) / 2 : 0.5 * std::max(std::abs(grid.x0), 1e-12);
    const double hy = grid.ny > 1 ? (grid.y1 - grid.y0) / (grid.ny - 1) / 2 : 0.5 * std::max(std::abs(grid.y0), 1e-12);
    data->setInterval(Qt::XAxis, QwtInterval((grid.x0 - hx) * xFactor, (grid.x1 + hx) * xFactor));
    data->setInterval(Qt::YAxis, QwtInterval((grid.y0 - hy) * yFactor, (grid.y1 + hy) * yFactor));
    data->setInterval(Qt::ZAxis, QwtInterval(-2.0, 16.0));
    data->setResampleMode(QwtMatrixRasterData::NearestNeighbour);
    spectrogram_->setData(data);
    plot_->setAxisScale(QwtPlot::xBottom, (grid.x0 - hx) * xFactor, (grid.x1 + hx) * xFactor);
    plot_->setAxisScale(QwtPlot::yLeft, (grid.y0 - hy) * yFactor, (grid.y1 + hy) * yFactor);
    plot_->replot();
    zoomer_->setZoomBase(false);
}

void PeriodicityMapPlot::clearAll() {
    map_ = PeriodicityGrid{};
    spectrogram_->setData(new QwtMatrixRasterData);
    PlotWidget::clearAll();
}

}  // namespace stickslip::widgets
