// The common look of all plots: colours per model, branch and orientation (internal header).
#pragma once

#include <QColor>
#include <QPen>

#include "core/params.hpp"

namespace stickslip::widgets::style {

inline QColor rateState() { return QColor(31, 119, 180); }   // blue
inline QColor coulomb() { return QColor(255, 127, 14); }     // orange
inline QColor measured() { return QColor(30, 30, 30); }
inline QColor clockwise() { return QColor(31, 119, 180); }
inline QColor counterClockwise() { return QColor(214, 39, 40); }
inline QColor branchUp() { return QColor(31, 119, 180); }
inline QColor branchDown() { return QColor(214, 39, 40); }
// A law's colour and pen by its slot (its index in the law registry): the paper's rate-state
// law blue and solid, Coulomb orange and dashed, further laws from the same palette.
inline int slot(LawKind law) { return static_cast<int>(law); }
inline QColor modelColor(LawKind law) {
    static const QColor c[] = {rateState(), coulomb(), QColor(44, 160, 44), QColor(148, 103, 189), QColor(140, 86, 75)};
    return c[slot(law) % 5];
}
inline Qt::PenStyle modelPenStyle(LawKind law) {
    static const Qt::PenStyle s[] = {Qt::SolidLine, Qt::DashLine, Qt::DashDotLine, Qt::DotLine};
    return s[slot(law) % 4];
}

// Width of model curves [px]. Qt strokes antialiased pens of at most 1 px with its fast
// cosmetic stroker; wider pens go through QStroker and a polygon fill, ~20x slower for
// thousands of points (1.3 px cost the Fig. 20 loop view ~15 ms per result; bench_gui_latency).
inline constexpr double kModelLineWidth = 1.0;

// Channel colours for the time series (stage, slider, F/t_N, V, α).
inline QColor channelColor(int index) {
    static const QColor c[] = {QColor(127, 127, 127), QColor(31, 119, 180), QColor(214, 39, 40),
                               QColor(44, 160, 44), QColor(148, 103, 189)};
    return c[index % 5];
}

}  // namespace stickslip::widgets::style
