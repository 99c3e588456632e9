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
#include "wrapped_text_label.hpp"

namespace stickslip::widgets {

namespace {

// The loops of a run: its complete slip excursions grouped by orientation (clockwise,
// counter-clockwise, flat), each group one point list cut into pieces (one per excursion),
// the grey pieces between them, and a mark per excursion.
struct LoopGeometry {
    QVector<QPointF> all;  // every sample (V, F/t_N)
    QVector<QPointF> setPts[3];
    QVector<QPair<int, int>> setPieces[3], greyPieces;
    std::vector<LoopMark> marks;
};

LoopGeometry loopGeometry(const std::vector<Sample>& samples) {
    LoopGeometry g;
    const size_t n = samples.size();
    std::vector<double> t(n), v(n), rho(n);
    QVector<QPointF>& all = g.all;
    all.resize(static_cast<int>(n));
    for (size_t k = 0; k < n; ++k) {
        t[k] = samples[k].t_s;
        v[k] = samples[k].relVel_mps;
        rho[k] = samples[k].ratio;
        all[static_cast<int>(k)] = QPointF(v[k], rho[k]);
    }
    // The complete slip excursions, grouped by orientation: one item per orientation draws its
    // excursions as separate polylines. The grey trajectory is drawn only where no loop covers
    // it (stick and reversals; each grey piece shares its end samples with the loops it joins).
    QVector<QPointF>* setPts = g.setPts;
    QVector<QPair<int, int>>* setPieces = g.setPieces;
    QVector<QPair<int, int>>& greyPieces = g.greyPieces;
    int greyFrom = 0;
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
        while (i < n && samples[i].t_s < m.t0_s) ++i;
        double vmin = INFINITY, vmax = -INFINITY, rmin = INFINITY, rmax = -INFINITY;
        size_t j = i;
        for (; j < n && (v[j] > 0 ? 1 : (v[j] < 0 ? -1 : 0)) == m.sign; ++j) {
            vmin = std::min(vmin, v[j]);
            vmax = std::max(vmax, v[j]);
            rmin = std::min(rmin, rho[j]);
            rmax = std::max(rmax, rho[j]);
        }
        m.t1_s = samples[j > i ? j - 1 : i].t_s;
        // Same degeneracy rule as the core (bounding box of the excursion).
        const double box = (vmax - vmin) * (rmax - rmin);
        m.orientation =
            !(box > 0) || std::abs(m.signedArea) <= opt.degenerateFraction * box ? 0 : (m.signedArea < 0 ? -1 : +1);
        g.marks.push_back(m);
        if (j > i) {
            const int o = m.orientation < 0 ? 0 : (m.orientation > 0 ? 1 : 2);
            const int first = setPts[o].size();
            setPts[o].append(all.mid(static_cast<int>(i), static_cast<int>(j - i)));
            setPieces[o].append({first, setPts[o].size() - 1});
            if (static_cast<int>(i) > greyFrom) greyPieces.append({greyFrom, static_cast<int>(i)});
            greyFrom = static_cast<int>(j - 1);
        }
        i = j;
    }
    if (greyFrom < static_cast<int>(n) - 1) greyPieces.append({greyFrom, static_cast<int>(n) - 1});

    return g;
}

// One orientation's loops: `c` (created, refilled, or removed when there are no pieces).
void fillSetCurve(QwtPlot* plot, PiecewiseCurve*& c, const QString& title, const QVector<QPointF>& pts,
                  const QVector<QPair<int, int>>& pieces, const QPen& pen, double z) {
    if (pieces.isEmpty()) {
        if (c) {
            c->detach();
            delete c;
            c = nullptr;
        }
        return;
    }
    if (!c) {
        // Built without a legend entry (the summary box names the orientations).
        c = new PiecewiseCurve(title);
        c->setItemAttribute(QwtPlotItem::Legend, false);
        c->setRenderHint(QwtPlotItem::RenderAntialiased, true);
        c->setZ(z);
        c->attach(plot);
    }
    c->setPen(pen);
    c->setSamples(pts);
    c->setPieces(pieces);
}

}  // namespace

FrictionLoopPlot::FrictionLoopPlot(QWidget* parent) : PlotWidget(parent) {
    plot_->setTitle(QStringLiteral("Friction loop"));
    setAxisTitles(QStringLiteral("relative velocity V [m/s]"), QStringLiteral("F/t_N [-]"));
    setFactors(1.0, 1.0);
    summary_ = new WrappedTextLabel;
    summary_->setZ(50);
    summary_->attach(plot_);
    updateSummary();
}

void FrictionLoopPlot::setRun(const RunResult& run, LawKind law) {
    const int slot = style::slot(law);
    const QString prefix = modelLabel(law) + QLatin1Char(':');
    const QString trajectoryTitle = prefix + QStringLiteral(" trajectory");
    const QString setTitle[3] = {prefix + QStringLiteral(" loops cw"), prefix + QStringLiteral(" loops ccw"),
                                 prefix + QStringLiteral(" loops flat")};
    marks_[slot].clear();
    const auto& samples = run.samples;
    // This model's curves are kept and refilled (attaching or removing a legend item re-lays
    // out the legend); any other curve of the model goes.
    PiecewiseCurve* bg = nullptr;
    PiecewiseCurve* sets[3] = {nullptr, nullptr, nullptr};
    for (QwtPlotCurve* c : curves()) {
        const QString title = c->title().text();
        if (!title.startsWith(prefix)) continue;
        auto* pc = dynamic_cast<PiecewiseCurve*>(c);
        if (pc && title == trajectoryTitle && !samples.empty()) {
            bg = pc;
            continue;
        }
        bool kept = false;
        for (int o = 0; o < 3 && pc; ++o) {
            if (title != setTitle[o]) continue;
            sets[o] = pc;
            kept = true;
        }
        if (kept) continue;
        c->detach();
        delete c;
    }
    if (samples.empty()) {
        for (PiecewiseCurve* c : sets) {
            if (!c) continue;
            c->detach();
            delete c;
        }
        updateSummary();
        rescale();
        return;
    }
    LoopGeometry g = loopGeometry(samples);
    marks_[slot] = std::move(g.marks);
    const QVector<QPointF>& all = g.all;
    const QVector<QPointF>* setPts = g.setPts;
    const QVector<QPair<int, int>>* setPieces = g.setPieces;
    const QVector<QPair<int, int>>& greyPieces = g.greyPieces;

    if (!bg) {
        bg = new PiecewiseCurve(trajectoryTitle);
        bg->setRenderHint(QwtPlotItem::RenderAntialiased, true);
        bg->setZ(10);
        bg->attach(plot_);
    }
    bg->setPen(QPen(QColor(190, 190, 190), 0.8, style::modelPenStyle(law)));
    bg->setSamples(all);
    bg->setPieces(greyPieces);
    const QColor colour[3] = {style::clockwise(), style::counterClockwise(), QColor(120, 120, 120)};
    for (int o = 0; o < 3; ++o)
        // Clockwise on top: not hidden under the others.
        fillSetCurve(plot_, sets[o], setTitle[o], setPts[o], setPieces[o],
                     QPen(colour[o], style::kModelLineWidth, style::modelPenStyle(law)), o == 0 ? 21 : 20);
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
    for (auto& m : marks_) m.clear();
    updateSummary();
    PlotWidget::clearAll();
}

// A text box in the canvas corner: per model, how many loops of each orientation, in the
// loops' colours (the loops themselves carry no legend entries).
void FrictionLoopPlot::updateSummary() {
    QStringList lines;
    for (int k = 0; k < kMaxLawSlots; ++k) {
        const LawKind law = static_cast<LawKind>(k);
        const auto& m = marks_[style::slot(law)];
        if (m.empty()) continue;
        const auto cw = std::count_if(m.begin(), m.end(), [](const LoopMark& x) { return x.orientation < 0; });
        const auto ccw = std::count_if(m.begin(), m.end(), [](const LoopMark& x) { return x.orientation > 0; });
        const auto flat = static_cast<long>(m.size()) - cw - ccw;
        QString line = QStringLiteral("%1%2: <span style='color:%3'>%4 clockwise</span>, "
                                      "<span style='color:%5'>%6 counter&#8209;clockwise</span>")
                           .arg(modelLabel(law), style::modelPenStyle(law) == Qt::DashLine ? QStringLiteral(" (dashed)") : QString())
                           .arg(style::clockwise().name())
                           .arg(cw)
                           .arg(style::counterClockwise().name())
                           .arg(ccw);
        if (flat > 0) line += QStringLiteral(", %1 flat").arg(flat);
        lines << line;
    }
    if (!lines.isEmpty()) lines.prepend(QStringLiteral("slip loops (grey: stick and reversals)"));
    QwtText text(lines.isEmpty() ? QString() : lines.join(QStringLiteral("<br>")), QwtText::RichText);
    text.setRenderFlags(Qt::AlignLeft | Qt::AlignTop);  // WrappedTextLabel wraps it at the canvas width
    QFont f = font();
    f.setPointSizeF(f.pointSizeF() * 0.9);
    text.setFont(f);
    text.setBackgroundBrush(QBrush(QColor(255, 255, 255, 210)));
    summary_->setText(text);
}

}  // namespace stickslip::widgets
