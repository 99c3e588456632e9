#include "friction_loop_plot.hpp"

#include <qwt_legend_data.h>
#include <qwt_plot.h>
#include <qwt_plot_curve.h>
#include <qwt_plot_textlabel.h>

#include <algorithm>
#include <cmath>

#include "core/analysis/loop_orientation.hpp"
#include "decimated_curve.hpp"
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

void FrictionLoopPlot::setRun(const RunResult& run, LawKind law) {
    const int slot = style::slot(law);
    const QString trajectoryTitle = modelLabel(law) + QStringLiteral(": trajectory");
    // The trajectory curve (the only one with a legend entry) is kept and refilled: removing
    // and attaching it re-lays out the legend.
    QwtPlotCurve* bg = curve(trajectoryTitle);
    const QString prefix = modelLabel(law) + QLatin1Char(':');
    for (QwtPlotCurve* c : curves()) {
        if (c == bg || !c->title().text().startsWith(prefix)) continue;
        c->detach();
        delete c;
    }
    marks_[slot].clear();
    const auto& samples = run.samples;
    if (!samples.empty()) {
        std::vector<double> t, v, rho;
        t.reserve(samples.size());
        v.reserve(samples.size());
        rho.reserve(samples.size());
        QVector<QPointF> all;
        all.reserve(static_cast<int>(samples.size()));
        for (const Sample& s : samples) {
            t.push_back(s.t_s);
            v.push_back(s.relVel_mps);
            rho.push_back(s.ratio);
            all.append(QPointF(s.relVel_mps, s.ratio));
        }
        if (!bg) bg = addCurve(trajectoryTitle, QPen(QColor(190, 190, 190), 0.8, style::modelPenStyle(law)));
        bg->setSamples(all);
        bg->setZ(10);

        const FrictionLoops loops = frictionLoops(t, v, rho);
        const LoopOptions opt;
        size_t i = 0;
        for (size_t k = 0; k < loops.signedArea.size(); ++k) {
            LoopMark m;
            m.index = static_cast<int>(k);
            m.sign = loops.sign[k];
            m.t0_s = loops.start_s[k];
            m.signedArea = loops.signedArea[k];
            // The excursion: from its start while V keeps its sign.
            while (i < samples.size() && samples[i].t_s < m.t0_s) ++i;
            QVector<QPointF> pts;
            double vmin = INFINITY, vmax = -INFINITY, rmin = INFINITY, rmax = -INFINITY;
            size_t j = i;
            for (; j < samples.size() && (samples[j].relVel_mps > 0 ? 1 : (samples[j].relVel_mps < 0 ? -1 : 0)) == m.sign;
                 ++j) {
                pts.append(QPointF(samples[j].relVel_mps, samples[j].ratio));
                vmin = std::min(vmin, samples[j].relVel_mps);
                vmax = std::max(vmax, samples[j].relVel_mps);
                rmin = std::min(rmin, samples[j].ratio);
                rmax = std::max(rmax, samples[j].ratio);
            }
            m.t1_s = samples[j > i ? j - 1 : i].t_s;
            i = j;
            // Same degeneracy rule as the core (bounding box of the excursion).
            const double box = (vmax - vmin) * (rmax - rmin);
            m.orientation =
                !(box > 0) || std::abs(m.signedArea) <= opt.degenerateFraction * box ? 0 : (m.signedArea < 0 ? -1 : +1);
            marks_[slot].push_back(m);
            const QString kind = m.orientation < 0 ? QStringLiteral("cw")
                                                   : (m.orientation > 0 ? QStringLiteral("ccw") : QStringLiteral("flat"));
            const QColor color = m.orientation < 0 ? style::clockwise()
                                                   : (m.orientation > 0 ? style::counterClockwise() : QColor(120, 120, 120));
            // Built detached and without a legend entry, then attached: attaching a legend item and
            // removing it again re-lays out the legend each time (seconds for ~200 excursions).
            auto* c = new DecimatedCurve(QStringLiteral("%1: loop %2 %3").arg(modelLabel(law)).arg(k).arg(kind));
            c->setItemAttribute(QwtPlotItem::Legend, false);
            c->setPen(QPen(color, style::kModelLineWidth, style::modelPenStyle(law)));
            c->setRenderHint(QwtPlotItem::RenderAntialiased, true);
            c->setSamples(pts);
            c->setZ(20);
            c->attach(plot_);
        }
    } else if (bg) {
        bg->detach();
        delete bg;
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
    if (!lines.isEmpty()) lines.prepend(QStringLiteral("slip loops (grey: stick and reversals)"));
    QwtText text(lines.isEmpty() ? QString() : lines.join(QStringLiteral("<br>")), QwtText::RichText);
    text.setRenderFlags(Qt::AlignLeft | Qt::AlignTop);
    QFont f = font();
    f.setPointSizeF(f.pointSizeF() * 0.9);
    text.setFont(f);
    text.setBackgroundBrush(QBrush(QColor(255, 255, 255, 210)));
    summary_->setText(text);
}

}  // namespace stickslip::widgets
