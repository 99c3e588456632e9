#include "identify_panel.hpp"

#include "self_test_view.hpp"

#include <QCheckBox>
#include <QComboBox>
#include <QDir>
#include <QDoubleSpinBox>
#include <QDragEnterEvent>
#include <QDropEvent>
#include <QFileDialog>
#include <QFileInfo>
#include <QFormLayout>
#include <QGridLayout>
#include <QGroupBox>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QLabel>
#include <QListWidget>
#include <QMimeData>
#include <QProgressBar>
#include <QPushButton>
#include <QSaveFile>
#include <QScrollArea>
#include <QScrollBar>
#include <QSpinBox>
#include <QSplitter>
#include <QTabWidget>
#include <QTableWidget>
#include <QVBoxLayout>
#include <algorithm>
#include <cmath>

#include "core/identify/effects/registry.hpp"
#include "core/identify/report_html.hpp"
#include "import_dialog.hpp"
#include "widgets/series_plot.hpp"

namespace stickslip::gui {

using namespace stickslip::identify;
using io::Signal;

QString formatEstimate(double value, double se) {
    QString s = QString::number(value, 'g', 4);
    if (se == 0.0) return s;
    if (!std::isfinite(se)) return s + QStringLiteral(" ± n/a");
    return s + QStringLiteral(" ± ") + QString::number(se, 'g', 2);
}

QString formatNrmse(double v) { return std::isfinite(v) ? QString::number(v, 'f', 4) : QStringLiteral("–"); }

namespace {

const char* kFitParams[] = {"mu", "C1", "eta", "Dc", "vc", "epsT", "r", "m", "zeta"};
const char* kLawParams[] = {"mu", "C1", "eta", "Dc", "vc", "epsT", "r"};

QString paramTitle(const std::string& n) {
    static const std::map<std::string, QString> t = {
        {"mu", "μ"}, {"C1", "C₁"}, {"eta", "η [s/m]"}, {"Dc", "D_c [m]"}, {"vc", "v_c [m/s]"}, {"epsT", "ε_T [N/m]"},
        {"r", "r"}, {"m", "m [kg]"}, {"zeta", "ζ"}, {"c", "c [N s/m]"}, {"k", "k [N/m]"}};
    auto it = t.find(n);
    return it != t.end() ? it->second : QString::fromStdString(n);
}

QTableWidget* makeTable(const QStringList& headers, QWidget* parent) {
    auto* t = new QTableWidget(0, headers.size(), parent);
    t->setHorizontalHeaderLabels(headers);
    t->verticalHeader()->setVisible(false);
    t->verticalHeader()->setDefaultSectionSize(22);
    t->setEditTriggers(QAbstractItemView::NoEditTriggers);
    t->setSelectionBehavior(QAbstractItemView::SelectRows);
    t->setAlternatingRowColors(true);
    t->horizontalHeader()->setStretchLastSection(true);
    t->horizontalHeader()->setHighlightSections(false);
    t->setWordWrap(false);
    return t;
}

void setCell(QTableWidget* t, int row, int col, const QString& text, const QString& tip = {}) {
    auto* item = new QTableWidgetItem(text);
    if (!tip.isEmpty()) item->setToolTip(tip);
    if (col > 0) item->setTextAlignment(Qt::AlignRight | Qt::AlignVCenter);
    t->setItem(row, col, item);
}

// Height that shows `rows` rows without a scroll bar (tables sit in a scrolling column).
void fitHeight(QTableWidget* t, int minRows = 2) {
    const int rows = std::max(t->rowCount(), minRows);
    int h = t->horizontalHeader()->height() + 2 * t->frameWidth() + 2;
    for (int r = 0; r < t->rowCount(); ++r) h += t->rowHeight(r);
    h += (rows - t->rowCount()) * t->verticalHeader()->defaultSectionSize();
    t->setMinimumHeight(std::min(h, 320));
    t->setMaximumHeight(std::min(h, 320));
}

QWidget* scrolled(QWidget* content) {
    auto* s = new QScrollArea;
    s->setWidget(content);
    s->setWidgetResizable(true);
    s->setFrameShape(QFrame::NoFrame);
    s->setHorizontalScrollBarPolicy(Qt::ScrollBarAlwaysOff);
    return s;
}

QString lawName(LawKind law) { return law == LawKind::Coulomb ? QStringLiteral("Coulomb") : QStringLiteral("rate-state"); }

const QColor kMeasured(40, 40, 40), kRate(31, 119, 180), kCoulomb(255, 127, 14), kBefore(214, 39, 40),
    kAfter(44, 160, 44);

bool writeAtomically(const QString& path, const QByteArray& bytes, QString* error) {
    QSaveFile f(path);
    if (!f.open(QIODevice::WriteOnly) || f.write(bytes) != bytes.size() || !f.commit()) {
        if (error) *error = QStringLiteral("%1: %2").arg(path, f.errorString());
        return false;
    }
    return true;
}

}  // namespace

IdentifyPanel::IdentifyPanel(QWidget* parent) : QWidget(parent) {
    setObjectName("identifyPanel");
    setAcceptDrops(true);
    worker_ = new IdentifyWorker(this);
    controls_ = new QTabWidget(this);
    controls_->addTab(scrolled(buildDataTab()), tr("Data"));
    controls_->addTab(scrolled(buildFitTab()), tr("Fit"));
    controls_->addTab(scrolled(buildIdentifyTab()), tr("Identify"));
    // At least as wide as the widest tab's content needs (the scroll areas do not scroll
    // sideways): at 1680 px with both docks open a 430 px minimum clipped the Fit tab's rows and
    // the wrapped identifiability line (seen in a screenshot).
    int need = 430;
    for (int i = 0; i < controls_->count(); ++i)
        if (auto* sa = qobject_cast<QScrollArea*>(controls_->widget(i)); sa && sa->widget())
            need = std::max(need, sa->widget()->minimumSizeHint().width() + sa->verticalScrollBar()->sizeHint().width() + 12);
    controls_->setMinimumWidth(need);
    auto* split = new QSplitter(Qt::Horizontal, this);
    split->addWidget(controls_);
    split->addWidget(buildPlots());
    split->setStretchFactor(0, 0);
    split->setStretchFactor(1, 1);
    split->setChildrenCollapsible(false);
    auto* top = new QVBoxLayout(this);
    top->setContentsMargins(4, 4, 4, 4);
    top->addWidget(split);

    connect(worker_, &IdentifyWorker::progress, this, &IdentifyPanel::onProgress);
    connect(worker_, &IdentifyWorker::fitFinished, this, &IdentifyPanel::onFitFinished);
    connect(worker_, &IdentifyWorker::identifyFinished, this, &IdentifyPanel::onIdentifyFinished);
    refreshRunTable();
}

IdentifyPanel::~IdentifyPanel() = default;

// --- Data --------------------------------------------------------------------------------

QWidget* IdentifyPanel::buildDataTab() {
    auto* w = new QWidget;
    auto* v = new QVBoxLayout(w);
    auto* buttons = new QHBoxLayout;
    auto* load = new QPushButton(tr("Load runs…"), w);
    load->setToolTip(tr("Open measured runs (CSV); they are fitted jointly. A manifest.json next to them is used."));
    auto* clear = new QPushButton(tr("Clear"), w);
    buttons->addWidget(load);
    buttons->addWidget(clear);
    buttons->addStretch(1);
    v->addLayout(buttons);
    auto* hint = new QLabel(tr("Drop CSV files here, or load them. Tick <i>validation</i> to hold a run out of the fit."), w);
    hint->setWordWrap(true);
    hint->setStyleSheet("color: #555;");
    v->addWidget(hint);
    runTable_ = makeTable({tr("Run"), tr("Samples"), tr("Length [s]"), tr("t_N [N]"), tr("f [Hz]"), tr("Validation")}, w);
    runTable_->horizontalHeader()->setSectionResizeMode(0, QHeaderView::Stretch);
    runTable_->horizontalHeader()->setStretchLastSection(false);
    v->addWidget(runTable_);
    dataSummary_ = new QLabel(w);
    dataSummary_->setWordWrap(true);
    v->addWidget(dataSummary_);

    auto* form = new QFormLayout;
    setupBox_ = new QComboBox(w);
    setupBox_->addItem(tr("prescribed slip (slip in, force out)"), int(SetupKind::Prescribed));
    setupBox_->addItem(tr("dynamics (stage in, slider and force out)"), int(SetupKind::Dynamics));
    form->addRow(tr("Set-up"), setupBox_);
    v->addLayout(form);

    auto* pre = new QGroupBox(tr("Preprocessing (as the paper)"), w);
    auto* pg = new QGridLayout(pre);
    bandStop_ = new QCheckBox(tr("60 Hz band-stop"), pre);
    bandStop_->setChecked(true);
    lowPass_ = new QCheckBox(tr("low-pass"), pre);
    lowPass_->setChecked(true);
    lowPassHz_ = new QDoubleSpinBox(pre);
    lowPassHz_->setRange(1, 10000);
    lowPassHz_->setValue(100);
    lowPassHz_->setSuffix(" Hz");
    steadyTrim_ = new QCheckBox(tr("trim to the steady drive amplitude"), pre);
    steadyTrim_->setChecked(true);
    pg->addWidget(bandStop_, 0, 0);
    pg->addWidget(lowPass_, 1, 0);
    pg->addWidget(lowPassHz_, 1, 1);
    pg->addWidget(steadyTrim_, 2, 0, 1, 2);
    v->addWidget(pre);

    auto* mapBox = new QGroupBox(tr("Column mapping of the selected run"), w);
    auto* mv = new QVBoxLayout(mapBox);
    mapping_ = new QLabel(tr("No run loaded."), mapBox);
    mapping_->setWordWrap(true);
    mapping_->setTextInteractionFlags(Qt::TextSelectableByMouse);
    mv->addWidget(mapping_);
    v->addWidget(mapBox);
    v->addStretch(1);

    connect(load, &QPushButton::clicked, this, [this] { openImport(); });
    connect(clear, &QPushButton::clicked, this, [this] { setDataset(io::Dataset{}); });
    connect(runTable_, &QTableWidget::currentCellChanged, this, [this](int row) { showMapping(row); });
    connect(runTable_, &QTableWidget::itemChanged, this, [this](QTableWidgetItem* item) {
        if (item->column() != 5 || item->row() >= static_cast<int>(runs_.validation.size())) return;
        runs_.validation[static_cast<size_t>(item->row())] = item->checkState() == Qt::Checked;
        dataSummary_->setText(tr("%1 runs: %2 to fit, %3 held out for validation.")
                                  .arg(runs_.data.runs.size()).arg(runs_.fitCount()).arg(runs_.validationCount()));
    });
    connect(setupBox_, QOverload<int>::of(&QComboBox::currentIndexChanged), this,
            [this] { runs_.setup = static_cast<SetupKind>(setupBox_->currentData().toInt()); });
    return w;
}

bool IdentifyPanel::loadRuns(const QStringList& files, const QString& manifest, QString* error) {
    io::DatasetOptions opt;
    opt.manifestPath = manifest.toStdString();
    if (manifest.isEmpty() && !files.isEmpty()) {
        const QString m = QFileInfo(files.front()).dir().filePath("manifest.json");
        if (QFileInfo::exists(m)) opt.manifestPath = m.toStdString();
    }
    std::vector<std::string> paths;
    for (const QString& f : files) paths.push_back(f.toStdString());
    io::Dataset ds;
    io::DatasetError err;
    if (paths.empty() || !io::loadDataset(paths, opt, ds, err)) {
        const QString why = paths.empty() ? tr("no file given") : QString::fromStdString(err.what());
        dataSummary_->setText(tr("<span style='color:#b00000'>Could not load: %1</span>").arg(why.toHtmlEscaped()));
        if (error) *error = why;
        emit statusMessage(tr("Could not load the runs: %1").arg(why));
        return false;
    }
    setDataset(ds);
    emit statusMessage(tr("Loaded %1 measured runs").arg(ds.runs.size()));
    return true;
}

// Files go through the import dialog (column mapping with preview, units, manifest, per-run
// settings, cleaning); its dataset, set-up and cleaning settings become the panel's.
void IdentifyPanel::openImport(const QStringList& given) {
    QStringList files = given;
    if (files.isEmpty())
        files = QFileDialog::getOpenFileNames(this, tr("Load measured runs"), {}, tr("CSV (*.csv *.txt);;All files (*)"));
    if (files.isEmpty()) return;
    ImportDialog dlg(files, this);
    dlg.setPreprocessSettings(fitRequest().runs.pre);
    if (dlg.exec() != QDialog::Accepted) return;
    setDataset(dlg.dataset());
    runs_.setup = dlg.setup();
    setupBox_->setCurrentIndex(setupBox_->findData(int(runs_.setup)));
    runs_.pre = dlg.preprocessSettings();
    bandStop_->setChecked(runs_.pre.filters.bandStop);
    lowPass_->setChecked(runs_.pre.filters.lowPass);
    lowPassHz_->setValue(runs_.pre.filters.lowPass_Hz);
    steadyTrim_->setChecked(runs_.pre.trim.steadyAmplitude);
    emit statusMessage(tr("Loaded %1 measured runs").arg(runs_.data.runs.size()));
}

void IdentifyPanel::setDataset(const io::Dataset& data) {
    runs_.data = data;
    runs_.validation.assign(data.runs.size(), false);
    runs_.setup = guessSetup(data);
    setupBox_->setCurrentIndex(setupBox_->findData(int(runs_.setup)));
    refreshRunTable();
}

int IdentifyPanel::runCount() const { return static_cast<int>(runs_.data.runs.size()); }

void IdentifyPanel::setValidationRun(int row, bool validation) {
    if (QTableWidgetItem* it = runTable_->item(row, 5)) it->setCheckState(validation ? Qt::Checked : Qt::Unchecked);
}

SetupKind IdentifyPanel::setup() const { return runs_.setup; }

void IdentifyPanel::refreshRunTable() {
    const QSignalBlocker block(runTable_);
    runTable_->setRowCount(static_cast<int>(runs_.data.runs.size()));
    for (size_t i = 0; i < runs_.data.runs.size(); ++i) {
        const io::Run& r = runs_.data.runs[i];
        const int row = static_cast<int>(i);
        setCell(runTable_, row, 0, QString::fromStdString(r.name()), QString::fromStdString(r.file));
        setCell(runTable_, row, 1, QString::number(r.size()));
        const auto& t = r[Signal::Time];
        setCell(runTable_, row, 2, t.size() > 1 ? QString::number(t.back() - t.front(), 'f', 2) : QStringLiteral("–"));
        double v = 0;
        setCell(runTable_, row, 3, r.setting("tN", v) ? QString::number(v, 'g', 4) : tr("unknown"));
        setCell(runTable_, row, 4, r.setting("f", v) ? QString::number(v, 'g', 4) : QStringLiteral("–"));
        auto* check = new QTableWidgetItem;
        check->setFlags(Qt::ItemIsUserCheckable | Qt::ItemIsEnabled | Qt::ItemIsSelectable);
        check->setCheckState(runs_.validation[i] ? Qt::Checked : Qt::Unchecked);
        runTable_->setItem(row, 5, check);
    }
    runTable_->resizeColumnsToContents();
    runTable_->horizontalHeader()->setSectionResizeMode(0, QHeaderView::Stretch);
    fitHeight(runTable_, 3);
    if (runs_.data.runs.empty()) {
        dataSummary_->setText(tr("No runs loaded."));
        mapping_->setText(tr("No run loaded."));
    } else {
        dataSummary_->setText(tr("%1 runs: %2 to fit, %3 held out for validation.%4")
                                  .arg(runs_.data.runs.size()).arg(runs_.fitCount()).arg(runs_.validationCount())
                                  .arg(runs_.data.manifestPath.empty() ? QString()
                                                                       : tr(" Manifest: %1.").arg(QFileInfo(QString::fromStdString(runs_.data.manifestPath)).fileName())));
        runTable_->setCurrentCell(0, 0);
        showMapping(0);
    }
    fitRun_->setEnabled(!runs_.data.runs.empty() && !worker_->isBusy());
    idRun_->setEnabled(!runs_.data.runs.empty() && !worker_->isBusy());
}

void IdentifyPanel::showMapping(int row) {
    if (row < 0 || row >= runCount()) return;
    const io::Run& r = runs_.data.runs[static_cast<size_t>(row)];
    QString html = QStringLiteral("<table cellspacing='2'>");
    for (size_t s = 0; s < io::kSignalCount; ++s) {
        const auto sig = static_cast<Signal>(s);
        if (!r.has(sig)) continue;
        auto it = r.sourceColumn.find(sig);
        html += QStringLiteral("<tr><td><b>%1</b></td><td>&larr; %2</td><td style='color:#666'>[%3]</td></tr>")
                    .arg(QString::fromLatin1(io::signalKey(sig)),
                         it != r.sourceColumn.end() ? QString::fromStdString(it->second).toHtmlEscaped() : tr("derived"),
                         QString::fromLatin1(io::signalUnit(sig)));
    }
    html += QStringLiteral("</table><p style='margin-top:4px'>");
    QStringList settings;
    for (const auto& [k, v] : r.settings) {
        auto src = r.settingSource.find(k);
        settings << QStringLiteral("%1 = %2 <span style='color:#666'>(%3)</span>")
                        .arg(QString::fromStdString(k), QString::number(v, 'g', 5),
                             src != r.settingSource.end() ? QString::fromStdString(src->second) : QString());
    }
    html += settings.isEmpty() ? tr("No known settings.") : settings.join(QStringLiteral(", "));
    mapping_->setText(html + QStringLiteral("</p>"));
}

// --- Fit ---------------------------------------------------------------------------------

QWidget* IdentifyPanel::buildFitTab() {
    auto* w = new QWidget;
    auto* v = new QVBoxLayout(w);
    auto* form = new QFormLayout;
    model_ = new QComboBox(w);
    model_->addItem(tr("rate-state"), "rate-state");
    model_->addItem(tr("Coulomb"), "coulomb");
    model_->addItem(tr("both, side by side"), "both");
    form->addRow(tr("Model"), model_);
    auto* freeBox = new QWidget(w);
    auto* fg = new QGridLayout(freeBox);
    fg->setContentsMargins(0, 0, 0, 0);
    int k = 0;
    for (const char* n : kFitParams) {
        auto* c = new QCheckBox(paramTitle(n).section(' ', 0, 0), freeBox);
        c->setToolTip(tr("fit %1 (else held at its start value)").arg(paramTitle(n)));
        fitFree_[n] = c;
        fg->addWidget(c, k / 3, k % 3);  // μ C1 η / D_c v_c ε_T / r m* ζ: fits the panel's width
        ++k;
    }
    setFreeParameters({"mu", "eta", "Dc", "vc", "epsT"});
    form->addRow(tr("Free"), freeBox);
    auto* lossRow = new QHBoxLayout;
    loss_ = new QComboBox(w);
    loss_->addItem(tr("none (least squares)"), int(LossKind::None));
    loss_->addItem(tr("Huber"), int(LossKind::Huber));
    loss_->addItem(tr("Cauchy"), int(LossKind::Cauchy));
    lossScale_ = new QDoubleSpinBox(w);
    lossScale_->setRange(1e-3, 1e3);
    lossScale_->setDecimals(3);
    lossScale_->setValue(1.0);
    lossScale_->setPrefix(tr("scale "));
    lossRow->addWidget(loss_, 1);
    lossRow->addWidget(lossScale_);
    form->addRow(tr("Robust loss"), lossRow);
    auto* splitRow = new QHBoxLayout;
    split_ = new QCheckBox(tr("hold out the end of every run"), w);
    splitFraction_ = new QDoubleSpinBox(w);
    splitFraction_->setRange(0.1, 0.95);
    splitFraction_->setSingleStep(0.05);
    splitFraction_->setValue(0.7);
    splitFraction_->setPrefix(tr("fit first "));
    splitFraction_->setEnabled(false);
    splitRow->addWidget(split_, 1);
    splitRow->addWidget(splitFraction_);
    form->addRow(tr("Validation"), splitRow);
    auto* solverRow = new QHBoxLayout;
    multistarts_ = new QSpinBox(w);
    multistarts_->setRange(1, 50);
    multistarts_->setValue(3);
    multistarts_->setPrefix(tr("starts "));
    maxIterations_ = new QSpinBox(w);
    maxIterations_->setRange(1, 1000);
    maxIterations_->setValue(40);
    maxIterations_->setPrefix(tr("iterations "));
    solverRow->addWidget(multistarts_);
    solverRow->addWidget(maxIterations_);
    solverRow->addStretch(1);
    form->addRow(tr("Solver"), solverRow);
    jackknife_ = new QCheckBox(tr("jackknife over runs"), w);
    jackknife_->setToolTip(tr("repeat the whole fit leaving each run out (3 or more runs): standard error = the larger "
                              "of the Jacobian and the jackknife value; honest where the cost has several minima, K more fits"));
    form->addRow(tr("Std. errors"), jackknife_);
    v->addLayout(form);

    auto* runRow = new QHBoxLayout;
    fitRun_ = new QPushButton(tr("Fit"), w);
    fitRun_->setDefault(true);
    fitCancel_ = new QPushButton(tr("Cancel"), w);
    fitCancel_->setEnabled(false);
    fitProgress_ = new QProgressBar(w);
    fitProgress_->setRange(0, 1000);
    fitProgress_->setValue(0);
    fitProgress_->setTextVisible(false);
    runRow->addWidget(fitRun_);
    runRow->addWidget(fitCancel_);
    runRow->addWidget(fitProgress_, 1);
    v->addLayout(runRow);
    fitStatus_ = new QLabel(tr("Load runs, then Fit."), w);
    fitStatus_->setWordWrap(true);
    v->addWidget(fitStatus_);

    fitParams_ = makeTable({tr("Parameter"), tr("rate-state"), tr("Coulomb")}, w);
    fitHeight(fitParams_, 5);
    v->addWidget(new QLabel(tr("<b>Parameters</b> (value ± 1σ standard error)"), w));
    v->addWidget(fitParams_);
    identifiability_ = new QLabel(w);
    identifiability_->setWordWrap(true);
    v->addWidget(identifiability_);
    fitRuns_ = makeTable({tr("Run"), tr("Role"), tr("RMS [N]"), tr("rate-state"), tr("Coulomb")}, w);
    fitHeight(fitRuns_, 3);
    v->addWidget(new QLabel(tr("<b>NRMSE per run</b> (RMS error / RMS measured)"), w));
    v->addWidget(fitRuns_);
    auto* exportRow = new QHBoxLayout;
    auto* exportButton = new QPushButton(tr("Export report…"), w);
    exportRow->addStretch(1);
    exportRow->addWidget(exportButton);
    v->addLayout(exportRow);
    v->addStretch(1);

    connect(split_, &QCheckBox::toggled, splitFraction_, &QWidget::setEnabled);
    connect(fitRun_, &QPushButton::clicked, this, &IdentifyPanel::startFit);
    connect(fitCancel_, &QPushButton::clicked, this, &IdentifyPanel::cancel);
    connect(exportButton, &QPushButton::clicked, this, &IdentifyPanel::exportDialog);
    return w;
}

void IdentifyPanel::setModel(const QString& model) {
    const int i = model_->findData(model);
    if (i >= 0) model_->setCurrentIndex(i);
}

void IdentifyPanel::setFreeParameters(const QStringList& names) {
    for (auto& [n, box] : fitFree_) box->setChecked(names.contains(QString::fromStdString(n)));
}

void IdentifyPanel::setMultistarts(int n) {
    multistarts_->setValue(n);
    idMultistarts_->setValue(n);
}

void IdentifyPanel::setMaxIterations(int n) { maxIterations_->setValue(n); }

void IdentifyPanel::setTimeSplit(double fraction) {
    split_->setChecked(fraction > 0);
    if (fraction > 0) splitFraction_->setValue(fraction);
}

FitRequest IdentifyPanel::fitRequest() const {
    FitRequest r;
    r.runs = runs_;
    r.runs.pre.filters.bandStop = bandStop_->isChecked();
    r.runs.pre.filters.lowPass = lowPass_->isChecked();
    r.runs.pre.filters.lowPass_Hz = lowPassHz_->value();
    r.runs.pre.trim.steadyAmplitude = steadyTrim_->isChecked();
    const QString m = model_->currentData().toString();
    r.laws = m == "coulomb" ? std::vector<LawKind>{LawKind::Coulomb}
             : m == "both"  ? std::vector<LawKind>{LawKind::RateState, LawKind::Coulomb}
                            : std::vector<LawKind>{LawKind::RateState};
    r.settings.setup = runs_.setup;
    r.settings.free.clear();
    for (const char* n : kFitParams)
        if (fitFree_.at(n)->isChecked()) r.settings.free.push_back(n);
    r.settings.loss = static_cast<LossKind>(loss_->currentData().toInt());
    r.settings.lossScale = lossScale_->value();
    r.settings.multistarts = multistarts_->value();
    r.settings.maxIterations = maxIterations_->value();
    r.settings.jackknife = jackknife_->isChecked();
    r.splitTime = split_->isChecked() ? splitFraction_->value() : 0.0;
    return r;
}

void IdentifyPanel::startFit() {
    if (runs_.data.runs.empty()) {
        fitStatus_->setText(tr("Load runs first."));
        return;
    }
    const FitRequest r = fitRequest();
    if (r.settings.free.empty()) {
        fitStatus_->setText(tr("<span style='color:#b00000'>Choose at least one free parameter.</span>"));
        return;
    }
    setBusy(true, true);
    fitStatus_->setText(tr("Fitting %1 runs…").arg(r.runs.fitCount()));
    worker_->startFit(r);
}

void IdentifyPanel::cancel() {
    if (!worker_->isBusy()) return;
    worker_->cancel();
    (fitJob_ ? fitStatus_ : idStatus_)->setText(tr("Cancelling…"));
}

void IdentifyPanel::setBusy(bool busy, bool fitJob) {
    fitJob_ = fitJob;
    const bool have = !runs_.data.runs.empty();
    fitRun_->setEnabled(!busy && have);
    idRun_->setEnabled(!busy && have);
    fitCancel_->setEnabled(busy && fitJob);
    idCancel_->setEnabled(busy && !fitJob);
    QProgressBar* bar = fitJob ? fitProgress_ : idProgress_;
    if (busy) bar->setValue(0);
}

void IdentifyPanel::onProgress(double fraction, const QString& stage) {
    QProgressBar* bar = fitJob_ ? fitProgress_ : idProgress_;
    bar->setValue(static_cast<int>(std::lround(1000 * std::clamp(fraction, 0.0, 1.0))));
    if (!worker_->isBusy()) return;
    (fitJob_ ? fitStatus_ : idStatus_)->setText(stage.isEmpty() ? tr("Working…") : stage + QStringLiteral("…"));
}

bool IdentifyPanel::showJobEnd(const QString& what, bool cancelled, bool ok, const QString& message, double elapsed_ms,
                               QProgressBar* bar, QLabel* status) {
    if (cancelled) {
        bar->setValue(0);
        status->setText(tr("%1 cancelled after %2 s.").arg(what).arg(elapsed_ms / 1000.0, 0, 'f', 1));
        emit statusMessage(tr("%1 cancelled").arg(what));
        return false;
    }
    if (!ok) {
        status->setText(tr("<span style='color:#b00000'>%1 failed: %2</span>").arg(what, message.toHtmlEscaped()));
        emit statusMessage(tr("%1 failed: %2").arg(what, message));
        return false;
    }
    return true;
}

void IdentifyPanel::onFitFinished(const FitOutcome& o) {
    setBusy(false, true);
    const double s = o.elapsed_ms / 1000.0;
    if (!showJobEnd(tr("Fit"), o.cancelled, o.ok, o.message, o.elapsed_ms, fitProgress_, fitStatus_)) return;
    lastFit_ = o;
    fitProgress_->setValue(1000);
    QStringList summary;
    for (const LawFit& lf : o.fits)
        summary << (std::isfinite(lf.fit.validationNrmse)
                        ? tr("%1: fit NRMSE %2, validation %3").arg(lawName(lf.law), formatNrmse(lf.fit.fitNrmse), formatNrmse(lf.fit.validationNrmse))
                        : tr("%1: fit NRMSE %2").arg(lawName(lf.law), formatNrmse(lf.fit.fitNrmse)));
    fitStatus_->setText(tr("Done in %1 s. %2").arg(s, 0, 'f', 1).arg(summary.join(QStringLiteral("; "))));

    // Parameters: one row per name over all laws, value ± stderr in each law's column.
    std::vector<std::string> names;
    for (const LawFit& lf : o.fits)
        for (const auto& n : lf.fit.fit.names)
            if (std::find(names.begin(), names.end(), n) == names.end()) names.push_back(n);
    fitParams_->setRowCount(static_cast<int>(names.size()));
    for (size_t i = 0; i < names.size(); ++i) {
        const int row = static_cast<int>(i);
        setCell(fitParams_, row, 0, paramTitle(names[i]));
        for (int col = 1; col <= 2; ++col) setCell(fitParams_, row, col, QStringLiteral(""));
        for (const LawFit& lf : o.fits) {
            const int col = lf.law == LawKind::Coulomb ? 2 : 1;
            const auto& f = lf.fit.fit;
            for (size_t j = 0; j < f.names.size(); ++j) {
                if (f.names[j] != names[i]) continue;
                const bool isFree = j < f.free.size() && f.free[j];
                setCell(fitParams_, row, col, isFree ? formatEstimate(f.values[j], f.stderrs[j]) : formatEstimate(f.values[j], 0.0) + tr(" (fixed)"));
            }
        }
    }
    fitParams_->setColumnHidden(1, std::none_of(o.fits.begin(), o.fits.end(), [](const LawFit& l) { return l.law == LawKind::RateState; }));
    fitParams_->setColumnHidden(2, std::none_of(o.fits.begin(), o.fits.end(), [](const LawFit& l) { return l.law == LawKind::Coulomb; }));
    fitParams_->resizeColumnsToContents();
    fitParams_->horizontalHeader()->setStretchLastSection(true);
    fitHeight(fitParams_, 5);

    QStringList warnings;
    bool bad = false;
    for (const LawFit& lf : o.fits) {
        const auto& f = lf.fit.fit;
        QString text = QString::fromStdString(f.identifiabilityMessage);
        // Strong correlations among the free parameters (|r| > 0.95) deserve a line of their own.
        QStringList pairs;
        const size_t p = f.freeNames.size();
        for (size_t a = 0; a < p && f.correlation.size() == p * p; ++a)
            for (size_t b = a + 1; b < p; ++b)
                if (std::abs(f.correlation[a * p + b]) > 0.95)
                    pairs << QStringLiteral("%1–%2 (r = %3)").arg(paramTitle(f.freeNames[a]).section(' ', 0, 0),
                                                                  paramTitle(f.freeNames[b]).section(' ', 0, 0))
                                 .arg(f.correlation[a * p + b], 0, 'f', 3);
        if (!pairs.isEmpty()) text += tr("; strongly correlated: %1").arg(pairs.join(", "));
        if (!lf.fit.stderrWarning.empty()) text += "; " + QString::fromStdString(lf.fit.stderrWarning);
        bad = bad || !f.identifiable || !pairs.isEmpty() || !lf.fit.stderrWarning.empty();
        warnings << QStringLiteral("<b>%1</b>: %2").arg(lawName(lf.law), text.toHtmlEscaped());
    }
    identifiability_->setText(warnings.join("<br>"));
    identifiability_->setStyleSheet(bad ? "QLabel { color: #9a5b00; }" : "QLabel { color: #2a6b2a; }");

    // Runs.
    const auto& first = o.fits.front().fit.runs;
    fitRuns_->setRowCount(static_cast<int>(first.size()));
    for (size_t i = 0; i < first.size(); ++i) {
        const int row = static_cast<int>(i);
        setCell(fitRuns_, row, 0, QString::fromStdString(QFileInfo(QString::fromStdString(first[i].file)).fileName().toStdString()));
        setCell(fitRuns_, row, 1, QString::fromStdString(first[i].role));
        setCell(fitRuns_, row, 2, std::isfinite(first[i].rms_N) ? QString::number(first[i].rms_N, 'g', 4) : QStringLiteral("–"));
        setCell(fitRuns_, row, 3, QString());
        setCell(fitRuns_, row, 4, QString());
        for (const LawFit& lf : o.fits) {
            if (i >= lf.fit.runs.size()) continue;
            const RunScore& r = lf.fit.runs[i];
            setCell(fitRuns_, row, lf.law == LawKind::Coulomb ? 4 : 3, r.ok ? formatNrmse(r.nrmse) : tr("failed"),
                    QString::fromStdString(r.message));
        }
    }
    fitRuns_->setColumnHidden(3, fitParams_->isColumnHidden(1));
    fitRuns_->setColumnHidden(4, fitParams_->isColumnHidden(2));
    fitRuns_->resizeColumnsToContents();
    fitHeight(fitRuns_, 3);

    shown_ = Shown::Fit;
    refreshPlots();
    emit statusMessage(tr("Fit done"));
    emit fitShown(o);
}

QString IdentifyPanel::fitStatus() const { return fitStatus_->text(); }
QString IdentifyPanel::identifyStatus() const { return idStatus_->text(); }

// --- Identify ----------------------------------------------------------------------------

QWidget* IdentifyPanel::buildIdentifyTab() {
    auto* w = new QWidget;
    auto* v = new QVBoxLayout(w);
    auto* intro = new QLabel(tr("Fit the baseline law, look at what its residual still contains, add the catalogue effect "
                                "that explains it best (BIC, then held-out error), repeat."), w);
    intro->setWordWrap(true);
    intro->setStyleSheet("color: #555;");
    v->addWidget(intro);
    auto* form = new QFormLayout;
    auto* freeBox = new QWidget(w);
    auto* fg = new QGridLayout(freeBox);
    fg->setContentsMargins(0, 0, 0, 0);
    int k = 0;
    for (const char* n : kLawParams) {
        auto* c = new QCheckBox(paramTitle(n).section(' ', 0, 0), freeBox);
        idFree_[n] = c;
        fg->addWidget(c, k / 4, k % 4);
        ++k;
    }
    {
        const IdentifyOptions defaults;  // the same baseline as stickslip-cli identify
        QStringList names;
        for (const std::string& n : defaults.freeLaw) names << QString::fromStdString(n);
        setIdentifyFree(names);
    }
    form->addRow(tr("Free law"), freeBox);
    candidateList_ = new QListWidget(w);
    for (const EffectInfo& e : effectCatalogue()) {
        auto* it = new QListWidgetItem(QString::fromStdString(e.name), candidateList_);
        it->setFlags(Qt::ItemIsUserCheckable | Qt::ItemIsEnabled);
        it->setCheckState(Qt::Checked);
        it->setToolTip(QString::fromStdString(e.description + "\n\nSignature: " + e.signature));
    }
    candidateList_->setMaximumHeight(5 * 20 + 8);
    form->addRow(tr("Candidates"), candidateList_);
    auto* row = new QHBoxLayout;
    maxEffects_ = new QSpinBox(w);
    maxEffects_->setRange(1, 9);
    maxEffects_->setValue(3);
    maxEffects_->setPrefix(tr("at most "));
    maxEffects_->setSuffix(tr(" effects"));
    bicMargin_ = new QDoubleSpinBox(w);
    bicMargin_->setRange(0, 1000);
    bicMargin_->setValue(IdentifyOptions{}.bicMargin);
    bicMargin_->setPrefix(tr("ΔBIC < −"));
    idMultistarts_ = new QSpinBox(w);
    idMultistarts_->setRange(1, 20);
    idMultistarts_->setValue(2);
    idMultistarts_->setPrefix(tr("starts "));
    row->addWidget(maxEffects_);
    row->addWidget(bicMargin_);
    row->addWidget(idMultistarts_);
    form->addRow(tr("Loop"), row);
    v->addLayout(form);

    selfTest_ = new SelfTestView(w);
    v->addWidget(selfTest_);

    auto* runRow = new QHBoxLayout;
    idRun_ = new QPushButton(tr("Identify"), w);
    idCancel_ = new QPushButton(tr("Cancel"), w);
    idCancel_->setEnabled(false);
    idProgress_ = new QProgressBar(w);
    idProgress_->setRange(0, 1000);
    idProgress_->setValue(0);
    idProgress_->setTextVisible(false);
    runRow->addWidget(idRun_);
    runRow->addWidget(idCancel_);
    runRow->addWidget(idProgress_, 1);
    v->addLayout(runRow);
    idStatus_ = new QLabel(tr("Load runs, then Identify."), w);
    idStatus_->setWordWrap(true);
    v->addWidget(idStatus_);
    unexplained_ = new QLabel(w);
    unexplained_->setWordWrap(true);
    v->addWidget(unexplained_);

    beforeAfter_ = makeTable({tr("Model"), tr("fit NRMSE"), tr("held-out NRMSE")}, w);
    v->addWidget(new QLabel(tr("<b>Error before and after</b>"), w));
    v->addWidget(beforeAfter_);
    fitHeight(beforeAfter_, 2);
    effects_ = makeTable({tr("Effect added"), tr("ΔBIC"), tr("held-out"), tr("Parameters")}, w);
    v->addWidget(new QLabel(tr("<b>Effects added</b> (parameters ± 1σ)"), w));
    v->addWidget(effects_);
    fitHeight(effects_, 1);
    candidates_ = makeTable({tr("Candidate"), tr("Round"), tr("ΔBIC"), tr("fit NRMSE"), tr("Verdict")}, w);
    v->addWidget(new QLabel(tr("<b>Candidates</b>"), w));
    v->addWidget(candidates_);
    fitHeight(candidates_, 4);
    auto* exportRow = new QHBoxLayout;
    auto* exportButton = new QPushButton(tr("Export report…"), w);
    exportRow->addStretch(1);
    exportRow->addWidget(exportButton);
    v->addLayout(exportRow);
    v->addStretch(1);

    connect(idRun_, &QPushButton::clicked, this, &IdentifyPanel::startIdentify);
    connect(idCancel_, &QPushButton::clicked, this, &IdentifyPanel::cancel);
    connect(exportButton, &QPushButton::clicked, this, &IdentifyPanel::exportDialog);
    return w;
}

void IdentifyPanel::setIdentifyFree(const QStringList& names) {
    for (auto& [n, box] : idFree_) box->setChecked(names.contains(QString::fromStdString(n)));
}

void IdentifyPanel::setCandidates(const QStringList& names) {
    for (int i = 0; i < candidateList_->count(); ++i) {
        QListWidgetItem* it = candidateList_->item(i);
        it->setCheckState(names.isEmpty() || names.contains(it->text()) ? Qt::Checked : Qt::Unchecked);
    }
}

void IdentifyPanel::setMaxEffects(int n) { maxEffects_->setValue(n); }

IdentifyRequest IdentifyPanel::identifyRequest() const {
    IdentifyRequest r;
    r.runs = fitRequest().runs;
    r.options.freeLaw.clear();
    for (const char* n : kLawParams)
        if (idFree_.at(n)->isChecked()) r.options.freeLaw.push_back(n);
    bool all = true;
    std::vector<std::string> cands;
    for (int i = 0; i < candidateList_->count(); ++i) {
        if (candidateList_->item(i)->checkState() == Qt::Checked) cands.push_back(candidateList_->item(i)->text().toStdString());
        else all = false;
    }
    if (!all) r.options.candidates = cands;
    r.options.maxEffects = maxEffects_->value();
    r.options.bicMargin = bicMargin_->value();
    r.options.multistarts = idMultistarts_->value();
    return r;
}

void IdentifyPanel::startIdentify() {
    if (runs_.data.runs.empty()) {
        idStatus_->setText(tr("Load runs first."));
        return;
    }
    const IdentifyRequest r = identifyRequest();
    if (r.options.freeLaw.empty()) {
        idStatus_->setText(tr("<span style='color:#b00000'>Choose at least one free law parameter.</span>"));
        return;
    }
    bool anyCandidate = false;
    for (int i = 0; i < candidateList_->count(); ++i) anyCandidate = anyCandidate || candidateList_->item(i)->checkState() == Qt::Checked;
    if (!anyCandidate) {
        idStatus_->setText(tr("<span style='color:#b00000'>Choose at least one candidate effect.</span>"));
        return;
    }
    IdentifyRequest req = r;
    QString why;
    if (!selfTest_->apply(req.options, why)) {
        idStatus_->setText(tr("<span style='color:#b00000'>%1</span>").arg(why.toHtmlEscaped()));
        return;
    }
    setBusy(true, false);
    unexplained_->clear();
    idStatus_->setText(tr("Identifying…"));
    worker_->startIdentify(req);
}

void IdentifyPanel::onIdentifyFinished(const IdentifyOutcome& o) {
    setBusy(false, false);
    const double s = o.elapsed_ms / 1000.0;
    if (!showJobEnd(tr("Identify"), o.cancelled, o.ok, o.message, o.elapsed_ms, idProgress_, idStatus_)) return;
    lastIdentify_ = o;
    const IdentifyResult& r = o.result;
    idProgress_->setValue(1000);
    QStringList added;
    for (const AddedEffect& e : r.effectsAdded) added << QString::fromStdString(e.name);
    idStatus_->setText(tr("Done in %1 s (%2 fits, %3 set-up). Effects added: %4.")
                           .arg(s, 0, 'f', 1).arg(r.fits).arg(QString::fromStdString(r.setup),
                                added.isEmpty() ? tr("none") : added.join(", ")));
    if (r.unexplained)
        unexplained_->setText(tr("<b>Unexplained structure remains</b>: %1").arg(QString::fromStdString(r.unexplainedReason).toHtmlEscaped()));
    else
        unexplained_->setText(tr("<b>No unexplained structure</b>: the final residual looks like noise."));
    unexplained_->setStyleSheet(r.unexplained ? "QLabel { color: #9a5b00; }" : "QLabel { color: #2a6b2a; }");

    beforeAfter_->setRowCount(2);
    setCell(beforeAfter_, 0, 0, tr("before (baseline)"));
    setCell(beforeAfter_, 0, 1, formatNrmse(r.before.fitNrmse));
    setCell(beforeAfter_, 0, 2, formatNrmse(r.before.validationNrmse));
    setCell(beforeAfter_, 1, 0, added.isEmpty() ? tr("after (unchanged)") : tr("after (+ %1)").arg(added.join(", ")));
    setCell(beforeAfter_, 1, 1, formatNrmse(r.after.fitNrmse));
    setCell(beforeAfter_, 1, 2, formatNrmse(r.after.validationNrmse));
    beforeAfter_->resizeColumnsToContents();
    fitHeight(beforeAfter_, 2);

    effects_->setRowCount(static_cast<int>(r.effectsAdded.size()));
    for (size_t i = 0; i < r.effectsAdded.size(); ++i) {
        const AddedEffect& e = r.effectsAdded[i];
        const int row = static_cast<int>(i);
        QStringList ps;
        for (const ParamEstimate& p : e.params) ps << QStringLiteral("%1 = %2").arg(QString::fromStdString(p.name), formatEstimate(p.value, p.stderr_));
        QStringList why;
        for (const SignalCorrelation& c : e.pointedBy) why << QStringLiteral("%1 (r = %2)").arg(QString::fromStdString(c.signal)).arg(c.correlation, 0, 'f', 2);
        setCell(effects_, row, 0, QString::fromStdString(e.name), why.isEmpty() ? QString() : tr("pointed to by ") + why.join(", "));
        setCell(effects_, row, 1, QString::number(e.deltaBic, 'f', 1));
        setCell(effects_, row, 2, QStringLiteral("%1 → %2").arg(formatNrmse(e.heldOutBefore), formatNrmse(e.heldOutAfter)));
        setCell(effects_, row, 3, ps.join("; "), ps.join("\n"));
        effects_->item(row, 3)->setTextAlignment(Qt::AlignLeft | Qt::AlignVCenter);
    }
    effects_->resizeColumnsToContents();
    fitHeight(effects_, 1);

    candidates_->setRowCount(static_cast<int>(r.candidates.size()));
    for (size_t i = 0; i < r.candidates.size(); ++i) {
        const CandidateScore& c = r.candidates[i];
        const int row = static_cast<int>(i);
        QStringList ps;
        for (const ParamEstimate& p : c.params) ps << QStringLiteral("%1 = %2").arg(QString::fromStdString(p.name), formatEstimate(p.value, p.stderr_));
        setCell(candidates_, row, 0, QString::fromStdString(c.name), ps.join("\n"));
        setCell(candidates_, row, 1, QString::number(c.round));
        setCell(candidates_, row, 2, c.applicable ? QString::number(c.deltaBic, 'f', 1) : QStringLiteral("–"));
        setCell(candidates_, row, 3, c.applicable ? formatNrmse(c.fitNrmse) : QStringLiteral("–"));
        const QString verdict = c.accepted ? tr("added") : QString::fromStdString(c.reason);
        setCell(candidates_, row, 4, verdict, verdict);
        candidates_->item(row, 4)->setTextAlignment(Qt::AlignLeft | Qt::AlignVCenter);
        if (c.accepted) candidates_->item(row, 0)->setForeground(QColor(44, 120, 44));
    }
    candidates_->resizeColumnsToContents();
    fitHeight(candidates_, 4);

    selfTest_->show(r.selfTest);

    shown_ = Shown::Identify;
    refreshPlots();
    emit statusMessage(tr("Identify done"));
    emit identifyShown(o);
}

// --- Plots -------------------------------------------------------------------------------

QWidget* IdentifyPanel::buildPlots() {
    auto* w = new QWidget;
    auto* v = new QVBoxLayout(w);
    v->setContentsMargins(0, 0, 0, 0);
    auto* row = new QHBoxLayout;
    row->addWidget(new QLabel(tr("Run"), w));
    plotRun_ = new QComboBox(w);
    plotRun_->setMinimumContentsLength(24);
    plotRun_->setSizeAdjustPolicy(QComboBox::AdjustToMinimumContentsLengthWithIcon);
    row->addWidget(plotRun_);
    plotSource_ = new QLabel(tr("Nothing fitted yet."), w);
    plotSource_->setStyleSheet("color: #555;");
    row->addWidget(plotSource_, 1);
    v->addLayout(row);
    plots_ = new QTabWidget(w);
    overlayPlot_ = new widgets::SeriesPlot(w);
    overlayPlot_->setTitles(tr("Measured versus predicted friction force"), tr("time t [s]"), tr("friction force F [N]"));
    residualPlot_ = new widgets::SeriesPlot(w);
    residualPlot_->setTitles(tr("Residual (measured − predicted)"), tr("time t [s]"), tr("residual [N]"));
    spectrumPlot_ = new widgets::SeriesPlot(w);
    spectrumPlot_->setTitles(tr("Residual spectrum (dotted: forcing harmonics)"), tr("frequency f [Hz]"), tr("power [N²/Hz]"));
    spectrumPlot_->setLogY(true);
    acfPlot_ = new widgets::SeriesPlot(w);
    acfPlot_->setTitles(tr("Residual autocorrelation"), tr("lag [decimated samples]"), tr("ρ"));
    correlations_ = makeTable({tr("Candidate signal"), tr("r before"), tr("r after")}, w);
    plots_->addTab(overlayPlot_, tr("Measured vs predicted"));
    plots_->addTab(residualPlot_, tr("Residual"));
    plots_->addTab(spectrumPlot_, tr("Spectrum"));
    plots_->addTab(acfPlot_, tr("Autocorrelation"));
    plots_->addTab(correlations_, tr("Correlations"));
    v->addWidget(plots_, 1);
    connect(plotRun_, QOverload<int>::of(&QComboBox::currentIndexChanged), this, [this] { refreshPlots(); });
    return w;
}

void IdentifyPanel::refreshPlots() {
    // Run names of what is shown.
    QStringList names;
    if (shown_ == Shown::Fit && !lastFit_.fits.empty())
        for (const RunOverlay& o : lastFit_.fits.front().overlays) names << QString::fromStdString(o.file) + (o.role == "validation" ? tr(" (validation)") : QString());
    else if (shown_ == Shown::Identify)
        for (const RunTrace& t : lastIdentify_.result.traces) names << QFileInfo(QString::fromStdString(t.file)).fileName();
    QStringList current;
    for (int i = 0; i < plotRun_->count(); ++i) current << plotRun_->itemText(i);
    if (current != names) {
        const QSignalBlocker block(plotRun_);
        plotRun_->clear();
        plotRun_->addItems(names);
        plotRun_->setCurrentIndex(names.isEmpty() ? -1 : 0);
    }
    const int k = plotRun_->currentIndex();
    std::vector<widgets::PlotSeries> over, res;
    const Diagnostics* diag = nullptr;
    const Diagnostics* diagAfter = nullptr;
    if (shown_ == Shown::Fit && k >= 0) {
        plotSource_->setText(tr("Fit: %1").arg(lastFit_.fits.size() > 1 ? tr("rate-state (solid) and Coulomb (dashed)")
                                                                           : lawName(lastFit_.fits.front().law)));
        bool first = true;
        for (const LawFit& lf : lastFit_.fits) {
            if (k >= static_cast<int>(lf.overlays.size())) continue;
            const RunOverlay& o = lf.overlays[static_cast<size_t>(k)];
            if (first) over.push_back({tr("measured"), o.t_s, o.measured_N, kMeasured, false, true, 1.0});
            first = false;
            const QColor c = lf.law == LawKind::Coulomb ? kCoulomb : kRate;
            over.push_back({tr("%1 predicted").arg(lawName(lf.law)), o.t_s, o.predicted_N, c, lf.law == LawKind::Coulomb, false, 1.4});
            std::vector<double> r(o.t_s.size());
            for (size_t j = 0; j < r.size(); ++j) r[j] = o.measured_N[j] - o.predicted_N[j];
            res.push_back({lawName(lf.law), o.t_s, r, c, lf.law == LawKind::Coulomb, false, 1.0});
        }
        diag = lastFit_.fits.front().diagnostics.spectrum.frequency_Hz.empty() ? nullptr : &lastFit_.fits.front().diagnostics;
    } else if (shown_ == Shown::Identify && k >= 0 && k < static_cast<int>(lastIdentify_.result.traces.size())) {
        const IdentifyResult& r = lastIdentify_.result;
        const RunTrace& t = r.traces[static_cast<size_t>(k)];
        plotSource_->setText(r.effectsAdded.empty() ? tr("Identify: baseline (no effect added)") : tr("Identify: baseline and extended model"));
        // Dynamics compares only the sliding samples: leave the others out.
        std::vector<double> ts, m, b, a;
        for (size_t j = 0; j < t.t_s.size(); ++j) {
            if (j < t.used.size() && !t.used[j]) continue;
            ts.push_back(t.t_s[j]);
            m.push_back(t.measured_N[j]);
            b.push_back(j < t.before_N.size() ? t.before_N[j] : NAN);
            a.push_back(j < t.after_N.size() ? t.after_N[j] : NAN);
        }
        over.push_back({tr("measured"), ts, m, kMeasured, false, true, 1.0});
        over.push_back({tr("baseline"), ts, b, kBefore, true, false, 1.3});
        std::vector<double> rb(ts.size()), ra(ts.size());
        for (size_t j = 0; j < ts.size(); ++j) {
            rb[j] = m[j] - b[j];
            ra[j] = m[j] - a[j];
        }
        if (!r.effectsAdded.empty()) over.push_back({tr("extended"), ts, a, kAfter, false, false, 1.4});
        res.push_back({tr("baseline"), ts, rb, kBefore, false, false, 1.0});
        if (!r.effectsAdded.empty()) res.push_back({tr("extended"), ts, ra, kAfter, false, false, 1.0});
        diag = &r.diagnosticsBefore;
        diagAfter = r.effectsAdded.empty() ? nullptr : &r.diagnosticsAfter;
    } else {
        plotSource_->setText(tr("Nothing fitted yet."));
    }
    overlayPlot_->setSeries(over);
    residualPlot_->setSeries(res);

    std::vector<widgets::PlotSeries> spec, acf;
    std::vector<double> harmonics;
    auto addDiag = [&](const Diagnostics& d, const QString& label, const QColor& c) {
        spec.push_back({label, d.spectrum.frequency_Hz, d.spectrum.power, c, false, false, 1.0});
        std::vector<double> lag(d.whiteness.acf.size());
        for (size_t j = 0; j < lag.size(); ++j) lag[j] = static_cast<double>(j);
        acf.push_back({label + QStringLiteral(" (Ljung–Box p = %1)").arg(d.whiteness.pValue, 0, 'g', 2), lag, d.whiteness.acf, c, false, false, 1.2});
        if (harmonics.empty()) harmonics = d.spectrum.harmonics_Hz;
    };
    const bool identify = shown_ == Shown::Identify;
    if (diag) addDiag(*diag, identify ? tr("baseline") : tr("residual"), identify ? kBefore : kRate);
    if (diagAfter) addDiag(*diagAfter, tr("extended"), kAfter);
    spectrumPlot_->setSeries(spec);
    spectrumPlot_->setVerticalLines(harmonics);
    acfPlot_->setSeries(acf);
    acfPlot_->setHorizontalLines({0.0});

    correlations_->setRowCount(0);
    if (diag) {
        correlations_->setRowCount(static_cast<int>(diag->correlations.size()));
        for (size_t i = 0; i < diag->correlations.size(); ++i) {
            const int row = static_cast<int>(i);
            setCell(correlations_, row, 0, QString::fromStdString(diag->correlations[i].signal));
            setCell(correlations_, row, 1, QString::number(diag->correlations[i].correlation, 'f', 3));
            double after = NAN;
            if (diagAfter)
                for (const SignalCorrelation& c : diagAfter->correlations)
                    if (c.signal == diag->correlations[i].signal) after = c.correlation;
            setCell(correlations_, row, 2, std::isfinite(after) ? QString::number(after, 'f', 3) : QStringLiteral("–"));
        }
        correlations_->resizeColumnsToContents();
    }
}

// --- Export ------------------------------------------------------------------------------

bool IdentifyPanel::exportFitReport(const QString& jsonPath, QString* error) const {
    if (!lastFit_.ok) {
        if (error) *error = tr("no fit to export");
        return false;
    }
    return writeAtomically(jsonPath, QByteArray::fromStdString(fitReportJson(lastFit_).dump(1) + "\n"), error);
}

bool IdentifyPanel::exportIdentifyReport(const QString& jsonPath, const QString& htmlPath, QString* error) const {
    if (!lastIdentify_.ok) {
        if (error) *error = tr("no identify result to export");
        return false;
    }
    if (!writeAtomically(jsonPath, QByteArray::fromStdString(identifyReportJson(lastIdentify_).dump(1) + "\n"), error)) return false;
    if (!htmlPath.isEmpty() && !writeAtomically(htmlPath, QByteArray::fromStdString(renderHtmlReport(lastIdentify_.result)), error))
        return false;
    return true;
}

void IdentifyPanel::exportDialog() {
    const bool identify = controls_->currentIndex() == 2;
    QString why;
    if (identify) {
        const QString p = QFileDialog::getSaveFileName(this, tr("Export identify report"), "report.json", tr("JSON (*.json)"));
        if (p.isEmpty()) return;
        QString html = p;
        html = (html.endsWith(".json", Qt::CaseInsensitive) ? html.left(html.size() - 5) : html) + ".html";
        if (!exportIdentifyReport(p, html, &why)) emit statusMessage(tr("Export failed: %1").arg(why));
        else emit statusMessage(tr("Exported %1 and %2").arg(p, html));
    } else {
        const QString p = QFileDialog::getSaveFileName(this, tr("Export fit report"), "fit.json", tr("JSON (*.json)"));
        if (p.isEmpty()) return;
        if (!exportFitReport(p, &why)) emit statusMessage(tr("Export failed: %1").arg(why));
        else emit statusMessage(tr("Exported %1").arg(p));
    }
}

void IdentifyPanel::dragEnterEvent(QDragEnterEvent* e) {
    if (e->mimeData()->hasUrls()) e->acceptProposedAction();
}

void IdentifyPanel::dropEvent(QDropEvent* e) {
    QStringList files;
    for (const QUrl& u : e->mimeData()->urls())
        if (u.isLocalFile() && !u.toLocalFile().endsWith(".json", Qt::CaseInsensitive)) files << u.toLocalFile();
    if (!files.isEmpty()) openImport(files);
    e->acceptProposedAction();
}

}  // namespace stickslip::gui
