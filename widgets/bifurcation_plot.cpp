#include "bifurcation_plot.hpp"

#include <qwt_plot.h>
#include <qwt_plot_curve.h>
#include <qwt_symbol.h>

#include <QTimer>

#include "plot_style.hpp"

namespace stickslip::widgets {

namespace {

QString branchName(SweepBranch b) { return b == SweepBranch::Up ? QStringLiteral("up") : QStringLiteral("down"); }

// Growable sample store for incremental appends.
class GrowingData : public QwtArraySeriesData<QPointF> {
public:
    void append(const QPointF& p) { d_samples.append(p); }
    QRectF boundingRect() const override {
        if (d_boundingRect.width() < 0.0) d_boundingRect = qwtBoundingRect(*this);
        return d_boundingRect;
    }
    void invalidate() { d_boundingRect = QRectF(0.0, 0.0, -1.0, -1.0); }
};

}  // namespace

BifurcationPlot::BifurcationPlot(QWidget* parent) : PlotWidget(parent) {
    plot_->setTitle(QStringLiteral("Bifurcation diagram"));
    setAxes(QStringLiteral("stage amplitude A [mm]"), 1.0e3, QStringLiteral("slider displacement x [mm]"), 1.0e3);
}

void BifurcationPlot::setAxes(const QString& paramTitle, double paramFactor, const QString& valueTitle,
                              double valueFactor) {
    setAxisTitles(paramTitle, valueTitle);
    setFactors(paramFactor, valueFactor);
    plot_->replot();
}

void BifurcationPlot::appendColumn(SweepBranch branch, double paramValue, const std::vector<double>& values,
                                   LawKind law) {
    const QString title = modelLabel(law) + QStringLiteral(": ") + branchName(branch);
    QwtPlotCurve* c = curve(title);
    if (!c) {
        // Up drawn first, down on top with smaller open markers so both stay visible.
        // Per law slot a pair of branch colours (up, down); the rate-state law's are the defaults.
        static const QColor up[] = {style::branchUp(), QColor(44, 160, 44), QColor(148, 103, 189)};
        static const QColor down[] = {style::branchDown(), QColor(255, 127, 14), QColor(140, 86, 75)};
        const int k = style::slot(law) % 3;
        const QColor col = branch == SweepBranch::Up ? up[k] : down[k];
        c = addCurve(title, QPen(col));
        c->setStyle(QwtPlotCurve::NoCurve);
        c->setPaintAttribute(QwtPlotCurve::FilterPoints, false);
        if (branch == SweepBranch::Up)
            c->setSymbol(new QwtSymbol(QwtSymbol::Ellipse, QBrush(col), QPen(col), QSize(3, 3)));
        else
            c->setSymbol(new QwtSymbol(QwtSymbol::XCross, QBrush(), QPen(col, 1.0), QSize(5, 5)));
        c->setZ(branch == SweepBranch::Up ? 20 : 21);
        c->setData(new GrowingData);
        c->setLegendIconSize(QSize(8, 8));
    }
    auto* data = static_cast<GrowingData*>(c->data());
    for (double v : values) data->append(QPointF(paramValue * xFactor_, v * yFactor_));
    data->invalidate();
    scheduleReplot();
}

void BifurcationPlot::scheduleReplot() {
    if (replotPending_) return;
    replotPending_ = true;
    QTimer::singleShot(50, this, [this] {
        replotPending_ = false;
        rescale();
    });
}

int BifurcationPlot::pointCount() const {
    int n = 0;
    for (auto* c : curves()) n += static_cast<int>(c->dataSize());
    return n;
}

void BifurcationPlot::clearAll() { PlotWidget::clearAll(); }
void BifurcationPlot::clearModel(LawKind law) { PlotWidget::clearModel(law); }

}  // namespace stickslip::widgets
