// Poincaré section (paper Figs 12, 13, 22, 23): one point per forcing period, relative
// velocity V [m/s] versus slider displacement x [mm], drawn as dots.
#pragma once

#include <vector>

#include "core/analysis/poincare.hpp"
#include "plot_widget.hpp"

namespace stickslip::widgets {

class PoincarePlot : public PlotWidget {
    Q_OBJECT
public:
    explicit PoincarePlot(QWidget* parent = nullptr);
    // Curve "<model>: section"; the two vectors have equal length (SI).
    void setSection(const std::vector<double>& slider_m, const std::vector<double>& relVel_mps,
                    LawKind law = LawKind::RateState);
    void setSection(const PoincareSection& section, LawKind law = LawKind::RateState) {
        setSection(section.slider_m, section.relVel_mps, law);
    }
    // The extent of the orbit the section cuts (its range of x [m] and V [m/s] over the run):
    // the axes show at least 1 % of it, so section points closer than that read as one point.
    // The integrator's own scatter (the tolerance's order times the orbit) would otherwise be
    // autoscaled into a cloud, and a periodic motion would look irregular. 0: no minimum.
    void setOrbitExtent(double slider_m, double relVel_mps);
};

}  // namespace stickslip::widgets
