#include "plot_widget.hpp"

#include <qwt_legend.h>
#include <qwt_picker_machine.h>
#include <qwt_plot.h>
#include <qwt_plot_canvas.h>
#include <qwt_plot_curve.h>
#include <qwt_plot_grid.h>
#include <qwt_plot_panner.h>
#include <qwt_plot_picker.h>
#include <qwt_plot_zoomer.h>
#include <qwt_scale_widget.h>
#include <qwt_symbol.h>

#include <QFileInfo>
#include <QFontMetrics>
#include <QResizeEvent>
#include <algorithm>
#include <cmath>
#include <QVBoxLayout>

#include "core/friction/friction_law.hpp"
#include "core/io/csv_table.hpp"
#include "decimated_curve.hpp"
#include "plot_export.hpp"
#include "plot_style.hpp"

namespace stickslip::widgets {

bool measuredFromTable(const io::CsvTable& table, const std::string& xColumn, const std::string& yColumn,
                       MeasuredSeries& out, QString* error) {
    const int ix = table.column(xColumn);
    const int iy = table.column(yColumn);
    for (const auto& [name, idx] : {std::pair{xColumn, ix}, std::pair{yColumn, iy}}) {
        if (idx < 0) {
            if (error) {
                *error = QStringLiteral("%1: no column named \"%2\"")
                             .arg(QString::fromStdString(table.path), QString::fromStdString(name));
            }
            return false;
        }
    }
    out.label = QStringLiteral("measured: %1").arg(QString::fromStdString(yColumn));
    out.x = table.columns[static_cast<size_t>(ix)];
    out.y = table.columns[static_cast<size_t>(iy)];
    return true;
}

QString modelLabel(LawKind law) {
    return QString::fromUtf8(lawInfo(law).label);
}

namespace {

// Zoomer whose rubber band is the only thing it draws (the picker does the read-out).
class Zoomer : public QwtPlotZoomer {
public:
    explicit Zoomer(QWidget* canvas) : QwtPlotZoomer(canvas) {
        setTrackerMode(QwtPicker::AlwaysOff);
        setRubberBandPen(QPen(QColor(80, 80, 80), 1, Qt::DashLine));
    }
};

}  // namespace

PlotWidget::PlotWidget(QWidget* parent) : QWidget(parent) {
    plot_ = new QwtPlot(this);
    plot_->setCanvasBackground(Qt::white);
    plot_->setAutoReplot(false);
    if (auto* canvas = qobject_cast<QwtPlotCanvas*>(plot_->canvas())) {
        canvas->setFrameShape(QFrame::Box);
        canvas->setFrameShadow(QFrame::Plain);
        canvas->setLineWidth(1);
        canvas->setPalette(QPalette(Qt::white));
    }
    grid_ = new QwtPlotGrid;
    grid_->setMajorPen(QPen(QColor(220, 220, 220), 0, Qt::DotLine));
    grid_->attach(plot_);

    auto* legend = new QwtLegend;
    plot_->insertLegend(legend, QwtPlot::BottomLegend);

    zoomer_ = new Zoomer(plot_->canvas());
    panner_ = new QwtPlotPanner(plot_->canvas());
    panner_->setMouseButton(Qt::MiddleButton);
    picker_ = new QwtPlotPicker(QwtPlot::xBottom, QwtPlot::yLeft, QwtPicker::CrossRubberBand,
                                QwtPicker::AlwaysOn, plot_->canvas());
    picker_->setStateMachine(new QwtPickerTrackerMachine);
    picker_->setRubberBandPen(QPen(QColor(120, 120, 120), 1, Qt::DotLine));
    picker_->setTrackerPen(QPen(Qt::black));

    auto* layout = new QVBoxLayout(this);
    layout->setContentsMargins(0, 0, 0, 0);
    layout->addWidget(plot_);
}

PlotWidget::~PlotWidget() = default;

void PlotWidget::setAxisTitles(const QString& xTitle, const QString& yTitle) {
    plot_->setAxisTitle(QwtPlot::xBottom, xTitle);
    plot_->setAxisTitle(QwtPlot::yLeft, yTitle);
}

QwtPlotCurve* PlotWidget::addCurve(const QString& title, const QPen& pen, int yAxis) {
    auto* c = new DecimatedCurve(title);
    c->setPen(pen);
    c->setRenderHint(QwtPlotItem::RenderAntialiased, true);
    c->setPaintAttribute(QwtPlotCurve::FilterPoints, true);
    c->setYAxis(yAxis);
    c->attach(plot_);
    return c;
}

QwtPlotCurve* PlotWidget::addCurve(const QString& title, LawKind law, const QColor& color, int yAxis) {
    return addCurve(title, QPen(color, style::kModelLineWidth, style::modelPenStyle(law)), yAxis);
}

QwtPlotCurve* PlotWidget::reuseCurve(const QString& title, const QPen& pen, int yAxis) {
    QwtPlotCurve* c = curve(title);
    if (!c) return addCurve(title, pen, yAxis);
    c->setPen(pen);
    c->setYAxis(yAxis);
    return c;
}

QwtPlotCurve* PlotWidget::reuseCurve(const QString& title, LawKind law, const QColor& color, int yAxis) {
    return reuseCurve(title, QPen(color, style::kModelLineWidth, style::modelPenStyle(law)), yAxis);
}

void PlotWidget::addMeasured(const MeasuredSeries& series) {
    auto* c = addCurve(series.label.isEmpty() ? QStringLiteral("measured") : series.label,
                       QPen(style::measured(), 0.8));
    c->setStyle(QwtPlotCurve::Dots);
    c->setSymbol(new QwtSymbol(QwtSymbol::Ellipse, QBrush(style::measured()), QPen(style::measured()), QSize(3, 3)));
    QVector<QPointF> pts;
    const size_t n = std::min(series.x.size(), series.y.size());
    pts.reserve(static_cast<int>(n));
    for (size_t i = 0; i < n; ++i) pts.append(QPointF(series.x[i] * xFactor_, series.y[i] * yFactor_));
    c->setSamples(pts);
    c->setZ(30);
    rescale();
}

void PlotWidget::removeCurvesWithPrefix(const QString& prefix) {
    const auto items = plot_->itemList(QwtPlotItem::Rtti_PlotCurve);
    for (auto* item : items) {
        if (item->title().text().startsWith(prefix)) {
            item->detach();
            delete item;
        }
    }
}

void PlotWidget::clearMeasured() {
    removeCurvesWithPrefix(QStringLiteral("measured"));
    rescale();
}

void PlotWidget::clearModel(LawKind law) {
    removeCurvesWithPrefix(modelLabel(law) + QLatin1Char(':'));
    rescale();
}

void PlotWidget::clearAll() {
    plot_->detachItems(QwtPlotItem::Rtti_PlotCurve, true);
    rescale();
}

QList<QwtPlotCurve*> PlotWidget::curves() const {
    QList<QwtPlotCurve*> out;
    for (auto* item : plot_->itemList(QwtPlotItem::Rtti_PlotCurve)) out.append(static_cast<QwtPlotCurve*>(item));
    return out;
}

QwtPlotCurve* PlotWidget::curve(const QString& title) const {
    for (auto* c : curves()) {
        if (c->title().text() == title) return c;
    }
    return nullptr;
}

bool PlotWidget::isOnScreen() const { return isVisible() && !visibleRegion().isEmpty(); }

void PlotWidget::updateWhenVisible(std::function<void()> update) {
    if (isOnScreen()) {
        pending_ = nullptr;
        update();
    } else {
        pending_ = std::move(update);
    }
}

void PlotWidget::applyPendingUpdate() {
    if (!pending_) return;
    const std::function<void()> update = std::move(pending_);
    pending_ = nullptr;
    update();
}

void PlotWidget::showEvent(QShowEvent* e) {
    QWidget::showEvent(e);
    applyPendingUpdate();
}

bool PlotWidget::exportTo(const QString& path, QString* error) {
    applyPendingUpdate();
    if (QFileInfo(path).suffix().compare(QLatin1String("csv"), Qt::CaseInsensitive) == 0) {
        return exportCsv(plot_, path, error);
    }
    return exportPlot(plot_, path, error);
}

// Consistent, compact typography: plain axis titles, a bold but modest plot title.
void PlotWidget::applyFonts() {
    QFont base = font();
    base.setPointSizeF(9.0);
    QFont titleFont = base;
    titleFont.setPointSizeF(10.0);
    titleFont.setBold(true);
    for (int axis = 0; axis < QwtPlot::axisCnt; ++axis) {
        plot_->setAxisFont(axis, base);
        QwtText t = plot_->axisTitle(axis);
        t.setFont(base);
        plot_->setAxisTitle(axis, t);
    }
    QwtText title = plot_->title();
    title.setFont(titleFont);
    plot_->setTitle(title);
    if (auto* legend = qobject_cast<QWidget*>(plot_->legend())) legend->setFont(base);
}

// Autoscaling a (numerically) single point gives a range of 1e-10 with unreadable labels:
// widen such an axis to ±1 % of its value. ±0.1 % needed five significant digits per label and
// the labels overlapped in a dock-sized plot. A range under the plot's minimum span
// (setMinimumSpans) is widened to that span.
namespace {
constexpr int kDefaultMajorTicks = 8;          // Qwt's default
constexpr int kDegenerateAxisMajorTicks = 4;   // labels there carry ~5 significant digits
}  // namespace

void PlotWidget::widenDegenerateAxes() {
    QRectF box;
    bool any = false;
    for (auto* c : curves()) {
        if (c->dataSize() == 0 || c->xAxis() != QwtPlot::xBottom || c->yAxis() != QwtPlot::yLeft) continue;
        box = any ? box.united(c->boundingRect()) : c->boundingRect();
        any = true;
    }
    plot_->setAxisMaxMajor(QwtPlot::yLeft, kDefaultMajorTicks);
    degenerateX_ = false;
    if (!any) {
        setXMajorTicks();
        return;
    }
    auto widen = [this](int axis, double lo, double hi, double minSpan) {
        const double centre = 0.5 * (lo + hi);
        const double scale = std::max(std::abs(lo), std::abs(hi));
        const bool single = !(hi - lo > 1e-6 * scale && hi - lo > 1e-300);
        if (!single && !(hi - lo < minSpan)) return;
        double half = 0.5 * minSpan;
        if (single) half = std::max(half, scale > 0 ? 1e-2 * scale : 1.0);
        plot_->setAxisScale(axis, centre - half, centre + half);
        if (axis == QwtPlot::xBottom) degenerateX_ = true;
        else plot_->setAxisMaxMajor(axis, kDegenerateAxisMajorTicks);
    };
    widen(QwtPlot::xBottom, box.left(), box.right(), minSpan_[0]);
    widen(QwtPlot::yLeft, box.top(), box.bottom(), minSpan_[1]);
    setXMajorTicks();
}

int PlotWidget::xMajorTicks() const {
    const int cap = degenerateX_ ? kDegenerateAxisMajorTicks : kDefaultMajorTicks;
    const QwtScaleWidget* bottom = plot_->axisWidget(QwtPlot::xBottom);
    const QwtScaleWidget* left = plot_->axisWidget(QwtPlot::yLeft);
    const QwtScaleWidget* right = plot_->axisWidget(QwtPlot::yRight);
    // A label and a gap of half its width per interval, over the width the canvas gets.
    const int label = QFontMetrics(bottom->font()).horizontalAdvance(QStringLiteral("-0.000"));
    int span = width() - (left ? left->width() : 0);
    if (right && plot_->axisEnabled(QwtPlot::yRight)) span -= right->width();
    return std::clamp(span / std::max(1, label * 3 / 2), 2, cap);
}

bool PlotWidget::setXMajorTicks() {
    const int n = xMajorTicks();
    if (plot_->axisMaxMajor(QwtPlot::xBottom) == n) return false;
    plot_->setAxisMaxMajor(QwtPlot::xBottom, n);
    return true;
}

// Callers of widenDegenerateAxes replot themselves; a resize alone replots only when the
// number of intervals changed.
void PlotWidget::resizeEvent(QResizeEvent* e) {
    QWidget::resizeEvent(e);
    if (setXMajorTicks()) plot_->replot();
}

void PlotWidget::rescale() {
    applyFonts();
    for (int axis = 0; axis < QwtPlot::axisCnt; ++axis) plot_->setAxisAutoScale(axis, true);
    widenDegenerateAxes();
    plot_->replot();
    zoomer_->setZoomBase(false);
}

}  // namespace stickslip::widgets
