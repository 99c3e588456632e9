#include "view_set.hpp"

#include "core/friction/friction_law.hpp"

#include <QVBoxLayout>

#include "param_specs.hpp"
#include "time_series_controls.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <utility>

#include "core/io/csv_table.hpp"
#include "widgets/autocorrelation_plot.hpp"
#include "widgets/bifurcation_plot.hpp"
#include "widgets/friction_loop_plot.hpp"
#include "widgets/periodicity_map_plot.hpp"
#include "widgets/phase_portrait_plot.hpp"
#include "widgets/poincare_plot.hpp"
#include "widgets/rig_view.hpp"
#include "widgets/spectrum_plot.hpp"
#include "widgets/time_series_plot.hpp"

namespace stickslip::gui {

using namespace stickslip::widgets;

namespace {

// The range of the slider displacement x and of the relative velocity V over the runs of an
// outcome, the orbit a Poincaré section cuts (PoincarePlot::setOrbitExtent).
std::pair<double, double> orbitExtent(const RunOutcome& o) {
    double x = 0, v = 0;
    for (const ModelRun& mr : o.runs) {
        const auto& s = mr.run.samples;
        if (s.empty()) continue;
        const auto [xl, xh] = std::minmax_element(s.begin(), s.end(), [](const Sample& a, const Sample& b) { return a.slider_m < b.slider_m; });
        const auto [vl, vh] = std::minmax_element(s.begin(), s.end(), [](const Sample& a, const Sample& b) { return a.relVel_mps < b.relVel_mps; });
        x = std::max(x, xh->slider_m - xl->slider_m);
        v = std::max(v, vh->relVel_mps - vl->relVel_mps);
    }
    return {x, v};
}

}  // namespace

ViewSet::ViewSet(QWidget* parent) : QObject(parent) {
    timeSeries_ = new TimeSeriesPlot(parent);
    loop_ = new FrictionLoopPlot(parent);
    phase_ = new PhasePortraitPlot(parent);
    poincare_ = new PoincarePlot(parent);
    bifurcation_ = new BifurcationPlot(parent);
    spectrum_ = new SpectrumPlot(parent);
    acf_ = new AutocorrelationPlot(parent);
    map_ = new PeriodicityMapPlot(parent);
    rig_ = new RigView(parent);
    spectrum_->setValueTitle(QStringLiteral("PSD of x [m²/Hz]"));
    // The time series comes with its channel and cycle-range strip.
    auto* tsBox = new QWidget(parent);
    auto* tsLayout = new QVBoxLayout(tsBox);
    tsLayout->setContentsMargins(0, 0, 0, 0);
    tsLayout->setSpacing(0);
    tsLayout->addWidget(new TimeSeriesControls(timeSeries_, tsBox));
    tsLayout->addWidget(timeSeries_, 1);
    views_ = {
        {"timeseries", tr("Time series"), tsBox, timeSeries_},
        {"rig", tr("Rig"), rig_, nullptr},
        {"loop", tr("F/t_N vs V loop"), loop_, loop_},
        {"phase", tr("Phase portrait"), phase_, phase_},
        {"poincare", tr("Poincaré section"), poincare_, poincare_},
        {"spectrum", tr("Spectrum"), spectrum_, spectrum_},
        {"autocorrelation", tr("Autocorrelation"), acf_, acf_},
        {"bifurcation", tr("Bifurcation"), bifurcation_, bifurcation_},
        {"map", tr("Periodicity map"), map_, map_},
    };
    for (const auto& v : views_) v.widget->setObjectName("view_" + v.id);
    // The time-series cursor follows the animated rig.
    connect(rig_, &RigView::timeChanged, timeSeries_, &TimeSeriesPlot::setCursorTime);
}

const ViewSet::View* ViewSet::find(const QString& id) const {
    for (const auto& v : views_)
        if (v.id == id) return &v;
    return nullptr;
}

void ViewSet::showRun(const RunOutcome& o) {
    // One copy, shared by the views that are hidden now and redraw when shown (tabs behind
    // others, closed docks): only visible views redraw on every result.
    showShared(std::make_shared<const RunOutcome>(o));
}

void ViewSet::showShared(const std::shared_ptr<const RunOutcome>& shared) {
    lastRun_ = shared;
    const RunOutcome& o = *shared;
    const bool prescribed = o.settings.params.setup == SetupKind::Prescribed;
    // The run of `law` in the outcome, or nullptr (also when it recorded nothing).
    auto runOf = [](const RunOutcome& out, LawKind law) -> const ModelRun* {
        for (const auto& r : out.runs)
            if (r.law == law && !r.run.samples.empty()) return &r;
        return nullptr;
    };
    const double period = o.settings.params.drive.period();
    timeSeries_->updateWhenVisible([this, shared, runOf, period] {
        for (LawKind law : allLaws()) {
            if (const ModelRun* mr = runOf(*shared, law)) timeSeries_->setRun(mr->run, period, law);
            else timeSeries_->clearModel(law);
        }
    });
    loop_->updateWhenVisible([this, shared, runOf, period] {
        for (LawKind law : allLaws()) {
            if (const ModelRun* mr = runOf(*shared, law)) loop_->setRun(mr->run, period, law);
            else loop_->clearModel(law);
        }
    });
    phase_->updateWhenVisible([this, shared, runOf] {
        for (LawKind law : allLaws()) {
            if (const ModelRun* mr = runOf(*shared, law)) phase_->setRun(mr->run, law);
            else phase_->clearModel(law);
        }
    });
    spectrum_->updateWhenVisible([this, shared, runOf, prescribed] {
        spectrum_->setValueTitle(prescribed ? QStringLiteral("PSD of F/t_N [1/Hz]") : QStringLiteral("PSD of x [m²/Hz]"));
        for (LawKind law : allLaws()) {
            const ModelRun* mr = runOf(*shared, law);
            if (mr && !mr->spectrumFreq_Hz.empty()) spectrum_->setSpectrum(mr->spectrumFreq_Hz, mr->spectrumPsd, law);
            else spectrum_->clearModel(law);
        }
    });
    acf_->updateWhenVisible([this, shared, runOf] {
        for (LawKind law : allLaws()) {
            const ModelRun* mr = runOf(*shared, law);
            if (mr && !mr->acf.empty()) acf_->setAutocorrelation(mr->acfLag_s, mr->acf, law);
            else acf_->clearModel(law);
        }
    });
    // The Poincaré section, when the runs recorded it (else the controller's Poincaré job
    // brings it; the block with prescribed slip has none).
    if (o.sectionInRun || prescribed) {
        poincare_->updateWhenVisible([this, shared] {
            poincare_->clearAll();
            const auto [x, v] = orbitExtent(*shared);
            poincare_->setOrbitExtent(x, v);
            for (const ModelRun& mr : shared->runs)
                if (!mr.section.slider_m.empty())
                    poincare_->setSection(mr.section.slider_m, mr.section.relVel_mps, mr.law);
        });
    }
    if (!o.runs.empty() && !o.runs.front().run.samples.empty())
        rig_->setRun(o.runs.front().run, o.settings.paramsFor(o.runs.front().law));
    else
        rig_->clear();
}

void ViewSet::showPoincare(const PoincareOutcome& o) {
    auto shared = std::make_shared<const PoincareOutcome>(o);
    poincare_->updateWhenVisible([this, shared, run = lastRun_] {
        poincare_->clearAll();
        const auto [x, v] = run ? orbitExtent(*run) : std::pair<double, double>{0.0, 0.0};
        poincare_->setOrbitExtent(x, v);
        for (const auto& [law, sec] : shared->sections)
            if (!sec.slider_m.empty()) poincare_->setSection(sec.slider_m, sec.relVel_mps, law);
    });
}

void ViewSet::viewBroughtToFront(const QString& id) {
    if (const View* v = find(id); v && v->plot) v->plot->applyPendingUpdate();
}

void ViewSet::showSweep(const SweepOutcome& o) {
    bifurcation_->clearAll();
    const ParamSpecScale scale = paramScale(QString::fromStdString(o.options.key));
    bifurcation_->setAxes(scale.title, scale.factor, tr("slider displacement x [mm]"), 1e3);
    for (const auto& [law, res] : o.results)
        for (const auto& pt : res.points)
            bifurcation_->appendColumn(pt.direction > 0 ? SweepBranch::Up : SweepBranch::Down, pt.value,
                                       pt.section.slider_m, law);
    bifurcation_->rescale();
}

void ViewSet::showMap(const MapOutcome& o) {
    const PeriodicityMap& m = o.map;
    PeriodicityGrid g;
    g.nx = static_cast<int>(m.values1.size());
    g.ny = static_cast<int>(m.values2.size());
    if (g.nx == 0 || g.ny == 0) {
        map_->clearAll();
        return;
    }
    g.x0 = m.values1.front();
    g.x1 = m.values1.back();
    g.y0 = m.values2.front();
    g.y1 = m.values2.back();
    g.classes.resize(m.motion.size());
    for (size_t i = 0; i < m.motion.size(); ++i) {
        if (i >= m.done.size() || !m.done[i]) g.classes[i] = kMapMissing;
        else if (m.motion[i] == MotionClass::Stick) g.classes[i] = kMapStick;
        else if (m.motion[i] == MotionClass::Periodic) g.classes[i] = m.period[i];
        else g.classes[i] = kMapIrregular;
    }
    const ParamSpecScale sx = paramScale(QString::fromStdString(m.key1));
    const ParamSpecScale sy = paramScale(QString::fromStdString(m.key2));
    map_->setMap(g, sx.title, sx.factor, sy.title, sy.factor);
}

namespace {

// Copies column `name` of the table, or an empty vector.
std::vector<double> columnOf(const io::CsvTable& t, const char* name) {
    const int i = t.column(name);
    return i < 0 ? std::vector<double>{} : t.columns[static_cast<size_t>(i)];
}

}  // namespace

int ViewSet::overlayMeasured(const io::CsvTable& t, double normalForce_N, QString* error) {
    const std::vector<double> time = columnOf(t, "time_s");
    const QString file = QString::fromStdString(t.path);
    if (time.empty()) {
        if (error) *error = tr("%1: no column named \"time_s\"").arg(file);
        return 0;
    }
    int n = 0;
    auto add = [&](Channel ch, const char* column, std::vector<double> y) {
        if (y.empty()) return;
        MeasuredSeries s;
        s.label = QStringLiteral("measured: %1").arg(QLatin1String(column));
        s.x = time;
        s.y = std::move(y);
        timeSeries_->addMeasured(ch, s);
        ++n;
    };
    // Column names as the CLI writes and reads them (core/io/run_csv.hpp).
    add(Channel::Stage, "stage_disp_m", columnOf(t, "stage_disp_m"));
    add(Channel::Slider, "slider_disp_m", columnOf(t, "slider_disp_m"));
    std::vector<double> ratio = columnOf(t, "friction_ratio");
    const char* ratioName = "friction_ratio";
    if (ratio.empty()) {
        // F/t_N from the force and the panel's normal force.
        ratio = columnOf(t, "friction_force_N");
        for (double& v : ratio) v /= normalForce_N;
        ratioName = "friction_force_N / t_N";
    }
    add(Channel::FrictionRatio, ratioName, ratio);
    std::vector<double> vel = columnOf(t, "rel_vel_mps");
    const char* velName = "rel_vel_mps";
    if (vel.empty()) {
        // Slider held fixed (prescribed slip): V = u̇.
        vel = columnOf(t, "stage_vel_mps");
        velName = "stage_vel_mps";
    }
    add(Channel::RelVel, velName, vel);
    add(Channel::Alpha, "state_alpha", columnOf(t, "state_alpha"));
    if (!ratio.empty() && vel.size() == ratio.size()) {
        MeasuredSeries s;
        s.label = QStringLiteral("measured: %1 vs %2").arg(QLatin1String(ratioName), QLatin1String(velName));
        s.x = vel;
        s.y = ratio;
        loop_->addMeasured(s);
    }
    if (n == 0 && error)
        *error = tr("%1: no column to overlay (expected stage_disp_m, slider_disp_m, friction_ratio, "
                    "friction_force_N, rel_vel_mps, stage_vel_mps or state_alpha)")
                     .arg(file);
    return n;
}

void ViewSet::clearMeasured() {
    // TimeSeriesPlot keeps its channel overlays until clearAll(); show the last run again.
    timeSeries_->clearAll();
    loop_->clearMeasured();
    if (lastRun_) showShared(lastRun_);
}

}  // namespace stickslip::gui
