// The plot widgets show exactly the data handed to them, mark friction-loop orientation
// correctly, export PNG/SVG/PDF/CSV that read back, and the rig view drives a cursor.
#include <qwt_matrix_raster_data.h>
#include <qwt_plot.h>
#include <qwt_plot_curve.h>
#include <qwt_plot_panner.h>
#include <qwt_plot_picker.h>
#include <qwt_plot_spectrogram.h>
#include <qwt_plot_zoomer.h>
#include <qwt_scale_draw.h>
#include <qwt_scale_widget.h>
#include <qwt_scale_engine.h>
#include <qwt_scale_map.h>
#include <qwt_symbol.h>

#include <QSignalSpy>
#include <QTemporaryDir>
#include <QtTest>

#include <array>
#include <cmath>
#include <map>

#include "core/integrate/simulate.hpp"
#include "core/io/csv_table.hpp"
#include "core/presets.hpp"
#include "widgets/autocorrelation_plot.hpp"
#include "widgets/bifurcation_plot.hpp"
#include "widgets/decimated_curve.hpp"
#include "widgets/friction_loop_plot.hpp"
#include "widgets/periodicity_map_plot.hpp"
#include "widgets/phase_portrait_plot.hpp"
#include "widgets/plot_export.hpp"
#include "widgets/poincare_plot.hpp"
#include "widgets/rig_view.hpp"
#include "widgets/spectrum_plot.hpp"
#include "widgets/time_series_plot.hpp"
#include "widgets/wrapped_text_label.hpp"

#include "tests/file_bytes.hpp"
#include "tests/gui/short_run.hpp"

using namespace stickslip;
using namespace stickslip::widgets;
using stickslip::testing::shortParams;
using stickslip::testing::shortRun;

namespace {

// A synthetic run whose (V, F/t_N) trace is an ellipse, traversed clockwise when cw.
RunResult ellipseRun(bool cw, int cycles, double period, int perCycle) {
    RunResult r;
    const int n = cycles * perCycle + 1;
    for (int i = 0; i < n; ++i) {
        const double t = period * i / perCycle;
        const double th = 2 * M_PI * t / period;
        Sample s;
        s.t_s = t;
        s.relVel_mps = 0.05 * std::cos(th);
        s.ratio = 0.25 + (cw ? -0.1 : 0.1) * std::sin(th);
        r.samples.push_back(s);
    }
    return r;
}

}  // namespace

class TestWidgets : public QObject {
    Q_OBJECT
private slots:
    void timeSeriesCurvesEqualSamples();
    void timeSeriesCycleRangeAndChannels();
    void twoModelsOverlaid();
    void measuredOverlayByColumnName();
    void navigationToolsExist();
    void phasePortraitAndPoincare();
    void singlePointSectionHasReadableTickLabels();
    void narrowLoopPlotHasReadableTickLabels();
    void sectionScatterBelowTheOrbitsResolutionIsOneDot();
    void loopOrientationMarksClockwise();
    void loopOrientationMarksCounterClockwise();
    void rateStateLoopsAreClockwise();
    void bifurcationAppendsBranches();
    void spectrumIsLogScaled();
    void periodicityMapShowsClasses();
    void rigViewDrivesCursor();
    void hiddenViewUpdatesWhenShown();
    void wrappedLabelStaysInsideTheCanvas();
};

void TestWidgets::timeSeriesCurvesEqualSamples() {
    const RunResult run = shortRun(LawKind::RateState);
    QVERIFY2(run.ok(), run.message.c_str());
    QVERIFY(run.samples.size() > 100);
    TimeSeriesPlot w;
    w.setChannels(kAllChannels);
    w.setRun(run, shortParams(LawKind::RateState).drive.period());
    const struct {
        const char* title;
        double (*get)(const Sample&);
        double scale;
    } expected[] = {
        {"rate-state: stage u", [](const Sample& s) { return s.stage_m; }, 1e3},
        {"rate-state: slider x", [](const Sample& s) { return s.slider_m; }, 1e3},
        {"rate-state: F/t_N", [](const Sample& s) { return s.ratio; }, 1.0},
        {"rate-state: V", [](const Sample& s) { return s.relVel_mps; }, 1.0},
        {"rate-state: alpha", [](const Sample& s) { return s.alpha; }, 1.0},
    };
    for (const auto& e : expected) {
        QwtPlotCurve* c = w.curve(QString::fromLatin1(e.title));
        QVERIFY2(c, e.title);
        QCOMPARE(c->dataSize(), run.samples.size());
        for (size_t i = 0; i < run.samples.size(); ++i) {
            const QPointF p = c->sample(static_cast<int>(i));
            QCOMPARE(p.x(), run.samples[i].t_s);
            QCOMPARE(p.y(), e.get(run.samples[i]) * e.scale);
        }
    }
    // Displacements on the left axis [mm], the rest on the right.
    QCOMPARE(w.curve("rate-state: slider x")->yAxis(), int(QwtPlot::yLeft));
    QCOMPARE(w.curve("rate-state: F/t_N")->yAxis(), int(QwtPlot::yRight));
    QVERIFY(w.plot()->axisTitle(QwtPlot::yLeft).text().contains("[mm]"));
    QVERIFY(w.plot()->axisTitle(QwtPlot::xBottom).text().contains("[s]"));
}

void TestWidgets::timeSeriesCycleRangeAndChannels() {
    const RunResult run = shortRun(LawKind::RateState);
    const double T = shortParams(LawKind::RateState).drive.period();
    TimeSeriesPlot w;
    w.setChannels(channelBit(Channel::Slider));
    w.setRun(run, T);
    QCOMPARE(w.curves().size(), 1);
    w.setCycleRange(1.0, 2.0);
    QwtPlotCurve* c = w.curve("rate-state: slider x");
    QVERIFY(c);
    QVERIFY(c->dataSize() > 10);
    const double t0 = run.samples.front().t_s;
    size_t inRange = 0;
    for (const Sample& s : run.samples)
        if (s.t_s >= t0 + T - 1e-12 && s.t_s < t0 + 2 * T - 1e-12) ++inRange;
    QCOMPARE(c->dataSize(), inRange);
    for (size_t i = 0; i < c->dataSize(); ++i) {
        QVERIFY(c->sample(static_cast<int>(i)).x() >= t0 + T - 1e-9);
        QVERIFY(c->sample(static_cast<int>(i)).x() < t0 + 2 * T);
    }
    // Only right-axis channels: they move to the left axis with their own title.
    w.setChannels(channelBit(Channel::FrictionRatio));
    QCOMPARE(w.curve("rate-state: F/t_N")->yAxis(), int(QwtPlot::yLeft));
    QVERIFY(w.plot()->axisTitle(QwtPlot::yLeft).text().contains("F/t_N"));
}

void TestWidgets::twoModelsOverlaid() {
    const RunResult rs = shortRun(LawKind::RateState);
    const RunResult cl = shortRun(LawKind::Coulomb);
    QVERIFY(cl.ok());
    const double T = shortParams(LawKind::RateState).drive.period();
    TimeSeriesPlot w;
    w.setChannels(channelBit(Channel::Slider));
    w.setRun(rs, T, LawKind::RateState);
    w.setRun(cl, T, LawKind::Coulomb);
    QwtPlotCurve* a = w.curve("rate-state: slider x");
    QwtPlotCurve* b = w.curve("Coulomb: slider x");
    QVERIFY(a && b);
    QCOMPARE(a->pen().style(), Qt::SolidLine);
    QCOMPARE(b->pen().style(), Qt::DashLine);
    QCOMPARE(b->dataSize(), cl.samples.size());
    QCOMPARE(b->sample(5).y(), cl.samples[5].slider_m * 1e3);
    w.clearModel(LawKind::Coulomb);
    QVERIFY(!w.curve("Coulomb: slider x"));
    QVERIFY(w.curve("rate-state: slider x"));
}

void TestWidgets::measuredOverlayByColumnName() {
    io::CsvTable table;
    io::CsvError err;
    QVERIFY(io::parseCsvTable("time_s,slider_m\n0,0.001\n0.01,0.002\n0.02,-0.0005\n", "measured.csv", table, err));
    MeasuredSeries m;
    QString why;
    QVERIFY(!measuredFromTable(table, "time_s", "force_N", m, &why));
    QVERIFY(why.contains("force_N"));
    QVERIFY(why.contains("measured.csv"));
    QVERIFY(measuredFromTable(table, "time_s", "slider_m", m, &why));
    TimeSeriesPlot w;
    w.setChannels(channelBit(Channel::Slider));
    w.addMeasured(Channel::Slider, m);
    QwtPlotCurve* c = w.curve("measured: slider_m");
    QVERIFY(c);
    QCOMPARE(c->dataSize(), size_t(3));
    QCOMPARE(c->sample(1).x(), 0.01);
    QCOMPARE(c->sample(1).y(), 2.0);     // mm
    QCOMPARE(c->sample(2).y(), -0.5);

    PhasePortraitPlot pp;   // base-class overlay: SI scaled like the axes (x in mm)
    MeasuredSeries xv{"measured: x-V", {0.001, 0.002}, {0.01, 0.02}};
    pp.addMeasured(xv);
    QCOMPARE(pp.curve("measured: x-V")->sample(1), QPointF(2.0, 0.02));
    pp.clearMeasured();
    QVERIFY(!pp.curve("measured: x-V"));
}

void TestWidgets::navigationToolsExist() {
    TimeSeriesPlot w;
    w.setRun(shortRun(LawKind::RateState), 1.0 / 3.0);
    QVERIFY(w.zoomer());
    QVERIFY(w.panner());
    QVERIFY(w.picker());
    QVERIFY(w.zoomer()->isEnabled());
    QCOMPARE(w.picker()->rubberBand(), QwtPicker::CrossRubberBand);
    QCOMPARE(w.picker()->trackerMode(), QwtPicker::AlwaysOn);
    // The zoom base spans the data (autoscaled).
    const QRectF base = w.zoomer()->zoomBase();
    const QRectF data = w.curve("rate-state: slider x")->boundingRect();
    QVERIFY(base.left() <= data.left() + 1e-9 && base.right() >= data.right() - 1e-9);
    QVERIFY(base.top() <= data.top() + 1e-9 && base.bottom() >= data.bottom() - 1e-9);
}

// A periodic run's section is one dot (Fig. 22 set at A = 0.4 mm: x ≈ 0.0711 mm). The axes
// around it must carry tick labels that fit side by side in a dock-sized plot.
void TestWidgets::singlePointSectionHasReadableTickLabels() {
    PoincarePlot poincare;
    poincare.resize(380, 300);
    poincare.show();
    poincare.setSection(std::vector<double>(50, 7.10512e-5), std::vector<double>(50, 4.76591e-3), LawKind::RateState);
    QwtPlot* plot = poincare.plot();
    plot->replot();
    QCoreApplication::processEvents();
    for (int axis : {int(QwtPlot::xBottom), int(QwtPlot::yLeft)}) {
        const QList<double> ticks = plot->axisScaleDiv(axis).ticks(QwtScaleDiv::MajorTick);
        QVERIFY(ticks.size() >= 2);
        const QFont font = plot->axisWidget(axis)->font();
        double labels = 0;
        for (double v : ticks) {
            const QSizeF sz = plot->axisScaleDraw(axis)->label(v).textSize(font);
            labels += axis == QwtPlot::xBottom ? sz.width() : sz.height();
        }
        const double room = axis == QwtPlot::xBottom ? plot->canvas()->width() : plot->canvas()->height();
        QVERIFY2(labels < 0.8 * room, qPrintable(QString("axis %1: %2 tick labels need %3 px of %4")
                                                      .arg(axis).arg(ticks.size()).arg(labels).arg(room)));
    }
}

// The F/t_N–V loop in the app's default dock (~340 px wide) on the Fig. 20 preset: the bottom
// axis's labels ("-0.04" … "0.04") do not run into each other (seen: "-0.04-0.03-0.02-0.01"),
// and a wide plot keeps Qwt's eight intervals.
void TestWidgets::narrowLoopPlotHasReadableTickLabels() {
    Preset p;
    QVERIFY(findPreset("fig20", p));
    SimParams s = p.params;
    s.cycles = 3;
    const RunResult run = simulate(s);
    QVERIFY2(run.ok(), run.message.c_str());
    FrictionLoopPlot w;
    w.resize(340, 330);
    w.show();
    QVERIFY(QTest::qWaitForWindowExposed(&w));
    w.setRun(run, s.drive.period());
    QwtPlot* plot = w.plot();
    plot->replot();
    QCoreApplication::processEvents();
    const QList<double> ticks = plot->axisScaleDiv(QwtPlot::xBottom).ticks(QwtScaleDiv::MajorTick);
    QVERIFY(ticks.size() >= 3);
    const QFont font = plot->axisWidget(QwtPlot::xBottom)->font();
    double labels = 0;
    for (double v : ticks) labels += plot->axisScaleDraw(QwtPlot::xBottom)->label(v).textSize(font).width();
    const double room = plot->canvas()->width();
    QVERIFY2(labels < 0.8 * room, qPrintable(QString("%1 tick labels need %2 px of %3").arg(ticks.size()).arg(labels).arg(room)));
    w.resize(1000, 330);
    QCoreApplication::processEvents();
    QCOMPARE(w.xMajorTicks(), 8);
}

// The section of a periodic run computed at a tolerance scatters by the tolerance's order (Fig. 22
// preset, TOL 1e-4: x within 4e-9 m, V within 6e-7 m/s). With the orbit's extent given, the
// axes show at least 1 % of it around the points (one dot); a section spread wider than that,
// and one without an extent, keep the autoscaled range.
void TestWidgets::sectionScatterBelowTheOrbitsResolutionIsOneDot() {
    std::vector<double> x, v;
    for (int i = 0; i < 40; ++i) {
        x.push_back(7.10377e-5 + 4e-10 * (i % 7));
        v.push_back(4.76614e-3 + 6e-8 * (i % 5));
    }
    auto spans = [](PoincarePlot& p) {
        QwtPlot* plot = p.plot();
        plot->replot();
        const QwtScaleDiv xs = plot->axisScaleDiv(QwtPlot::xBottom), ys = plot->axisScaleDiv(QwtPlot::yLeft);
        return std::array<double, 4>{xs.lowerBound(), xs.upperBound(), ys.lowerBound(), ys.upperBound()};
    };
    PoincarePlot plain;
    plain.setSection(x, v, LawKind::RateState);
    const auto a = spans(plain);
    QVERIFY2(a[1] - a[0] < 1e-4, qPrintable(QString("x span %1 mm").arg(a[1] - a[0])));  // autoscaled to the scatter
    PoincarePlot dot;
    dot.setOrbitExtent(1.0e-3, 0.05);  // x over 1 mm, V over 0.05 m/s
    dot.setSection(x, v, LawKind::RateState);
    const auto b = spans(dot);
    QVERIFY2(b[1] - b[0] >= 0.01 * 1.0 * (1 - 1e-9), qPrintable(QString("x span %1 mm").arg(b[1] - b[0])));
    QVERIFY2(b[3] - b[2] >= 0.01 * 0.05 * (1 - 1e-9), qPrintable(QString("V span %1 m/s").arg(b[3] - b[2])));
    QVERIFY(b[0] < x.front() * 1e3 && b[1] > x.back() * 1e3 && b[2] < v.front() && b[3] > v.back());
    QVERIFY(std::abs(0.5 * (b[0] + b[1]) - 7.10389e-2) < 1e-5);  // centred on the points
    // A cloud wider than 1 % of the orbit: the data's own range.
    std::vector<double> wide = x;
    for (size_t i = 0; i < wide.size(); ++i) wide[i] += 3e-4 * static_cast<double>(i) / 39.0;
    dot.setSection(wide, v, LawKind::RateState);
    const auto c = spans(dot);
    QVERIFY(c[1] - c[0] >= 0.3 && c[1] - c[0] < 0.6);
}

void TestWidgets::phasePortraitAndPoincare() {
    const RunResult run = shortRun(LawKind::RateState);
    PhasePortraitPlot pp;
    pp.setRun(run);
    QwtPlotCurve* c = pp.curve("rate-state: trajectory");
    QVERIFY(c);
    QCOMPARE(c->dataSize(), run.samples.size());
    QCOMPARE(c->sample(17), QPointF(run.samples[17].slider_m * 1e3, run.samples[17].relVel_mps));

    PoincarePlot poincare;
    poincare.setSection(std::vector<double>{1e-3, 2e-3, 3e-3}, std::vector<double>{0.1, 0.2, 0.3}, LawKind::Coulomb);
    QwtPlotCurve* s = poincare.curve("Coulomb: section");
    QVERIFY(s);
    QCOMPARE(s->style(), QwtPlotCurve::NoCurve);   // dots only
    QCOMPARE(s->sample(2), QPointF(3.0, 0.3));
}

void TestWidgets::loopOrientationMarksClockwise() {
    const double T = 0.5;
    FrictionLoopPlot w;
    w.setRun(ellipseRun(true, 3, T, 200), T);
    const auto& marks = w.loopMarks(LawKind::RateState);
    // V = 0.05 cos(2πt/T) from its maximum: the first and last (partial) half-cycles are not
    // loops; the 5 complete slip excursions in between are, alternating in the sign of V.
    QCOMPARE(marks.size(), size_t(5));
    for (size_t k = 0; k < marks.size(); ++k) {
        const LoopMark& m = marks[k];
        QCOMPARE(m.orientation, -1);
        QVERIFY(m.signedArea < 0);
        QCOMPARE(m.sign, k % 2 == 0 ? -1 : +1);
        QVERIFY(std::abs(m.t1_s - m.t0_s - T / 2) < 0.02 * T);
        // Half the ellipse (a = 0.05, b = 0.1) with |V| < 10 % of the peak cut off and closed by
        // the chord: a b (acos c − c √(1 − c²)) with c = 0.1.
        const double c = 0.1, expected = 0.05 * 0.1 * (std::acos(c) - c * std::sqrt(1 - c * c));
        // (5 %: with 200 samples per cycle the cut falls up to one 1.8° sample further in.)
        QVERIFY2(std::abs(std::abs(m.signedArea) - expected) < 0.05 * expected, qPrintable(QString::number(m.signedArea)));
    }
    QVERIFY(w.curve("rate-state: trajectory"));
    // The five loops are the five pieces of one clockwise item, each exactly its excursion's samples.
    auto* cw = dynamic_cast<PiecewiseCurve*>(w.curve("rate-state: loops cw"));
    QVERIFY(cw);
    QVERIFY(!w.curve("rate-state: loops ccw"));
    QVERIFY(!w.curve("rate-state: loops flat"));
    QCOMPARE(cw->pen().color(), QColor(31, 119, 180));
    QCOMPARE(cw->testItemAttribute(QwtPlotItem::Legend), false);
    QCOMPARE(cw->pieces().size(), 5);
    const RunResult run = ellipseRun(true, 3, T, 200);
    size_t total = 0;
    for (int k = 0; k < 5; ++k) {
        const QVector<QPointF> piece = cw->pieceSamples(k);
        QVERIFY(piece.size() > 2);
        total += static_cast<size_t>(piece.size());
        for (const QPointF& p : piece) QVERIFY(p.x() * marks[static_cast<size_t>(k)].sign > 0);   // one sign of V
        // First and last samples at the excursion's time span.
        size_t first = 0;
        while (run.samples[first].t_s < marks[static_cast<size_t>(k)].t0_s) ++first;
        QCOMPARE(piece.front(), QPointF(run.samples[first].relVel_mps, run.samples[first].ratio));
        size_t last = first;
        while (run.samples[last].t_s < marks[static_cast<size_t>(k)].t1_s) ++last;
        QCOMPARE(piece.back(), QPointF(run.samples[last].relVel_mps, run.samples[last].ratio));
        QCOMPARE(static_cast<size_t>(piece.size()), last - first + 1);
    }
    QCOMPARE(cw->dataSize(), total);
    // The grey trajectory keeps every sample but is drawn only between the loops: its pieces
    // and the loops' cover every sample, joined at shared end samples.
    auto* grey = dynamic_cast<PiecewiseCurve*>(w.curve("rate-state: trajectory"));
    QVERIFY(grey);
    QCOMPARE(grey->dataSize(), run.samples.size());
    QCOMPARE(grey->pieces().size(), 6);
    size_t greySamples = 0;
    for (const auto& pc : grey->pieces()) greySamples += static_cast<size_t>(pc.second - pc.first + 1);
    QCOMPARE(greySamples + total, run.samples.size() + 2 * 5);
    // Drawing a piecewise item draws every piece (and only those).
    w.resize(400, 300);
    w.show();
    QVERIFY(QTest::qWaitForWindowExposed(&w));
    w.plot()->replot();
    QVERIFY(cw->lastDrawnPoints() > 5 * 2);
    QVERIFY(cw->lastDrawnPoints() <= static_cast<int>(total));
    // A new run refills the same items.
    w.setRun(ellipseRun(true, 2, T, 200), T);
    QCOMPARE(dynamic_cast<PiecewiseCurve*>(w.curve("rate-state: loops cw")), cw);
    QCOMPARE(cw->pieces().size(), 3);
}

void TestWidgets::loopOrientationMarksCounterClockwise() {
    const double T = 0.5;
    FrictionLoopPlot w;
    w.setRun(ellipseRun(false, 2, T, 100), LawKind::Coulomb);
    const auto& marks = w.loopMarks(LawKind::Coulomb);
    QCOMPARE(marks.size(), size_t(3));
    for (const LoopMark& m : marks) QCOMPARE(m.orientation, +1);
    auto* ccw = dynamic_cast<PiecewiseCurve*>(w.curve("Coulomb: loops ccw"));
    QVERIFY(ccw);
    QCOMPARE(ccw->pieces().size(), 3);
    QVERIFY(!w.curve("Coulomb: loops cw"));
    QCOMPARE(ccw->pen().color(), QColor(214, 39, 40));
    QCOMPARE(ccw->pen().style(), Qt::DashLine);
    QVERIFY(w.loopMarks(LawKind::RateState).empty());
}

// MODEL.md fact 6: the rate-state law gives only clockwise F/t_N–V loops (prescribed slip, Fig. 17).
void TestWidgets::rateStateLoopsAreClockwise() {
    Preset p;
    QVERIFY(findPreset("fig17", p));
    SimParams s = p.params;
    s.integration.dt_s = s.drive.period() / 4000.0;
    s.cycles = 3;
    const RunResult run = simulate(s);
    QVERIFY2(run.ok(), run.message.c_str());
    FrictionLoopPlot w;
    w.setRun(run, s.drive.period());
    const auto& marks = w.loopMarks(LawKind::RateState);
    QVERIFY(marks.size() >= 2);
    for (const LoopMark& m : marks) QVERIFY2(m.orientation <= 0, "a counter-clockwise rate-state loop");
    QVERIFY(std::count_if(marks.begin(), marks.end(), [](const LoopMark& m) { return m.orientation < 0; }) >= 1);
}

void TestWidgets::bifurcationAppendsBranches() {
    BifurcationPlot w;
    w.appendColumn(SweepBranch::Up, 1e-3, {0.1e-3, 0.2e-3});
    w.appendColumn(SweepBranch::Up, 2e-3, {0.3e-3});
    w.appendColumn(SweepBranch::Down, 2e-3, {0.4e-3, 0.5e-3, 0.6e-3});
    QCOMPARE(w.pointCount(), 6);
    QwtPlotCurve* up = w.curve("rate-state: up");
    QwtPlotCurve* down = w.curve("rate-state: down");
    QVERIFY(up && down);
    QCOMPARE(up->dataSize(), size_t(3));
    QCOMPARE(up->sample(2), QPointF(2.0, 0.3));   // mm, mm
    QCOMPARE(down->sample(0), QPointF(2.0, 0.4));
    QVERIFY(up->symbol() && down->symbol());
    QVERIFY(up->symbol()->pen().color() != down->symbol()->pen().color());
    // Streamed appends grow the bounding rect (cached rect invalidated).
    w.appendColumn(SweepBranch::Up, 4e-3, {1e-3});
    QCOMPARE(up->boundingRect().right(), 4.0);
    SweepPoint pt;
    pt.value = 5e-3;
    pt.direction = -1;
    pt.section.slider_m = {0.7e-3};
    w.appendPoint(pt, LawKind::Coulomb);
    QVERIFY(w.curve("Coulomb: down"));
    w.clearAll();
    QCOMPARE(w.pointCount(), 0);
}

void TestWidgets::spectrumIsLogScaled() {
    SpectrumPlot w;
    w.setSpectrum({0.0, 1.0, 2.0, 3.0}, {0.0, 1e-6, 1e-3, 1e-9});
    QVERIFY(dynamic_cast<const QwtLogScaleEngine*>(w.plot()->axisScaleEngine(QwtPlot::yLeft)));
    QwtPlotCurve* c = w.curve("rate-state: PSD");
    QVERIFY(c);
    QCOMPARE(c->sample(0).y(), 1e-9);   // zero clamped to the smallest positive value
    QCOMPARE(c->sample(2).y(), 1e-3);

    AutocorrelationPlot a;
    a.setAutocorrelation({0.0, 0.1, 0.2}, {1.0, 0.5, -0.2});
    QCOMPARE(a.curve("rate-state: autocorrelation")->sample(2), QPointF(0.2, -0.2));
}

void TestWidgets::periodicityMapShowsClasses() {
    PeriodicityGrid g;
    g.nx = 3;
    g.ny = 2;
    g.x0 = 1e-3;
    g.x1 = 3e-3;
    g.y0 = 3.0;
    g.y1 = 4.0;
    g.classes = {kMapStick, 1, 2, kMapIrregular, 5, kMapMissing};
    PeriodicityMapPlot w;
    w.setMap(g, "A [mm]", 1e3, "f [Hz]", 1.0);
    const auto* data = dynamic_cast<const QwtMatrixRasterData*>(w.spectrogram()->data());
    QVERIFY(data);
    // Cell centres carry their class codes.
    QCOMPARE(data->value(1.0, 3.0), double(kMapStick));
    QCOMPARE(data->value(2.0, 3.0), 1.0);
    QCOMPARE(data->value(3.0, 3.0), 2.0);
    QCOMPARE(data->value(1.0, 4.0), double(kMapIrregular));
    QCOMPARE(data->value(2.0, 4.0), 5.0);
    // Titles in the fonts of the other views (seen: the map's axis titles bold and larger).
    BifurcationPlot other;
    other.appendColumn(SweepBranch::Up, 1e-3, {0.1e-3});
    other.rescale();
    for (int axis : {int(QwtPlot::xBottom), int(QwtPlot::yLeft)})
        QCOMPARE(w.plot()->axisTitle(axis).font(), other.plot()->axisTitle(axis).font());
    QCOMPARE(w.plot()->title().font(), other.plot()->title().font());
    // Every class reads apart from the others: periods 5–16 share one hue, darker with the
    // period, and none of them is near a colour of stick, period 1–4 or irregular.
    auto distance = [](const QColor& a, const QColor& b) {
        return std::hypot(a.red() - b.red(), a.green() - b.green(), a.blue() - b.blue());
    };
    const int named[] = {kMapStick, 1, 2, 3, 4, kMapIrregular};
    for (int a : named)
        for (int b : named)
            if (a < b) QVERIFY(distance(PeriodicityMapPlot::classColor(a), PeriodicityMapPlot::classColor(b)) > 60);
    for (int p = 5; p <= 16; ++p) {
        const QColor c = PeriodicityMapPlot::classColor(p);
        QCOMPARE(c.hslHue(), PeriodicityMapPlot::classColor(5).hslHue());
        if (p > 5) QVERIFY(c.lightness() < PeriodicityMapPlot::classColor(p - 1).lightness());
        for (int a : named) {
            const QColor o = PeriodicityMapPlot::classColor(a);
            QVERIFY2(distance(c, o) > 60, qPrintable(QString("period %1 vs class %2").arg(p).arg(a)));
            const int dh = std::abs(c.hslHue() - o.hslHue());
            if (o.hslHue() >= 0) QVERIFY2(std::min(dh, 360 - dh) >= 40, qPrintable(QString("period %1's hue vs class %2's").arg(p).arg(a)));
        }
    }
    QVERIFY(w.plot()->footer().text().contains("5–16"));

    // From the core map type: motion classes become codes, undone cells "missing".
    PeriodicityMap m;
    m.values1 = {1e-3, 2e-3};
    m.values2 = {3.0};
    m.motion = {MotionClass::Stick, MotionClass::Periodic};
    m.period = {1, 3};
    m.done = {1, 1};
    PeriodicityGrid g2 = gridFromMap(m);
    QCOMPARE(g2.nx, 2);
    QCOMPARE(g2.at(0, 0), kMapStick);
    QCOMPARE(g2.at(1, 0), 3);
    m.done = {1, 0};
    QCOMPARE(gridFromMap(m).at(1, 0), kMapMissing);

    QTemporaryDir dir;
    const QString csv = dir.filePath("map.csv");
    QVERIFY(w.exportTo(csv));
    const QString text = QString::fromUtf8(readAll(csv));
    QVERIFY(text.contains("class,2,4,5"));   // cell (A = 2 mm, f = 4 Hz) is period 5
}

void TestWidgets::rigViewDrivesCursor() {
    const SimParams p = shortParams(LawKind::RateState);
    const RunResult run = simulate(p);
    RigView rig;
    TimeSeriesPlot ts;
    ts.setRun(run, p.drive.period());
    QObject::connect(&rig, &RigView::timeChanged, &ts, &TimeSeriesPlot::setCursorTime);
    QSignalSpy spy(&rig, &RigView::timeChanged);
    rig.setRun(run, p);
    QCOMPARE(spy.count(), 1);
    const double tMid = run.samples[run.samples.size() / 2].t_s;
    rig.setTime(tMid);
    QCOMPARE(ts.cursorTime(), tMid);
    Sample s;
    QVERIFY(rig.currentSample(s));
    QCOMPARE(s.t_s, tMid);
    QCOMPARE(s.stuck, run.samples[run.samples.size() / 2].stuck);
    // Out-of-range times are clamped to the run.
    rig.setTime(1e9);
    QCOMPARE(rig.currentTime(), run.samples.back().t_s);

    // Playing advances time (and loops at the end); pausing stops it.
    rig.setTime(run.samples.front().t_s);
    rig.setSpeed(0.2);
    QCOMPARE(rig.speed(), 0.2);
    rig.play();
    QVERIFY(rig.isPlaying());
    QTRY_VERIFY_WITH_TIMEOUT(rig.currentTime() > run.samples.front().t_s, 5000);
    QVERIFY(ts.cursorTime() > run.samples.front().t_s);
    rig.pause();
    QVERIFY(!rig.isPlaying());
    const double t = rig.currentTime();
    QTest::qWait(100);
    QCOMPARE(rig.currentTime(), t);
    // Rendering the schematic works offscreen and is not blank.
    rig.resize(600, 300);
    const QImage img = rig.grab().toImage();
    QVERIFY(!img.isNull());
    int nonWhite = 0;
    for (int y = 0; y < img.height(); y += 3)
        for (int x = 0; x < img.width(); x += 3)
            if (img.pixelColor(x, y) != QColor(Qt::white)) ++nonWhite;
    QVERIFY(nonWhite > 100);
    // The read-out (t, u, x, V, F/t_N) fits on one line when wide; a narrow view puts it on two
    // lines instead of letting it run under the STICK/SLIP label (seen in a screenshot): ink in
    // the second line's band at the right only when narrow.
    auto secondLineInk = [&](int width) {
        rig.resize(width, 300);
        const QImage im = rig.grab().toImage();
        int ink = 0;
        for (int y = 42; y < 52; ++y)  // the second line's band (the grab includes the frame)
            for (int x = static_cast<int>(0.6 * width); x < static_cast<int>(0.97 * width); ++x)
                if (qGray(im.pixel(x, y)) < 128) ++ink;
        return ink;
    };
    const int wide = secondLineInk(1100), narrow = secondLineInk(420);
    qInfo("read-out second-line ink: wide %d, narrow %d", wide, narrow);
    QCOMPARE(wide, 0);
    QVERIFY(narrow > 20);
    rig.clear();
    QVERIFY(!rig.currentSample(s));
}

void TestWidgets::hiddenViewUpdatesWhenShown() {
    const RunResult run = shortRun(LawKind::RateState);
    PhasePortraitPlot w;   // never shown yet: hidden
    int calls = 0;
    w.updateWhenVisible([&] {
        ++calls;
        w.setRun(run);
    });
    QCOMPARE(calls, 0);
    QVERIFY(w.hasPendingUpdate());
    QVERIFY(!w.curve("rate-state: trajectory"));
    // A newer update replaces the older one.
    w.updateWhenVisible([&] {
        calls += 10;
        w.setRun(run);
    });
    w.show();
    QCOMPARE(calls, 10);
    QVERIFY(!w.hasPendingUpdate());
    QCOMPARE(w.curve("rate-state: trajectory")->dataSize(), run.samples.size());
    // Visible: runs at once.
    w.updateWhenVisible([&] { ++calls; });
    QCOMPARE(calls, 11);
    // Hidden again, then exported: the file shows the newest data.
    w.hide();
    w.updateWhenVisible([&] {
        ++calls;
        w.clearAll();
    });
    QTemporaryDir dir;
    QVERIFY(w.exportTo(dir.filePath("p.csv")));
    QCOMPARE(calls, 12);
    QVERIFY(!readAll(dir.filePath("p.csv")).contains("rate-state: trajectory"));
}

// The loop view's summary in a narrow dock: its text wraps inside the canvas instead of running
// off its right edge (seen on the default preset's screenshot, 361 px canvas).
void TestWidgets::wrappedLabelStaysInsideTheCanvas() {
    widgets::WrappedTextLabel label;
    QwtText t(QStringLiteral("rate-state: <span style='color:#1f77b4'>19 clockwise</span>, "
                             "<span style='color:#d62728'>162 counter&#8209;clockwise</span>"),
              QwtText::RichText);
    t.setRenderFlags(Qt::AlignLeft | Qt::AlignTop);
    label.setText(t);
    const QFont font;
    const QSizeF natural = t.textSize(font);
    QVERIFY(natural.width() > 50);
    const QRectF narrow(0, 0, 0.6 * natural.width(), 400);
    const QRectF r = label.textRect(narrow, font);
    QVERIFY2(narrow.contains(r), "the text's rectangle leaves the canvas");
    QVERIFY2(r.height() > 1.5 * natural.height(), "a line too long for the canvas is not wrapped");
    const QRectF wide(0, 0, 3 * natural.width(), 400);
    const QRectF rw = label.textRect(wide, font);
    QVERIFY(std::abs(rw.width() - natural.width()) < 1.0);  // as wide as the text, not the canvas
    QVERIFY(std::abs(rw.height() - natural.height()) < 1.0);
    QVERIFY(widgets::WrappedTextLabel().textRect(wide, font).isEmpty());
}

QTEST_MAIN(TestWidgets)
#include "tst_widgets.moc"
