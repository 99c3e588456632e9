#include "import_cleaning_page.hpp"

#include <QCheckBox>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QFileInfo>
#include <QFormLayout>
#include <QGroupBox>
#include <QHBoxLayout>
#include <QLabel>
#include <QSpinBox>
#include <QTimer>
#include <QVBoxLayout>
#include <QtConcurrent/QtConcurrentRun>
#include <algorithm>

#include "import_signals.hpp"
#include "widgets/signal_compare_plot.hpp"

namespace stickslip::gui {

namespace {

// How a signal is shown in the plot: SI times factor, with the unit text.
std::pair<double, QString> displayUnit(io::Signal s) {
    const QString si = QString::fromLatin1(io::signalUnit(s));
    if (si == QLatin1String("m")) return {1e3, QStringLiteral("mm")};
    if (si == QLatin1String("m/s")) return {1e3, QStringLiteral("mm/s")};
    if (si == QLatin1String("m/s^2")) return {1.0, QStringLiteral("m/s\u00b2")};
    return {1.0, si};
}

QString signalTitle(io::Signal s) {
    const SignalInfo& r = rowOf(s);
    return QStringLiteral("%1 %2").arg(QString::fromUtf8(r.label).toLower(), QString::fromUtf8(r.symbol));
}

QDoubleSpinBox* doubleBox(double lo, double hi, int decimals, const QString& suffix) {
    auto* b = new QDoubleSpinBox;
    b->setRange(lo, hi);
    b->setDecimals(decimals);
    b->setSuffix(suffix);
    b->setStepType(QAbstractSpinBox::AdaptiveDecimalStepType);
    b->setAlignment(Qt::AlignRight);
    return b;
}

QSpinBox* intBox(int lo, int hi, const QString& suffix = QString()) {
    auto* b = new QSpinBox;
    b->setRange(lo, hi);
    b->setSuffix(suffix);
    b->setAlignment(Qt::AlignRight);
    return b;
}

}  // namespace

ImportCleaningPage::ImportCleaningPage(QWidget* parent) : QWidget(parent) {
    timer_ = new QTimer(this);
    timer_->setSingleShot(true);
    timer_->setInterval(120);
    connect(timer_, &QTimer::timeout, this, &ImportCleaningPage::start);
    connect(&watcher_, &QFutureWatcher<CleaningPreview>::finished, this, &ImportCleaningPage::onFinished);
    auto* layout = new QHBoxLayout(this);
    layout->addWidget(buildSettings(), 0);
    layout->addWidget(buildPlotBox(), 1);
}

ImportCleaningPage::~ImportCleaningPage() {
    // The job holds copies of its inputs only; wait so it does not outlive the page.
    watcher_.waitForFinished();
}

// --- settings ----------------------------------------------------------------------------------

QWidget* ImportCleaningPage::buildSettings() {
    auto* settings = new QWidget;
    auto* sl = new QVBoxLayout(settings);
    sl->setContentsMargins(0, 0, 0, 0);
    sl->addWidget(buildBandBox());
    sl->addWidget(buildLowPassBox());
    sl->addWidget(buildDerivativeBox());
    sl->addWidget(buildTrimBox());
    sl->addStretch(1);
    settings->setMaximumWidth(330);
    auto changed = [this] {
        if (!populating_) emit settingsChanged();
    };
    for (QCheckBox* c : {bandStop_, lowPass_, steadyTrim_, resample_, fuseAccel_}) connect(c, &QCheckBox::toggled, this, changed);
    for (QDoubleSpinBox* b : {bandCenter_, bandWidth_, lowPassHz_, trimStart_, trimEnd_, trimFraction_})
        connect(b, QOverload<double>::of(&QDoubleSpinBox::valueChanged), this, changed);
    for (QSpinBox* b : {bandOrder_, lowPassOrder_, sgHalf_, sgOrder_, stageHarmonics_})
        connect(b, QOverload<int>::of(&QSpinBox::valueChanged), this, changed);
    return settings;
}

QWidget* ImportCleaningPage::buildBandBox() {
    auto* band = new QGroupBox(tr("Mains band-stop (zero-phase)"));
    auto* bf = new QFormLayout(band);
    bandStop_ = new QCheckBox(tr("On"));
    bandCenter_ = doubleBox(0.1, 1e5, 1, tr(" Hz"));
    bandWidth_ = doubleBox(0.1, 1e4, 1, tr(" Hz"));
    bandOrder_ = intBox(1, 10);
    bandOrder_->setToolTip(tr("Prototype order; the band-stop has twice as many poles and is applied forward and backward"));
    bf->addRow(bandStop_);
    bf->addRow(tr("Centre:"), bandCenter_);
    bf->addRow(tr("Width (\u22123 dB):"), bandWidth_);
    bf->addRow(tr("Order:"), bandOrder_);
    return band;
}

QWidget* ImportCleaningPage::buildLowPassBox() {
    auto* low = new QGroupBox(tr("Butterworth low-pass (zero-phase)"));
    auto* lf = new QFormLayout(low);
    lowPass_ = new QCheckBox(tr("On"));
    lowPassHz_ = doubleBox(0.01, 1e5, 1, tr(" Hz"));
    lowPassOrder_ = intBox(1, 12);
    lf->addRow(lowPass_);
    lf->addRow(tr("Cut-off:"), lowPassHz_);
    lf->addRow(tr("Order:"), lowPassOrder_);
    return low;
}

QWidget* ImportCleaningPage::buildDerivativeBox() {
    auto* deriv = new QGroupBox(tr("Velocities and input"));
    auto* df = new QFormLayout(deriv);
    sgHalf_ = intBox(1, 500, tr(" samples"));
    sgHalf_->setToolTip(tr("Savitzky\u2013Golay half window: the window is 2\u00b7h+1 samples"));
    sgOrder_ = intBox(1, 20);
    stageHarmonics_ = intBox(0, 50);
    stageHarmonics_->setToolTip(tr("Dynamics runs: the stage displacement driving the model is replaced by its "
                                   "Fourier fit with this many harmonics (0: the filtered measurement)"));
    resample_ = new QCheckBox(tr("Resample irregular time steps"));
    fuseAccel_ = new QCheckBox(tr("Fuse slider x with acceleration"));
    fuseAccel_->setToolTip(tr("Dynamics runs with a slider acceleration: the slider's displacement and velocity "
                              "come from a Rauch\u2013Tung\u2013Striebel smoother of x'' = a (noise levels "
                              "estimated per run; see the status line's notes). The position's noise, "
                              "differentiated into the slip rate, otherwise biases the law's C1, \u03b7, v_c"));
    df->addRow(tr("SG half window:"), sgHalf_);
    df->addRow(tr("SG order:"), sgOrder_);
    df->addRow(tr("Stage harmonics:"), stageHarmonics_);
    df->addRow(resample_);
    df->addRow(fuseAccel_);
    return deriv;
}

QWidget* ImportCleaningPage::buildTrimBox() {
    auto* trim = new QGroupBox(tr("Trimming"));
    auto* tf = new QFormLayout(trim);
    trimStart_ = doubleBox(0, 1e5, 3, tr(" s"));
    trimEnd_ = doubleBox(0, 1e5, 3, tr(" s"));
    steadyTrim_ = new QCheckBox(tr("Keep steady drive amplitude only"));
    trimFraction_ = doubleBox(0.01, 1.0, 2, QString());
    trimFraction_->setToolTip(tr("Steady: moving amplitude at least this fraction of its maximum (drops ramps)"));
    tf->addRow(tr("Drop at start:"), trimStart_);
    tf->addRow(tr("Drop at end:"), trimEnd_);
    tf->addRow(steadyTrim_);
    tf->addRow(tr("Amplitude fraction:"), trimFraction_);
    return trim;
}

QWidget* ImportCleaningPage::buildPlotBox() {
    auto* plotBox = new QGroupBox(tr("Raw and cleaned"));
    auto* pl = new QVBoxLayout(plotBox);
    auto* pick = new QHBoxLayout;
    plotSignal_ = new QComboBox;
    plotSignal_->setSizeAdjustPolicy(QComboBox::AdjustToContents);
    detail_ = new QCheckBox(tr("Show 3 drive periods"));
    detail_->setChecked(true);
    detail_->setToolTip(tr("Zoom to three drive periods in the middle of the fit window (all samples stay "
                           "plotted; zoom out with the right mouse button)"));
    pick->addWidget(new QLabel(tr("Signal:")));
    pick->addWidget(plotSignal_);
    pick->addSpacing(12);
    pick->addWidget(detail_);
    pick->addStretch(1);
    connect(detail_, &QCheckBox::toggled, this, [this](bool) { showCleaning(); });
    status_ = new QLabel;
    status_->setWordWrap(true);
    plot_ = new widgets::SignalComparePlot;
    plot_->setMinimumSize(420, 300);
    pl->addLayout(pick);
    pl->addWidget(plot_, 1);
    pl->addWidget(status_);
    connect(plotSignal_, QOverload<int>::of(&QComboBox::currentIndexChanged), this, [this](int) {
        if (!populating_) showCleaning();
    });
    return plotBox;
}

identify::PreprocessSettings ImportCleaningPage::settings() const {
    identify::PreprocessSettings s;
    s.filters.bandStop = bandStop_->isChecked();
    s.filters.bandStopCenter_Hz = bandCenter_->value();
    s.filters.bandStopWidth_Hz = bandWidth_->value();
    s.filters.bandStopOrder = bandOrder_->value();
    s.filters.lowPass = lowPass_->isChecked();
    s.filters.lowPass_Hz = lowPassHz_->value();
    s.filters.lowPassOrder = lowPassOrder_->value();
    s.resample = resample_->isChecked();
    s.sgHalfWindow = sgHalf_->value();
    s.sgOrder = sgOrder_->value();
    s.stageFourierOrder = stageHarmonics_->value();
    s.fuseSliderAcceleration = fuseAccel_->isChecked();
    s.trim.start_s = trimStart_->value();
    s.trim.end_s = trimEnd_->value();
    s.trim.steadyAmplitude = steadyTrim_->isChecked();
    s.trim.amplitudeFraction = trimFraction_->value();
    return s;
}

void ImportCleaningPage::setSettings(const identify::PreprocessSettings& s) {
    populating_ = true;
    bandStop_->setChecked(s.filters.bandStop);
    bandCenter_->setValue(s.filters.bandStopCenter_Hz);
    bandWidth_->setValue(s.filters.bandStopWidth_Hz);
    bandOrder_->setValue(s.filters.bandStopOrder);
    lowPass_->setChecked(s.filters.lowPass);
    lowPassHz_->setValue(s.filters.lowPass_Hz);
    lowPassOrder_->setValue(s.filters.lowPassOrder);
    resample_->setChecked(s.resample);
    sgHalf_->setValue(s.sgHalfWindow);
    sgOrder_->setValue(s.sgOrder);
    stageHarmonics_->setValue(s.stageFourierOrder);
    fuseAccel_->setChecked(s.fuseSliderAcceleration);
    trimStart_->setValue(s.trim.start_s);
    trimEnd_->setValue(s.trim.end_s);
    steadyTrim_->setChecked(s.trim.steadyAmplitude);
    trimFraction_->setValue(s.trim.amplitudeFraction);
    populating_ = false;
}

void ImportCleaningPage::updateEnabledStates() {
    for (QWidget* w : std::initializer_list<QWidget*>{bandCenter_, bandWidth_, bandOrder_}) w->setEnabled(bandStop_->isChecked());
    for (QWidget* w : std::initializer_list<QWidget*>{lowPassHz_, lowPassOrder_}) w->setEnabled(lowPass_->isChecked());
    trimFraction_->setEnabled(steadyTrim_->isChecked());
}

// --- the cleaning job ------------------------------------------------------------------------

void ImportCleaningPage::schedule() { timer_->start(); }

bool ImportCleaningPage::isBusy() const { return running_ || timer_->isActive() || pending_; }

void ImportCleaningPage::start() {
    if (running_) {
        pending_ = true;
        return;
    }
    pending_ = false;
    const Source src = source_ ? source_() : Source{};
    ++generation_;
    if (!src.ready) {
        cleaning_ = CleaningPreview{};
        cleaning_.generation = generation_;
        plot_->clearAll();
        status_->setText(src.haveFile ? tr("Fix the problem below to see the cleaned signals.") : QString());
        emit cleaningUpdated();
        return;
    }
    status_->setText(tr("Cleaning %1\u2026").arg(QFileInfo(src.file).fileName()));
    const quint64 gen = generation_;
    watcher_.setFuture(QtConcurrent::run([gen, file = src.file, opts = src.options, settings = settings()] {
        CleaningPreview r = computeCleaningPreview(file, opts, settings);
        r.generation = gen;
        return r;
    }));
    running_ = true;
}

void ImportCleaningPage::onFinished() {
    CleaningPreview r = watcher_.result();
    running_ = false;
    if (pending_ || timer_->isActive() || r.generation != generation_) {
        if (pending_) start();  // stale: settings changed meanwhile
        return;
    }
    cleaning_ = std::move(r);
    fillSignalChoices();
    showCleaning();
    emit cleaningUpdated();
}

// The signals to choose from: those of the cleaned run (derived ones included).
void ImportCleaningPage::fillSignalChoices() {
    const QVariant keep = plotSignal_->currentData();
    populating_ = true;
    plotSignal_->clear();
    if (cleaning_.ok) {
        for (const SignalInfo& row : signalRows()) {
            if (row.signal == io::Signal::Time || !cleaning_.clean.run.has(row.signal)) continue;
            const QString derived = cleaning_.raw.has(row.signal) ? QString() : tr(" (derived)");
            plotSignal_->addItem(QString::fromUtf8(row.label) + derived, static_cast<int>(row.signal));
        }
        int at = plotSignal_->findData(keep);
        if (at < 0) at = plotSignal_->findData(static_cast<int>(io::Signal::Friction));
        plotSignal_->setCurrentIndex(std::max(at, 0));
    }
    populating_ = false;
}

void ImportCleaningPage::setPlotSignal(io::Signal s) {
    const int at = plotSignal_->findData(static_cast<int>(s));
    if (at >= 0) plotSignal_->setCurrentIndex(at);
}

void ImportCleaningPage::showCleaning() {
    if (!cleaning_.ok) {
        plot_->clearAll();
        status_->setStyleSheet(QStringLiteral("QLabel { color: #b26b00; }"));
        status_->setText(cleaning_.error.isEmpty() ? QString() : tr("Cannot clean this run: %1").arg(cleaning_.error));
        return;
    }
    if (plotSignal_->currentIndex() < 0) return;
    const auto s = static_cast<io::Signal>(plotSignal_->currentData().toInt());
    const identify::CleanRun& c = cleaning_.clean;
    widgets::SignalComparison cmp;
    const auto [factor, unitText] = displayUnit(s);
    cmp.signalTitle = QStringLiteral("%1 [%2]").arg(signalTitle(s), unitText);
    cmp.displayFactor = factor;
    if (cleaning_.raw.has(s)) {
        cmp.rawTime_s = cleaning_.raw[io::Signal::Time];
        cmp.raw = cleaning_.raw[s];
    }
    cmp.cleanTime_s = c.run[io::Signal::Time];
    cmp.clean = c.run[s];
    if (c.end > c.begin && c.end <= cmp.cleanTime_s.size()) {
        cmp.windowBegin_s = cmp.cleanTime_s[c.begin];
        cmp.windowEnd_s = cmp.cleanTime_s[c.end - 1];
    }
    plot_->setComparison(cmp);
    if (detail_->isChecked() && c.period_s > 0 && cmp.windowEnd_s - cmp.windowBegin_s > 3 * c.period_s) {
        const double mid = 0.5 * (cmp.windowBegin_s + cmp.windowEnd_s);
        plot_->showTimeRange(mid - 1.5 * c.period_s, mid + 1.5 * c.period_s);
    }
    showStatus(cmp.windowBegin_s, cmp.windowEnd_s);
}

void ImportCleaningPage::showStatus(double windowBegin_s, double windowEnd_s) {
    const identify::CleanRun& c = cleaning_.clean;
    status_->setStyleSheet(QStringLiteral("QLabel { color: palette(dark); }"));
    QString status = tr("%1: step %2 ms%3, fit window %4\u2013%5 s (%6 of %7 samples)")
                         .arg(cleaning_.raw.name().c_str())
                         .arg(c.dt_s * 1e3, 0, 'g', 4)
                         .arg(c.resampled ? tr(" (resampled)") : QString())
                         .arg(windowBegin_s, 0, 'f', 3)
                         .arg(windowEnd_s, 0, 'f', 3)
                         .arg(c.end - c.begin)
                         .arg(c.run.size());
    if (c.period_s > 0) status += tr(", drive period %1 s").arg(c.period_s, 0, 'g', 5);
    status_->setText(status);
    QString notes;
    for (const std::string& n : c.notes) notes += (notes.isEmpty() ? "" : "\n") + QString::fromStdString(n);
    status_->setToolTip(notes);
}

}  // namespace stickslip::gui
