// A self-contained HTML page of an identify result: tables and inline SVG plots (measured vs
// predicted before and after, residuals, F–V loops, residual spectrum and autocorrelation).
// The SVG is written by hand as text: core has no Qt.
#pragma once

#include <string>
#include <vector>

#include "identify.hpp"

namespace stickslip::identify {

struct SvgSeries {
    std::vector<double> x, y;  // NaN y breaks the line
    std::string color;
    std::string label;
};

// One line plot (axes, ticks, legend) as an <svg> element.
std::string svgLinePlot(const std::vector<SvgSeries>& series, const std::string& title, const std::string& xLabel,
                        const std::string& yLabel, int width = 640, int height = 300);
// Escapes & < > " for HTML text.
std::string htmlEscape(const std::string& s);
// The page.
std::string renderHtmlReport(const IdentifyResult& r);

}  // namespace stickslip::identify
