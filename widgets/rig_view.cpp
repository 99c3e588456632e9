#include "rig_view.hpp"

#include "core/friction/friction_law.hpp"

#include <QComboBox>
#include <QDateTime>
#include <QHBoxLayout>
#include <QLabel>
#include <QFontMetricsF>
#include <QPainter>
#include <QPainterPath>
#include <QSlider>
#include <QTimer>
#include <QToolButton>
#include <QVBoxLayout>
#include <algorithm>
#include <cmath>

namespace stickslip::widgets {

// The drawing surface: a pure function of (sample, scale) painted on demand.
class RigCanvas : public QWidget {
public:
    explicit RigCanvas(QWidget* parent) : QWidget(parent) {
        setMinimumSize(420, 220);
        setSizePolicy(QSizePolicy::Expanding, QSizePolicy::Expanding);
    }
    void show(const Sample* s, double scale_m, double mu) {
        has_ = s != nullptr;
        if (s) sample_ = *s;
        scale_m_ = scale_m > 0 ? scale_m : 1e-3;
        mu_ = mu;
        update();
    }

protected:
    void paintEvent(QPaintEvent*) override;

private:
    // The STICK/SLIP label and the sample's values beside it, in the top line(s).
    void drawReadout(QPainter& p, const QColor& contact, bool stuck, const QPen& ink, double W);
    bool has_ = false;
    Sample sample_;
    double scale_m_ = 1e-3;   // displacement that maps to a quarter of the width
    double mu_ = 0.25;
};

namespace {

// Zig-zag spring between two points along x at height y.
void drawSpring(QPainter& p, double x0, double x1, double y, int coils, double amp) {
    QPainterPath path(QPointF(x0, y));
    const double lead = 0.12 * (x1 - x0);
    path.lineTo(x0 + lead, y);
    const double span = (x1 - x0) - 2 * lead;
    for (int i = 0; i < 2 * coils; ++i) {
        const double xx = x0 + lead + span * (i + 0.5) / (2 * coils);
        path.lineTo(xx, y + (i % 2 == 0 ? -amp : amp));
    }
    path.lineTo(x1 - lead, y);
    path.lineTo(x1, y);
    p.drawPath(path);
}

// Dashpot between x0 and x1 at height y.
void drawDamper(QPainter& p, double x0, double x1, double y, double h) {
    const double mid = 0.5 * (x0 + x1);
    p.drawLine(QPointF(x0, y), QPointF(mid - 6, y));
    p.drawLine(QPointF(mid - 10, y - h), QPointF(mid + 8, y - h));
    p.drawLine(QPointF(mid - 10, y + h), QPointF(mid + 8, y + h));
    p.drawLine(QPointF(mid - 10, y - h), QPointF(mid - 10, y + h));
    p.drawLine(QPointF(mid - 2, y - h + 2), QPointF(mid - 2, y + h - 2));
    p.drawLine(QPointF(mid - 2, y), QPointF(x1, y));
}

void drawArrow(QPainter& p, QPointF from, QPointF to) {
    p.drawLine(from, to);
    const QPointF d = to - from;
    const double len = std::hypot(d.x(), d.y());
    if (len < 1e-6) return;
    const QPointF u = d / len, n(-u.y(), u.x());
    const double a = std::min(8.0, 0.5 * len);
    QPolygonF head;
    head << to << to - a * u + 0.5 * a * n << to - a * u - 0.5 * a * n;
    p.setBrush(p.pen().color());
    p.drawPolygon(head);
    p.setBrush(Qt::NoBrush);
}

}  // namespace

void RigCanvas::paintEvent(QPaintEvent*) {
    QPainter p(this);
    p.setRenderHint(QPainter::Antialiasing, true);
    p.fillRect(rect(), Qt::white);
    const double W = width(), H = height();
    const double pxPerM = 0.22 * W / scale_m_;
    const double u = has_ ? sample_.stage_m : 0.0, x = has_ ? sample_.slider_m : 0.0;
    const bool stuck = has_ ? sample_.stuck : true;
    const QColor contact = stuck ? QColor(44, 160, 44) : QColor(214, 39, 40);

    const double groundX = 0.08 * W;
    const double blockW = 0.16 * W, blockH = 0.22 * H;
    const double centreX = 0.55 * W;
    const double stageTop = 0.62 * H, stageH = 0.08 * H;
    const double blockX = centreX + x * pxPerM - 0.5 * blockW;
    const double stageX = centreX + u * pxPerM;

    // Ground wall (hatched) on the left, and the floor under the stage rollers.
    QPen ink(QColor(40, 40, 40), 1.6);
    p.setPen(ink);
    p.drawLine(QPointF(groundX, stageTop - blockH - 0.08 * H), QPointF(groundX, stageTop - 0.02 * H));
    for (double y = stageTop - blockH - 0.08 * H; y < stageTop - 0.02 * H; y += 8)
        p.drawLine(QPointF(groundX, y), QPointF(groundX - 7, y + 7));
    const double floorY = stageTop + stageH + 12;
    p.drawLine(QPointF(0.05 * W, floorY), QPointF(0.97 * W, floorY));
    for (double xx = 0.05 * W; xx < 0.97 * W; xx += 10) p.drawLine(QPointF(xx, floorY), QPointF(xx - 7, floorY + 7));

    // Stage: a long platform on rollers, driven u(t) = A sin(ωt).
    const double stageW = 0.62 * W;
    QRectF stage(stageX - 0.5 * stageW, stageTop, stageW, stageH);
    p.setBrush(QColor(225, 225, 235));
    p.drawRect(stage);
    p.setBrush(Qt::NoBrush);
    for (double f : {0.15, 0.5, 0.85}) p.drawEllipse(QPointF(stage.left() + f * stageW, stageTop + stageH + 6), 5.5, 5.5);
    p.drawText(QRectF(stage.left(), stageTop, stageW, stageH), Qt::AlignCenter, QStringLiteral("stage  u = A sin ωt"));

    // Slider block with the spring k and damper c to the wall.
    QRectF block(blockX, stageTop - blockH, blockW, blockH);
    p.setBrush(QColor(200, 215, 235));
    p.drawRect(block);
    p.setBrush(Qt::NoBrush);
    // The label in the block's upper part: the friction arrow (below) runs through its middle.
    p.drawText(QRectF(block.left(), block.top(), blockW, 0.45 * blockH), Qt::AlignCenter, QStringLiteral("m*"));
    drawSpring(p, groundX, block.left(), stageTop - 0.7 * blockH, 7, 7);
    drawDamper(p, groundX, block.left(), stageTop - 0.28 * blockH, 6);
    p.drawText(QPointF(0.5 * (groundX + block.left()) - 4, stageTop - 0.7 * blockH - 12), QStringLiteral("k"));
    // Above the damper (below it the label would touch the stage's top edge).
    p.drawText(QPointF(0.5 * (groundX + block.left()) - 4, stageTop - 0.28 * blockH - 9), QStringLiteral("c"));

    // Normal load t_N pressing the block down.
    drawArrow(p, QPointF(block.center().x(), block.top() - 32), QPointF(block.center().x(), block.top() - 2));
    p.drawText(QPointF(block.center().x() + 6, block.top() - 18), QStringLiteral("t_N"));

    // The contact, coloured by stick (green) / slip (red), and the friction force on the
    // slider as an arrow scaled by (F/t_N)/μ.
    p.setPen(QPen(contact, 5, Qt::SolidLine, Qt::FlatCap));
    p.drawLine(QPointF(block.left(), stageTop), QPointF(block.right(), stageTop));
    if (has_) {
        const double len = std::clamp(sample_.ratio / std::max(mu_, 1e-6), -2.0, 2.0) * 0.4 * blockW;
        p.setPen(QPen(contact, 2.2));
        const QPointF base(block.center().x(), stageTop - 0.5 * blockH);
        if (std::abs(len) > 1.5) drawArrow(p, base, base + QPointF(len, 0));
    }

    drawReadout(p, contact, stuck, ink, W);
    // Scale bar.
    const double bar = scale_m_ * pxPerM;
    const double by = H - 8;
    p.drawLine(QPointF(0.05 * W, by), QPointF(0.05 * W + bar, by));
    p.drawText(QPointF(0.05 * W + bar + 6, by + 4), QStringLiteral("%1 mm (displacements magnified)").arg(scale_m_ * 1e3, 0, 'g', 3));
}

void RigCanvas::drawReadout(QPainter& p, const QColor& contact, bool stuck, const QPen& ink, double W) {
    p.setPen(ink);
    QFont f = font();
    f.setBold(true);
    p.setFont(f);
    p.setPen(contact);
    const QString state = has_ ? (stuck ? QStringLiteral("STICK") : QStringLiteral("SLIP")) : QStringLiteral("no run");
    p.drawText(QRectF(0.05 * W, 6, 0.9 * W, 20), Qt::AlignLeft | Qt::AlignVCenter, state);
    const double stateRight = 0.05 * W + QFontMetricsF(f).horizontalAdvance(QStringLiteral("STICK")) + 12;
    p.setFont(font());
    p.setPen(ink);
    if (has_) {
        const QStringList items = {QStringLiteral("t = %1 s").arg(sample_.t_s, 0, 'f', 3),
                                   QStringLiteral("u = %1 mm").arg(sample_.stage_m * 1e3, 0, 'f', 3),
                                   QStringLiteral("x = %1 mm").arg(sample_.slider_m * 1e3, 0, 'f', 3),
                                   QStringLiteral("V = %1 m/s").arg(sample_.relVel_mps, 0, 'f', 4),
                                   QStringLiteral("F/t_N = %1").arg(sample_.ratio, 0, 'f', 3)};
        // As many items per line as fit right of the STICK/SLIP label (a narrow view gets more
        // lines instead of text running under the label).
        const QRectF line(stateRight, 6, 0.98 * W - stateRight, 20);
        const QFontMetricsF fm(font());
        const QString gap = QStringLiteral("   ");
        QStringList lines;
        for (const QString& item : items) {
            if (!lines.isEmpty() && fm.horizontalAdvance(lines.back() + gap + item) <= line.width()) lines.back() += gap + item;
            else lines << item;
        }
        for (int i = 0; i < lines.size(); ++i)
            p.drawText(line.translated(0, 18 * i), Qt::AlignRight | Qt::AlignVCenter, lines[i]);
    }
}

RigView::RigView(QWidget* parent) : QWidget(parent) {
    canvas_ = new RigCanvas(this);
    playButton_ = new QToolButton(this);
    playButton_->setCheckable(true);
    playButton_->setText(QStringLiteral("Play"));
    playButton_->setToolTip(QStringLiteral("Play / pause the animation (Space)"));
    playButton_->setShortcut(Qt::Key_Space);
    speedBox_ = new QComboBox(this);
    for (double s : {0.02, 0.05, 0.1, 0.2, 0.5, 1.0})
        speedBox_->addItem(QStringLiteral("%1× real time").arg(s), s);
    speedBox_->setCurrentIndex(2);
    speedBox_->setToolTip(QStringLiteral("Simulated seconds per wall-clock second"));
    timeSlider_ = new QSlider(Qt::Horizontal, this);
    timeSlider_->setRange(0, 1000);
    timeLabel_ = new QLabel(this);
    timeLabel_->setMinimumWidth(90);

    auto* controls = new QHBoxLayout;
    controls->addWidget(playButton_);
    controls->addWidget(speedBox_);
    controls->addWidget(timeSlider_, 1);
    controls->addWidget(timeLabel_);
    auto* layout = new QVBoxLayout(this);
    layout->addWidget(canvas_, 1);
    layout->addLayout(controls);

    timer_ = new QTimer(this);
    timer_->setInterval(30);
    connect(timer_, &QTimer::timeout, this, &RigView::tick);
    connect(playButton_, &QToolButton::toggled, this, &RigView::setPlaying);
    connect(speedBox_, qOverload<int>(&QComboBox::currentIndexChanged), this,
            [this](int i) { setSpeed(speedBox_->itemData(i).toDouble()); });
    connect(timeSlider_, &QSlider::sliderMoved, this, [this](int pos) {
        if (run_.samples.empty()) return;
        const double t0 = run_.samples.front().t_s, t1 = run_.samples.back().t_s;
        setTime(t0 + (t1 - t0) * pos / 1000.0);
    });
    syncControls();
}

void RigView::setRun(const RunResult& run, const SimParams& params) {
    run_ = run;
    params_ = params;
    time_s_ = run_.samples.empty() ? 0.0 : run_.samples.front().t_s;
    // Scale: the larger of the stage amplitude and the largest excursion in the run.
    scale_m_ = std::abs(params_.drive.amplitude_m);
    for (const auto& x : run_.samples) scale_m_ = std::max({scale_m_, std::abs(x.slider_m), std::abs(x.stage_m)});
    if (!(scale_m_ > 0)) scale_m_ = 1e-3;
    syncControls();
    emit timeChanged(time_s_);
}

void RigView::clear() {
    pause();
    run_ = RunResult{};
    syncControls();
}

bool RigView::isPlaying() const { return timer_->isActive(); }

bool RigView::currentSample(Sample& out) const {
    const auto& s = run_.samples;
    if (s.empty()) return false;
    auto it = std::upper_bound(s.begin(), s.end(), time_s_, [](double t, const Sample& x) { return t < x.t_s; });
    out = it == s.begin() ? *it : *(it - 1);
    return true;
}

void RigView::play() { setPlaying(true); }
void RigView::pause() { setPlaying(false); }

void RigView::setPlaying(bool playing) {
    if (playing == isPlaying()) return;
    if (playing && run_.samples.empty()) playing = false;
    if (playing) {
        lastTickMs_ = QDateTime::currentMSecsSinceEpoch();
        timer_->start();
    } else {
        timer_->stop();
    }
    syncControls();
    emit playingChanged(playing);
}

void RigView::setSpeed(double simSecondsPerSecond) {
    if (!(simSecondsPerSecond > 0)) return;
    speed_ = simSecondsPerSecond;
    syncControls();
}

void RigView::setTime(double t_s) {
    if (!run_.samples.empty()) {
        t_s = std::clamp(t_s, run_.samples.front().t_s, run_.samples.back().t_s);
    }
    time_s_ = t_s;
    syncControls();
    emit timeChanged(time_s_);
}

// Advance by wall time × speed; loop back to the start at the end of the run.
void RigView::tick() {
    if (run_.samples.empty()) return pause();
    const qint64 now = QDateTime::currentMSecsSinceEpoch();
    const double dt = std::clamp((now - lastTickMs_) / 1000.0, 0.0, 0.2);
    lastTickMs_ = now;
    double t = time_s_ + dt * speed_;
    if (t > run_.samples.back().t_s) t = run_.samples.front().t_s;
    setTime(t);
}

void RigView::syncControls() {
    const QSignalBlocker b1(playButton_), b2(speedBox_), b3(timeSlider_);
    playButton_->setChecked(isPlaying());
    playButton_->setText(isPlaying() ? QStringLiteral("Pause") : QStringLiteral("Play"));
    playButton_->setEnabled(!run_.samples.empty());
    for (int i = 0; i < speedBox_->count(); ++i)
        if (std::abs(speedBox_->itemData(i).toDouble() - speed_) < 1e-12) speedBox_->setCurrentIndex(i);
    Sample s;
    const bool has = currentSample(s);
    if (has) {
        const double t0 = run_.samples.front().t_s, t1 = run_.samples.back().t_s;
        timeSlider_->setValue(t1 > t0 ? static_cast<int>(std::lround(1000.0 * (time_s_ - t0) / (t1 - t0))) : 0);
    }
    timeLabel_->setText(has ? QStringLiteral("t = %1 s").arg(time_s_, 0, 'f', 3) : QString());
    const double mu = lawMu(params_);
    canvas_->show(has ? &s : nullptr, scale_m_, mu);
}

}  // namespace stickslip::widgets
