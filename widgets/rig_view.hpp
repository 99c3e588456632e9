// Teaching view: an animated schematic of the rig (paper Fig. 15b) — the harmonically driven
// stage, the slider on it held by the beam spring k (and damper c) to the ground, and the
// contact between them, coloured green while stuck and red while slipping. Play, pause and
// speed controls; emits the current time so a TimeSeriesPlot cursor can follow.
#pragma once

#include <QWidget>

#include "core/integrate/run_result.hpp"
#include "core/params.hpp"

class QTimer;
class QToolButton;
class QComboBox;
class QSlider;
class QLabel;

namespace stickslip::widgets {

class RigCanvas;

class RigView : public QWidget {
    Q_OBJECT
public:
    explicit RigView(QWidget* parent = nullptr);

    // The run to animate (its samples) and the parameters it came from (A, k, t_N).
    void setRun(const RunResult& run, const SimParams& params);
    void clear();

    double currentTime() const { return time_s_; }
    double speed() const { return speed_; }   // simulated seconds per wall second
    bool isPlaying() const;
    // The sample shown at the current time (nearest not after it); false if there is no run.
    bool currentSample(Sample& out) const;

public slots:
    void play();
    void pause();
    void setPlaying(bool playing);
    void setSpeed(double simSecondsPerSecond);   // e.g. 0.05 … 1
    void setTime(double t_s);                    // jumps; emits timeChanged

signals:
    void timeChanged(double t_s);
    void playingChanged(bool playing);

private:
    void tick();
    void syncControls();
    RunResult run_;
    SimParams params_;
    double time_s_ = 0.0;
    double speed_ = 0.1;
    double scale_m_ = 1e-3;   // displacement drawn as a quarter of the width [m]
    QTimer* timer_ = nullptr;
    RigCanvas* canvas_ = nullptr;
    QToolButton* playButton_ = nullptr;
    QComboBox* speedBox_ = nullptr;
    QSlider* timeSlider_ = nullptr;
    QLabel* timeLabel_ = nullptr;
    qint64 lastTickMs_ = 0;
};

}  // namespace stickslip::widgets
