// A general line plot of named series (measured vs predicted, residuals, diagnostics): each
// series has its own colour and style, the y axis may be logarithmic, and vertical or
// horizontal reference lines can be marked (forcing harmonics, whiteness bounds).
#pragma once

#include <QColor>
#include <vector>

#include "plot_widget.hpp"

class QwtPlotMarker;

namespace stickslip::widgets {

struct PlotSeries {
    QString label;
    std::vector<double> x, y;  // plotted as given (no unit scaling); non-finite y are skipped
    QColor color = QColor(31, 119, 180);
    bool dashed = false;
    bool dots = false;         // markers only (measured data)
    double width = 1.2;
};

class SeriesPlot : public PlotWidget {
    Q_OBJECT
public:
    explicit SeriesPlot(QWidget* parent = nullptr);

    void setTitles(const QString& title, const QString& xTitle, const QString& yTitle);
    void setLogY(bool on);
    bool logY() const { return logY_; }
    // Replaces every series (and keeps the reference lines).
    void setSeries(const std::vector<PlotSeries>& series);
    // Dotted vertical lines at x (e.g. the forcing harmonics), replacing earlier ones.
    void setVerticalLines(const std::vector<double>& x, const QColor& color = QColor(214, 39, 40));
    // Dashed horizontal lines at y (e.g. ±1.96/√n), replacing earlier ones.
    void setHorizontalLines(const std::vector<double>& y, const QColor& color = QColor(120, 120, 120));
    void clearAll() override;

    int seriesCount() const;
    int verticalLineCount() const { return static_cast<int>(vlines_.size()); }

private:
    void clearLines(std::vector<QwtPlotMarker*>& lines);
    bool logY_ = false;
    std::vector<QwtPlotMarker*> vlines_, hlines_;
};

}  // namespace stickslip::widgets
