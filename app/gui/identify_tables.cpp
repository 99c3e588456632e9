#include "identify_tables.hpp"

#include "core/friction/friction_law.hpp"

#include <QCoreApplication>
#include <QHeaderView>
#include <QScrollArea>
#include <QTableWidget>
#include <algorithm>
#include <cmath>
#include <map>

namespace stickslip::gui {

QString formatEstimate(double value, double se) {
    QString s = QString::number(value, 'g', 4);
    if (se == 0.0) return s;
    if (!std::isfinite(se)) return s + QStringLiteral(" ± n/a");
    return s + QStringLiteral(" ± ") + QString::number(se, 'g', 2);
}

QString formatNrmse(double v) { return std::isfinite(v) ? QString::number(v, 'f', 4) : QStringLiteral("–"); }

QString boundSentence(const identify::BoundVerdict& b) {
    const char* text =
        b.solverFailure ? "%1 had stopped on its %2 bound %3: a second start from %4 left it (%5) and ended lower; "
                          "refitted there (a solver failure)."
        : b.leftLater() ? "%1 ended on its %2 bound %3 in the first baseline fit (a second start from %4 ended at %5); a "
                          "later refit of the baseline left it, to %6: a worse minimum, not the data's answer."
        : b.refitted    ? "%1 ended on its %2 bound %3: a second start from %4 ended there too (%5): the data's answer; "
                          "that start was lower elsewhere, and the baseline was refitted there."
                        : "%1 ended on its %2 bound %3: a second start from %4 ended at %5, no lower: the data's answer.";
    QString line = QCoreApplication::translate("IdentifyLoopTab", text)
                       .arg(QString::fromStdString(b.name), QString::fromStdString(b.side))
                       .arg(b.bound, 0, 'g', 4)
                       .arg(b.retryStart, 0, 'g', 4)
                       .arg(b.retryValue, 0, 'g', 4);
    if (!b.leftLater()) return line;
    if (!b.solverFailure) return line.arg(b.leftLaterTo, 0, 'g', 4);
    return line + QCoreApplication::translate("IdentifyLoopTab", " The baseline adopted later has it at %1.")
                      .arg(b.leftLaterTo, 0, 'g', 4);
}

QString paramTitle(const std::string& n) {
    static const std::map<std::string, QString> t = {
        {"mu", "μ"}, {"C1", "C₁"}, {"eta", "η [s/m]"}, {"Dc", "D_c [m]"}, {"vc", "v_c [m/s]"}, {"epsT", "ε_T [N/m]"},
        {"r", "r"}, {"m", "m [kg]"}, {"zeta", "ζ"}, {"c", "c [N s/m]"}, {"k", "k [N/m]"}};
    auto it = t.find(n);
    return it != t.end() ? it->second : QString::fromStdString(n);
}

QString lawName(LawKind law) { return QString::fromUtf8(lawInfo(law).label); }

QColor lawColor(LawKind law) {
    static const QColor c[] = {kRate, kCoulomb, QColor(44, 160, 44), QColor(148, 103, 189)};
    return c[static_cast<int>(law) % 4];
}

QTableWidget* makeTable(const QStringList& headers, QWidget* parent) {
    auto* t = new QTableWidget(0, headers.size(), parent);
    t->setHorizontalHeaderLabels(headers);
    t->verticalHeader()->setVisible(false);
    t->verticalHeader()->setDefaultSectionSize(22);
    t->setEditTriggers(QAbstractItemView::NoEditTriggers);
    t->setSelectionBehavior(QAbstractItemView::SelectRows);
    t->setAlternatingRowColors(true);
    t->horizontalHeader()->setStretchLastSection(true);
    t->horizontalHeader()->setHighlightSections(false);
    t->setWordWrap(false);
    return t;
}

void setCell(QTableWidget* t, int row, int col, const QString& text, const QString& tip) {
    auto* item = new QTableWidgetItem(text);
    if (!tip.isEmpty()) item->setToolTip(tip);
    if (col > 0) item->setTextAlignment(Qt::AlignRight | Qt::AlignVCenter);
    t->setItem(row, col, item);
}

void fitHeight(QTableWidget* t, int minRows) {
    const int rows = std::max(t->rowCount(), minRows);
    int h = t->horizontalHeader()->height() + 2 * t->frameWidth() + 2;
    for (int r = 0; r < t->rowCount(); ++r) h += t->rowHeight(r);
    h += (rows - t->rowCount()) * t->verticalHeader()->defaultSectionSize();
    t->setMinimumHeight(std::min(h, 320));
    t->setMaximumHeight(std::min(h, 320));
}

QWidget* scrolled(QWidget* content) {
    auto* s = new QScrollArea;
    s->setWidget(content);
    s->setWidgetResizable(true);
    s->setFrameShape(QFrame::NoFrame);
    s->setHorizontalScrollBarPolicy(Qt::ScrollBarAlwaysOff);
    return s;
}

}  // namespace stickslip::gui
