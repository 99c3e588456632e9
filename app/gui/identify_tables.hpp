// Formatting and table helpers shared by the Identify panel's tabs, so that every tab shows
// estimates, errors and parameter names the same way.
#pragma once

#include <QColor>
#include <QString>
#include <QStringList>
#include <string>

#include "identify_worker.hpp"

class QTableWidget;
class QWidget;

namespace stickslip::gui {

// "0.3012 ± 0.0021" (4 significant digits; "± n/a" when the standard error is not finite,
// no "±" when it is 0, i.e. the parameter was fixed).
QString formatEstimate(double value, double stderr_);
// A dimensionless error as shown in the tables ("0.1608"; "–" when not finite).
QString formatNrmse(double v);

// The sentence the Identify tab shows for a baseline parameter that ended on a bound: where the
// second start ended it, the verdict (the data's answer, or a solver failure refitted), and
// where a baseline adopted later (a restart, the backward check) has it, if it left the bound.
QString boundSentence(const identify::BoundVerdict& b);

// "η [s/m]" for "eta"; the name itself when unknown.
QString paramTitle(const std::string& n);
QString lawName(LawKind law);

// A read-only table with these headers and no row numbers.
QTableWidget* makeTable(const QStringList& headers, QWidget* parent);
// Text cell (right-aligned except in the first column).
void setCell(QTableWidget* t, int row, int col, const QString& text, const QString& tip = {});
// Height that shows the rows without a scroll bar (tables sit in a scrolling column).
void fitHeight(QTableWidget* t, int minRows = 2);
// A vertically scrolling frame around a tab's content.
QWidget* scrolled(QWidget* content);

// Curve colours, the same in every plot.
inline const QColor kMeasured(40, 40, 40), kRate(31, 119, 180), kCoulomb(255, 127, 14), kBefore(214, 39, 40),
    kAfter(44, 160, 44);
// A law's colour in the Identify plots (its registry slot; rate-state kRate, Coulomb kCoulomb).
QColor lawColor(LawKind law);

}  // namespace stickslip::gui
