// Latency of the live explorer: time from a parameter-slider value change to redrawn plots,
// driving the real MainWindow offscreen with the Fig. 20 preset (20 cycles, dt = T/10 000).
// 50 changes of the amplitude slider, one at a time (each waits for its redraw): prints the
// median and the 95th percentile, and the worker's compute time for comparison.
// Target (issue 4): median ≤ 50 ms, p95 ≤ 100 ms.
#include <QApplication>
#include <QElapsedTimer>
#include <QEventLoop>
#include <QSlider>
#include <QTimer>
#include <algorithm>
#include <cstdio>
#include <vector>

#include "main_window.hpp"
#include "parameter_panel.hpp"
#include "simulation_controller.hpp"
#include "view_set.hpp"
#include "widgets/friction_loop_plot.hpp"
#include "widgets/phase_portrait_plot.hpp"
#include "widgets/rig_view.hpp"
#include "widgets/time_series_plot.hpp"

using namespace stickslip::gui;

namespace {

double percentile(std::vector<double> v, double q) {
    std::sort(v.begin(), v.end());
    const double pos = q * (v.size() - 1);
    const size_t i = static_cast<size_t>(pos);
    const double f = pos - i;
    return i + 1 < v.size() ? v[i] * (1 - f) + v[i + 1] * f : v[i];
}

// Runs the event loop until the window shows a run, or the timeout.
bool waitForRun(MainWindow& w, RunOutcome* out, int timeout_ms) {
    QEventLoop loop;
    bool got = false;
    auto c = QObject::connect(&w, &MainWindow::runShown, &loop, [&](const RunOutcome& o) {
        got = true;
        if (out) *out = o;
        loop.quit();
    });
    QTimer::singleShot(timeout_ms, &loop, &QEventLoop::quit);
    loop.exec();
    QObject::disconnect(c);
    return got;
}

}  // namespace

int main(int argc, char** argv) {
    if (qEnvironmentVariableIsEmpty("QT_QPA_PLATFORM")) qputenv("QT_QPA_PLATFORM", "offscreen");
    QApplication app(argc, argv);
    const int changes = argc > 1 ? std::max(5, std::atoi(argv[1])) : 50;
    MainWindow w(/*restoreSettings=*/false);
    w.resize(1280, 800);
    w.show();
    if (!w.panel()->loadPreset("fig20") || !waitForRun(w, nullptr, 60000)) {
        std::fprintf(stderr, "bench_gui_latency: no first result\n");
        return 1;
    }
    // Let the start-up jobs (Poincaré section) finish so every change starts from idle.
    while (!w.controller()->isIdle()) QCoreApplication::processEvents(QEventLoop::WaitForMoreEvents);

    QSlider* slider = w.panel()->slider("A");   // 0–10 mm; Fig. 20 sits at 1 mm = position 100
    std::vector<double> latency, compute, guiSide;
    RunOutcome lastOutcome;
    for (int i = 0; i < changes; ++i) {
        const int pos = 80 + (i * 37) % 60;   // 0.8–1.4 mm; consecutive values always differ
        if (pos == slider->value()) continue;
        QElapsedTimer clock;
        clock.start();
        slider->setValue(pos);
        RunOutcome o;
        if (!waitForRun(w, &o, 60000)) {
            std::fprintf(stderr, "bench_gui_latency: change %d produced no result\n", i);
            return 1;
        }
        w.repaint();   // the plots and the rest of the window painted, synchronously
        latency.push_back(clock.nsecsElapsed() / 1e6);
        compute.push_back(o.elapsed_ms);
        lastOutcome = o;
        // The GUI side alone: hand the same outcome to the views again and repaint.
        QElapsedTimer gui;
        gui.start();
        w.views()->showRun(o);
        w.repaint();
        guiSide.push_back(gui.nsecsElapsed() / 1e6);
        // Next change from idle (the Poincaré job of this change may still be running).
        while (!w.controller()->isIdle()) QCoreApplication::processEvents(QEventLoop::WaitForMoreEvents);
    }
    std::printf("bench_gui_latency: Fig. 20 preset, 20 cycles, %zu slider changes (offscreen)\n", latency.size());
    std::printf("  slider change -> redrawn plots: median %.1f ms, p95 %.1f ms, max %.1f ms\n",
                percentile(latency, 0.5), percentile(latency, 0.95), *std::max_element(latency.begin(), latency.end()));
    std::printf("  of which the worker's run:       median %.1f ms, p95 %.1f ms\n", percentile(compute, 0.5),
                percentile(compute, 0.95));
    std::printf("  GUI side (views updated + window repainted): median %.1f ms, p95 %.1f ms\n",
                percentile(guiSide, 0.5), percentile(guiSide, 0.95));
    // Where the GUI side goes: each visible view fed the last outcome and repainted alone.
    {
        const RunOutcome& o = lastOutcome;
        const auto& run = o.runs.front().run;
        const double T = o.settings.params.drive.period();
        auto timeIt = [](const char* name, auto&& f, QWidget* wid) {
            std::vector<double> v;
            for (int k = 0; k < 5; ++k) {
                QElapsedTimer c;
                c.start();
                f();
                wid->repaint();
                v.push_back(c.nsecsElapsed() / 1e6);
            }
            std::printf("    %-16s median %.1f ms\n", name, percentile(v, 0.5));
        };
        std::printf("  per view (update + repaint):\n");
        auto* v = w.views();
        timeIt("time series", [&] { v->timeSeries()->setRun(run, T); }, v->timeSeries());
        timeIt("friction loop", [&] { v->frictionLoop()->setRun(run, T); }, v->frictionLoop());
        timeIt("phase portrait", [&] { v->phasePortrait()->setRun(run); }, v->phasePortrait());
        timeIt("rig", [&] { v->rig()->setRun(run, o.settings.params); }, v->rig());
        timeIt("whole window", [] {}, &w);
    }
    std::printf("  target: median <= 50 ms, p95 <= 100 ms -> %s\n",
                percentile(latency, 0.5) <= 50 && percentile(latency, 0.95) <= 100 ? "met" : "NOT met");
    return 0;
}
