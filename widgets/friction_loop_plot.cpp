#include "friction_loop_plot.hpp"

#include <qwt_legend_data.h>
#include <qwt_plot.h>
#include <qwt_plot_curve.h>
#include <qwt_plot_textlabel.h>

#include <algorithm>
#include <cmath>

#include "core/analysis/loop_orientation.hpp"
#include "plot_style.hpp"

namespace stickslip::widgets {

FrictionLoopPlot::FrictionLoopPlot(QWidget* parent) : PlotWidget(parent) {
    plot_->setTitle(QStringLiteral("Friction loop"));
    setAxisTitles(QStringLiteral("relative velocity V [m/s]"), QStringLiteral("F/t_N [-]"));
    setFactors(1.0, 1.0);
    summary_ = new QwtPlotTextLabel;
    summary_->setZ(50);
    summary_->attach(plot_);
    updateSummary();
}

void FrictionLoopPlot::setRun(const RunResult& run, double period_s, LawKind law) {
    const int slot = style::slot(law);
    removeCurvesWithPrefix(modelLabel(law) + QLatin1Char(':'));
    marks_[slot].clear();
    const auto& samples = run.samples;
    if (!samples.empty() && period_s > 0) {
        std::vector<double> t, v, rho;
        t.reserve(samples.size());
        v.reserve(samples.size());
        rho.reserve(samples.size());
        for (const Sample& s : samples) {
            t.push_back(s.t_s);
            v.push_back(s.relVel_mps);
            rho.push_back(s.ratio);
        }
        const LoopOrientation lo = frictionLoopOrientation(t, v, rho, period_s);
        const double t0 = samples.front().t_s;
        size_t i = 0;
        for (size_t k = 0; k < lo.signedArea.size(); ++k) {
            LoopMark m;
            m.cycle = static_cast<int>(k);
            m.t0_s = lo.cycleStart_s[k];
            m.t1_s = m.t0_s + period_s;
            m.signedArea = lo.signedArea[k];
            // Same degeneracy rule as the core: |area| ≤ 1e-3 × the loop's bounding box.
            QVector<QPointF> pts;
            double vmin = INFINITY, vmax = -INFINITY, rmin = INFINITY, rmax = -INFINITY;
            while (i < samples.size() && samples[i].t_s < m.t0_s - 1e-12) ++i;
            size_t j = i;
            for (; j < samples.size() && samples[j].t_s <= m.t1_s + 1e-12; ++j) {
                pts.append(QPointF(samples[j].relVel_mps, samples[j].ratio));
                vmin = std::min(vmin, samples[j].relVel_mps);
                vmax = std::max(vmax, samples[j].relVel_mps);
                rmin = std::min(rmin, samples[j].ratio);
                rmax = std::max(rmax, samples[j].ratio);
            }
            const double box = (vmax - vmin) * (rmax - rmin);
            m.orientation = std::abs(m.signedArea) <= 1e-3 * box ? 0 : (m.signedArea < 0 ? -1 : +1);
            marks_[slot].push_back(m);
            const QString kind = m.orientation < 0 ? QStringLiteral("cw")
                                                   : (m.orientation > 0 ? QStringLiteral("ccw") : QStringLiteral("flat"));
            const QColor color = m.orientation < 0 ? style::clockwise()
                                                   : (m.orientation > 0 ? style::counterClockwise() : QColor(120, 120, 120));
            auto* c = addCurve(QStringLiteral("%1: cycle %2 %3").arg(modelLabel(law)).arg(k).arg(kind), law, color);
            c->setSamples(pts);
            c->setItemAttribute(QwtPlotItem::Legend, false);
        }
        // The tail after the last complete cycle (grey).
        const double tTail = t0 + static_cast<double>(lo.signedArea.size()) * period_s;
        QVector<QPointF> tail;
        for (const Sample& s : samples)
            if (s.t_s >= tTail - 1e-12) tail.append(QPointF(s.relVel_mps, s.ratio));
        if (tail.size() > 1) {
            auto* c = addCurve(modelLabel(law) + QStringLiteral(": partial"), law, QColor(170, 170, 170));
            c->setSamples(tail);
            c->setItemAttribute(QwtPlotItem::Legend, false);
        }
    }
    updateSummary();
    rescale();
}

const std::vector<LoopMark>& FrictionLoopPlot::loopMarks(LawKind law) const { return marks_[style::slot(law)]; }

void FrictionLoopPlot::clearModel(LawKind law) {
    marks_[style::slot(law)].clear();
    updateSummary();
    PlotWidget::clearModel(law);
}

void FrictionLoopPlot::clearAll() {
    marks_[0].clear();
    marks_[1].clear();
    updateSummary();
    PlotWidget::clearAll();
}

// A text box in the canvas corner: per model, how many loops of each orientation, in the
// loops' colours (the loops themselves carry no legend entries).
void FrictionLoopPlot::updateSummary() {
    QStringList lines;
    for (LawKind law : {LawKind::RateState, LawKind::Coulomb}) {
        const auto& m = marks_[style::slot(law)];
        if (m.empty()) continue;
        const auto cw = std::count_if(m.begin(), m.end(), [](const LoopMark& x) { return x.orientation < 0; });
        const auto ccw = std::count_if(m.begin(), m.end(), [](const LoopMark& x) { return x.orientation > 0; });
        const auto flat = static_cast<long>(m.size()) - cw - ccw;
        QString line = QStringLiteral("%1%2: <span style='color:%3'>%4 clockwise</span>, "
                                      "<span style='color:%5'>%6 counter-clockwise</span>")
                           .arg(modelLabel(law), law == LawKind::Coulomb ? QStringLiteral(" (dashed)") : QString())
                           .arg(style::clockwise().name())
                           .arg(cw)
                           .arg(style::counterClockwise().name())
                           .arg(ccw);
        if (flat > 0) line += QStringLiteral(", %1 flat").arg(flat);
        lines << line;
    }
    QwtText text(lines.isEmpty() ? QString() : lines.join(QStringLiteral("<br>")), QwtText::RichText);
    text.setRenderFlags(Qt::AlignLeft | Qt::AlignTop);
    QFont f = font();
    f.setPointSizeF(f.pointSizeF() * 0.9);
    text.setFont(f);
    text.setBackgroundBrush(QBrush(QColor(255, 255, 255, 210)));
    summary_->setText(text);
}

}  // namespace stickslip::widgets
