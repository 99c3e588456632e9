#include "import_dialog.hpp"

#include <QCheckBox>
#include <QComboBox>
#include <QDialogButtonBox>
#include <QDir>
#include <QDoubleSpinBox>
#include <QFileDialog>
#include <QFileInfo>
#include <QFormLayout>
#include <QGridLayout>
#include <QGroupBox>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QLabel>
#include <QLineEdit>
#include <QListWidget>
#include <QPlainTextEdit>
#include <QPushButton>
#include <QSpinBox>
#include <QSplitter>
#include <QStyle>
#include <QTabWidget>
#include <QTableWidget>
#include <QTimer>
#include <QVBoxLayout>
#include <QtConcurrent/QtConcurrentRun>
#include <algorithm>
#include <cmath>

#include "core/io/csv_table.hpp"
#include "widgets/signal_compare_plot.hpp"

namespace stickslip::gui {

namespace {

const QString kNone = QStringLiteral("(none)");

struct SignalInfo {
    io::Signal signal;
    const char* label;   // in the paper's terms
    const char* symbol;
};

// Rows of the mapping grid, in a reading order (measured kinematics, forces, derived).
const std::array<SignalInfo, io::kSignalCount>& signalRows() {
    static const std::array<SignalInfo, io::kSignalCount> rows{{
        {io::Signal::Time, "Time", "t"},
        {io::Signal::StageDisp, "Stage displacement", "u"},
        {io::Signal::SliderDisp, "Slider displacement", "x"},
        {io::Signal::Slip, "Relative slip", "g = u \u2212 x"},
        {io::Signal::StageVel, "Stage velocity", "u\u0307"},
        {io::Signal::SliderVel, "Slider velocity", "x\u0307"},
        {io::Signal::RelVel, "Relative velocity", "V = u\u0307 \u2212 x\u0307"},
        {io::Signal::SliderAccel, "Slider acceleration", "x\u0308"},
        {io::Signal::Friction, "Friction force", "F"},
        {io::Signal::Normal, "Normal force", "t_N"},
        {io::Signal::Tension, "Band tension", "sets t_N"},
    }};
    return rows;
}

const SignalInfo& rowOf(io::Signal s) {
    for (const SignalInfo& r : signalRows())
        if (r.signal == s) return r;
    return signalRows()[0];
}

size_t idx(io::Signal s) { return static_cast<size_t>(s); }

// Units offered per SI unit (the combo is editable: anything the core's unit parser accepts
// with the right dimension works).
QStringList unitChoices(io::Signal s) {
    const QString si = QString::fromLatin1(io::signalUnit(s));
    if (si == QLatin1String("s")) return {"s", "ms"};
    if (si == QLatin1String("m")) return {"m", "mm", "um", "in"};
    if (si == QLatin1String("m/s")) return {"m/s", "mm/s", "in/s"};
    if (si == QLatin1String("N")) return {"N", "kN", "lbf"};
    return {"m/s^2", "mm/s^2"};
}

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

double median(std::vector<double> v) {
    if (v.empty()) return 0.0;
    const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
    std::nth_element(v.begin(), mid, v.end());
    return *mid;
}

QString q(const std::string& s) { return QString::fromStdString(s); }

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

// ---------------------------------------------------------------------------------------------
// Off-GUI-thread work: value types in, value types out.

FilePreview readFilePreview(const QString& path, int maxRows) {
    FilePreview p;
    p.path = path;
    io::CsvTable t;
    if (!io::readCsvTable(path.toStdString(), t, p.error)) {
        if (p.error.file.empty()) p.error.file = path.toStdString();
        return p;
    }
    p.ok = true;
    p.header = t.header;
    p.comments = t.comments;
    p.headerLine = t.headerLine;
    p.rowCount = t.rows();
    const size_t shown = std::min(p.rowCount, static_cast<size_t>(std::max(0, maxRows)));
    p.rows.assign(shown, std::vector<double>(t.header.size()));
    for (size_t i = 0; i < shown; ++i) {
        for (size_t j = 0; j < t.header.size(); ++j) p.rows[i][j] = t.columns[j][i];
        p.rowLines.push_back(i < t.rowLines.size() ? t.rowLines[i] : 0);
    }
    const size_t nc = t.header.size();
    p.medianStep.assign(nc, 0.0);
    p.firstNonIncreasing.assign(nc, 0);
    p.firstNonIncreasingLine.assign(nc, 0);
    p.nonIncreasingValues.assign(nc, {0.0, 0.0});
    for (size_t j = 0; j < nc; ++j) {
        const std::vector<double>& c = t.columns[j];
        for (size_t i = 1; i < c.size(); ++i)
            if (!(c[i] > c[i - 1])) {
                p.firstNonIncreasing[j] = i;
                p.firstNonIncreasingLine[j] = i < t.rowLines.size() ? t.rowLines[i] : 0;
                p.nonIncreasingValues[j] = {c[i - 1], c[i]};
                break;
            }
        if (p.firstNonIncreasing[j] == 0 && c.size() > 1) {
            std::vector<double> d(c.size() - 1);
            for (size_t i = 1; i < c.size(); ++i) d[i - 1] = c[i] - c[i - 1];
            p.medianStep[j] = median(std::move(d));
        }
    }
    return p;
}

CleaningPreview computeCleaningPreview(const QString& file, const io::DatasetOptions& options,
                                       const identify::PreprocessSettings& settings) {
    CleaningPreview out;
    out.file = file;
    io::DatasetOptions one = options;
    one.runSets.clear();
    io::Dataset ds;
    io::DatasetError err;
    if (!io::loadDataset({file.toStdString()}, one, ds, err)) {
        out.error = q(err.what());
        return out;
    }
    for (const std::string& spec : options.runSets) {  // those naming other files do not apply
        std::string ignored;
        io::applyRunSet(ds, spec, &ignored);
    }
    out.raw = std::move(ds.runs.front());
    std::string why;
    if (!identify::preprocessRun(out.raw, settings, out.clean, &why)) {
        out.error = q(why);
        return out;
    }
    out.ok = true;
    return out;
}

// ---------------------------------------------------------------------------------------------

ImportDialog::ImportDialog(const QStringList& files, QWidget* parent) : QDialog(parent) {
    setWindowTitle(tr("Import measured runs"));
    setSizeGripEnabled(true);
    cleaningTimer_ = new QTimer(this);
    cleaningTimer_->setSingleShot(true);
    cleaningTimer_->setInterval(120);
    connect(cleaningTimer_, &QTimer::timeout, this, &ImportDialog::startCleaning);
    connect(&scanWatcher_, &QFutureWatcher<std::vector<FilePreview>>::finished, this, &ImportDialog::onScanFinished);
    connect(&cleaningWatcher_, &QFutureWatcher<CleaningPreview>::finished, this, &ImportDialog::onCleaningFinished);
    connect(&loadWatcher_, &QFutureWatcher<LoadResult>::finished, this, &ImportDialog::onLoadFinished);
    buildUi();
    setPreprocessSettings(identify::PreprocessSettings{});
    // A manifest.json next to the files (as in the synthetic datasets) is offered by default.
    if (!files.isEmpty()) {
        const QDir dir = QFileInfo(files.front()).absoluteDir();
        bool sameDir = true;
        for (const QString& f : files) sameDir = sameDir && QFileInfo(f).absoluteDir() == dir;
        const QString m = dir.filePath(QStringLiteral("manifest.json"));
        if (sameDir && QFileInfo::exists(m)) manifest_->setText(m);
    }
    setFiles(files);
}

ImportDialog::~ImportDialog() {
    // Background jobs hold copies of their inputs only; wait so none outlives the dialog.
    scanWatcher_.waitForFinished();
    cleaningWatcher_.waitForFinished();
    loadWatcher_.waitForFinished();
}

// --- UI ----------------------------------------------------------------------------------------

void ImportDialog::buildUi() {
    auto* splitter = new QSplitter(Qt::Horizontal, this);
    splitter->setChildrenCollapsible(false);
    auto* tabs = new QTabWidget;
    tabs->addTab(buildColumnsPage(), tr("Columns && units"));
    tabs->addTab(buildCleaningPage(), tr("Cleaning"));
    splitter->addWidget(buildFilesPanel());
    splitter->addWidget(tabs);
    splitter->setStretchFactor(0, 0);
    splitter->setStretchFactor(1, 1);
    splitter->setSizes({270, 950});

    message_ = new QLabel;
    message_->setWordWrap(true);
    message_->setTextInteractionFlags(Qt::TextSelectableByMouse);
    message_->setMinimumHeight(fontMetrics().height() * 2 + 6);
    message_->setAlignment(Qt::AlignLeft | Qt::AlignVCenter);

    auto* buttons = new QDialogButtonBox(QDialogButtonBox::Ok | QDialogButtonBox::Cancel);
    okButton_ = buttons->button(QDialogButtonBox::Ok);
    okButton_->setText(tr("Load"));
    okButton_->setEnabled(false);
    connect(buttons, &QDialogButtonBox::accepted, this, &ImportDialog::accept);
    connect(buttons, &QDialogButtonBox::rejected, this, &ImportDialog::reject);

    auto* bottom = new QHBoxLayout;
    bottom->addWidget(message_, 1);
    bottom->addWidget(buttons, 0, Qt::AlignBottom);

    auto* top = new QVBoxLayout(this);
    top->addWidget(splitter, 1);
    top->addLayout(bottom);
    resize(1220, 760);
}

QWidget* ImportDialog::buildFilesPanel() {
    auto* panel = new QWidget;
    panel->setMaximumWidth(340);
    auto* layout = new QVBoxLayout(panel);
    layout->setContentsMargins(0, 0, 6, 0);

    auto* filesBox = new QGroupBox(tr("Data files"));
    auto* fl = new QVBoxLayout(filesBox);
    fileList_ = new QListWidget;
    fileList_->setSelectionMode(QAbstractItemView::SingleSelection);
    fileList_->setAlternatingRowColors(true);
    fileList_->setMinimumHeight(150);
    addButton_ = new QPushButton(tr("Add\u2026"));
    removeButton_ = new QPushButton(tr("Remove"));
    auto* fb = new QHBoxLayout;
    fb->addWidget(addButton_);
    fb->addWidget(removeButton_);
    fb->addStretch(1);
    fl->addWidget(fileList_, 1);
    fl->addLayout(fb);
    connect(addButton_, &QPushButton::clicked, this, &ImportDialog::addFilesClicked);
    connect(removeButton_, &QPushButton::clicked, this, &ImportDialog::removeFileClicked);
    connect(fileList_, &QListWidget::currentRowChanged, this, [this](int) {
        removeButton_->setEnabled(fileList_->currentRow() >= 0);
        updatePreviewTable();
        scheduleCleaning();
    });

    auto* runBox = new QGroupBox(tr("Run settings"));
    auto* rf = new QFormLayout(runBox);
    rf->setFieldGrowthPolicy(QFormLayout::AllNonFixedFieldsGrow);
    manifest_ = new QLineEdit;
    manifest_->setPlaceholderText(tr("optional manifest.json"));
    manifest_->setClearButtonEnabled(true);
    auto* browse = new QPushButton(tr("\u2026"));
    browse->setFixedWidth(32);
    browse->setToolTip(tr("Choose a manifest file"));
    auto* ml = new QHBoxLayout;
    ml->setContentsMargins(0, 0, 0, 0);
    ml->addWidget(manifest_, 1);
    ml->addWidget(browse);
    rf->addRow(tr("Manifest:"), ml);
    connect(browse, &QPushButton::clicked, this, &ImportDialog::browseManifest);
    connect(manifest_, &QLineEdit::textChanged, this, &ImportDialog::settingsChanged);

    runSets_ = new QPlainTextEdit;
    runSets_->setPlaceholderText(tr("one per line, e.g.\nrun_01.csv:tN=6.2N\nrun_02.csv:k=8.4kN/m"));
    runSets_->setToolTip(tr("Known settings of single runs, as the command line's --run-set FILE:KEY=VALUE "
                            "(keys k, A, f, tN, m, c, \u2026; values may carry a unit). They override the "
                            "manifest and the columns."));
    runSets_->setTabChangesFocus(true);
    runSets_->setMaximumHeight(fontMetrics().lineSpacing() * 5 + 12);
    rf->addRow(tr("Per run:"), runSets_);
    connect(runSets_, &QPlainTextEdit::textChanged, this, &ImportDialog::settingsChanged);

    setup_ = new QComboBox;
    setup_->addItem(tr("Automatic"));
    setup_->addItem(tr("Prescribed slip (slider held)"));
    setup_->addItem(tr("Dynamics (slider on spring)"));
    setup_->setToolTip(tr("Automatic: dynamics when the files have a slider displacement, else prescribed slip "
                          "(as the command line)."));
    setupHint_ = new QLabel;
    setupHint_->setWordWrap(true);
    setupHint_->setStyleSheet(QStringLiteral("color: palette(mid);"));
    rf->addRow(tr("Set-up:"), setup_);
    rf->addRow(QString(), setupHint_);
    connect(setup_, QOverload<int>::of(&QComboBox::currentIndexChanged), this, [this](int) {
        updateSetupHint();
        revalidate();
    });

    layout->addWidget(filesBox, 1);
    layout->addWidget(runBox, 0);
    return panel;
}

QWidget* ImportDialog::buildColumnsPage() {
    auto* page = new QWidget;
    auto* layout = new QHBoxLayout(page);

    auto* mapBox = new QGroupBox(tr("Signals"));
    auto* grid = new QGridLayout(mapBox);
    grid->setHorizontalSpacing(8);
    grid->setVerticalSpacing(4);
    auto header = [](const QString& text) {
        auto* l = new QLabel(QStringLiteral("<b>%1</b>").arg(text));
        return l;
    };
    grid->addWidget(header(tr("Signal")), 0, 0, 1, 2);
    grid->addWidget(header(tr("Column")), 0, 2);
    grid->addWidget(header(tr("Unit")), 0, 3);
    int row = 1;
    for (const SignalInfo& r : signalRows()) {
        auto* name = new QLabel(QString::fromUtf8(r.label));
        auto* sym = new QLabel(QString::fromUtf8(r.symbol));
        sym->setStyleSheet(QStringLiteral("color: palette(mid);"));
        auto* col = new QComboBox;
        col->setSizeAdjustPolicy(QComboBox::AdjustToMinimumContentsLengthWithIcon);
        col->setMinimumContentsLength(14);
        col->setToolTip(tr("Column for %1 (default name \"%2\"; key \"%3\" on the command line)")
                            .arg(QString::fromUtf8(r.label).toLower(), QString::fromLatin1(io::defaultColumn(r.signal)),
                                 QString::fromLatin1(io::signalKey(r.signal))));
        auto* unit = new QComboBox;
        unit->setEditable(true);
        unit->addItems(unitChoices(r.signal));
        unit->setMinimumContentsLength(5);
        unit->setSizeAdjustPolicy(QComboBox::AdjustToMinimumContentsLengthWithIcon);
        unit->setToolTip(tr("Unit of the column (converted to %1); any unit of the right dimension may be typed")
                             .arg(QString::fromLatin1(io::signalUnit(r.signal))));
        columnCombos_[idx(r.signal)] = col;
        unitCombos_[idx(r.signal)] = unit;
        grid->addWidget(name, row, 0);
        grid->addWidget(sym, row, 1);
        grid->addWidget(col, row, 2);
        grid->addWidget(unit, row, 3);
        const io::Signal s = r.signal;
        connect(col, QOverload<int>::of(&QComboBox::currentIndexChanged), this, [this, s](int) { columnChosen(s); });
        connect(unit, &QComboBox::currentTextChanged, this, [this](const QString&) { settingsChanged(); });
        ++row;
    }
    grid->setRowStretch(row, 1);
    mapBox->setSizePolicy(QSizePolicy::Maximum, QSizePolicy::Preferred);
    mapBox->setMaximumWidth(mapBox->sizeHint().width());

    auto* previewBox = new QGroupBox(tr("Preview"));
    auto* pl = new QVBoxLayout(previewBox);
    previewCaption_ = new QLabel;
    previewCaption_->setWordWrap(true);
    preview_ = new QTableWidget;
    preview_->setEditTriggers(QAbstractItemView::NoEditTriggers);
    preview_->setSelectionMode(QAbstractItemView::NoSelection);
    preview_->setAlternatingRowColors(true);
    preview_->verticalHeader()->setDefaultSectionSize(fontMetrics().height() + 4);
    preview_->horizontalHeader()->setDefaultAlignment(Qt::AlignCenter);
    pl->addWidget(previewCaption_);
    pl->addWidget(preview_, 1);
    previewBox->setMinimumWidth(420);

    layout->addWidget(mapBox, 0);
    layout->addWidget(previewBox, 1);
    return page;
}

QWidget* ImportDialog::buildCleaningPage() {
    auto* page = new QWidget;
    auto* layout = new QHBoxLayout(page);
    auto* settings = new QWidget;
    auto* sl = new QVBoxLayout(settings);
    sl->setContentsMargins(0, 0, 0, 0);

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

    auto* low = new QGroupBox(tr("Butterworth low-pass (zero-phase)"));
    auto* lf = new QFormLayout(low);
    lowPass_ = new QCheckBox(tr("On"));
    lowPassHz_ = doubleBox(0.01, 1e5, 1, tr(" Hz"));
    lowPassOrder_ = intBox(1, 12);
    lf->addRow(lowPass_);
    lf->addRow(tr("Cut-off:"), lowPassHz_);
    lf->addRow(tr("Order:"), lowPassOrder_);

    auto* deriv = new QGroupBox(tr("Velocities and input"));
    auto* df = new QFormLayout(deriv);
    sgHalf_ = intBox(1, 500, tr(" samples"));
    sgHalf_->setToolTip(tr("Savitzky\u2013Golay half window: the window is 2\u00b7h+1 samples"));
    sgOrder_ = intBox(1, 20);
    stageHarmonics_ = intBox(0, 50);
    stageHarmonics_->setToolTip(tr("Dynamics runs: the stage displacement driving the model is replaced by its "
                                   "Fourier fit with this many harmonics (0: the filtered measurement)"));
    resample_ = new QCheckBox(tr("Resample irregular time steps"));
    df->addRow(tr("SG half window:"), sgHalf_);
    df->addRow(tr("SG order:"), sgOrder_);
    df->addRow(tr("Stage harmonics:"), stageHarmonics_);
    df->addRow(resample_);

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

    sl->addWidget(band);
    sl->addWidget(low);
    sl->addWidget(deriv);
    sl->addWidget(trim);
    sl->addStretch(1);
    settings->setMaximumWidth(330);

    for (QCheckBox* c : {bandStop_, lowPass_, steadyTrim_, resample_})
        connect(c, &QCheckBox::toggled, this, &ImportDialog::settingsChanged);
    for (QDoubleSpinBox* b : {bandCenter_, bandWidth_, lowPassHz_, trimStart_, trimEnd_, trimFraction_})
        connect(b, QOverload<double>::of(&QDoubleSpinBox::valueChanged), this, &ImportDialog::settingsChanged);
    for (QSpinBox* b : {bandOrder_, lowPassOrder_, sgHalf_, sgOrder_, stageHarmonics_})
        connect(b, QOverload<int>::of(&QSpinBox::valueChanged), this, &ImportDialog::settingsChanged);

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
    cleaningStatus_ = new QLabel;
    cleaningStatus_->setWordWrap(true);
    plot_ = new widgets::SignalComparePlot;
    plot_->setMinimumSize(420, 300);
    pl->addLayout(pick);
    pl->addWidget(plot_, 1);
    pl->addWidget(cleaningStatus_);
    connect(plotSignal_, QOverload<int>::of(&QComboBox::currentIndexChanged), this, [this](int) {
        if (!populating_) showCleaning();
    });

    layout->addWidget(settings, 0);
    layout->addWidget(plotBox, 1);
    return page;
}

// --- files -------------------------------------------------------------------------------------

QStringList ImportDialog::files() const {
    QStringList out;
    for (int i = 0; i < fileList_->count(); ++i) out << fileList_->item(i)->data(Qt::UserRole).toString();
    return out;
}

void ImportDialog::setFiles(const QStringList& list) {
    const QSignalBlocker block(fileList_);
    fileList_->clear();
    for (const QString& f : list) {
        if (files().contains(f)) continue;
        auto* item = new QListWidgetItem(QFileInfo(f).fileName(), fileList_);
        item->setData(Qt::UserRole, f);
        item->setToolTip(f);
    }
    if (fileList_->count() > 0) fileList_->setCurrentRow(0);
    removeButton_->setEnabled(fileList_->currentRow() >= 0);
    scanFiles();
    settingsChanged();
}

void ImportDialog::addFilesClicked() {
    const QStringList more = QFileDialog::getOpenFileNames(this, tr("Add measured runs"), QString(),
                                                           tr("CSV files (*.csv *.txt *.tsv);;All files (*)"));
    if (more.isEmpty()) return;
    QStringList all = files();
    for (const QString& f : more)
        if (!all.contains(f)) all << f;
    const int keep = fileList_->currentRow();
    setFiles(all);
    if (keep >= 0) setSelectedFile(keep);
}

void ImportDialog::removeFileClicked() {
    const int row = fileList_->currentRow();
    if (row < 0) return;
    QStringList all = files();
    all.removeAt(row);
    setFiles(all);
    if (!all.isEmpty()) setSelectedFile(std::min(row, static_cast<int>(all.size()) - 1));
}

void ImportDialog::setSelectedFile(int row) { fileList_->setCurrentRow(row); }

void ImportDialog::browseManifest() {
    const QString start = manifest_->text().isEmpty() && !files().isEmpty() ? QFileInfo(files().front()).absolutePath()
                                                                             : manifest_->text();
    const QString f = QFileDialog::getOpenFileName(this, tr("Manifest"), start, tr("JSON (*.json);;All files (*)"));
    if (!f.isEmpty()) manifest_->setText(f);
}

void ImportDialog::scanFiles() {
    if (scanning_) {
        rescanPending_ = true;
        return;
    }
    QStringList todo;
    for (const QString& f : files())
        if (!previews_.count(f)) todo << f;
    if (todo.isEmpty()) return;
    scanning_ = true;
    scanWatcher_.setFuture(QtConcurrent::run([todo] {
        std::vector<FilePreview> out;
        for (const QString& f : todo) out.push_back(readFilePreview(f));
        return out;
    }));
    revalidate();
}

void ImportDialog::onScanFinished() {
    scanning_ = false;
    for (FilePreview& p : scanWatcher_.result()) previews_[p.path] = std::move(p);
    if (rescanPending_) {
        rescanPending_ = false;
        scanFiles();
    }
    populateColumnCombos();
    updatePreviewTable();
    settingsChanged();
    emit previewsUpdated();
}

const FilePreview* ImportDialog::selectedPreview() const {
    const int row = fileList_->currentRow();
    if (row < 0) return nullptr;
    const auto it = previews_.find(fileList_->item(row)->data(Qt::UserRole).toString());
    return it == previews_.end() ? nullptr : &it->second;
}

QStringList ImportDialog::columnUnion() const {
    QStringList cols;
    for (const QString& f : files()) {
        const auto it = previews_.find(f);
        if (it == previews_.end() || !it->second.ok) continue;
        for (const std::string& h : it->second.header)
            if (!cols.contains(q(h))) cols << q(h);
    }
    return cols;
}

// --- mapping -----------------------------------------------------------------------------------

void ImportDialog::populateColumnCombos() {
    const QStringList cols = columnUnion();
    populating_ = true;
    for (const SignalInfo& r : signalRows()) {
        QComboBox* box = columnCombos_[idx(r.signal)];
        const QSignalBlocker block(box);
        box->clear();
        box->addItem(kNone);
        box->addItems(cols);
        const QString& want = chosen_[idx(r.signal)];
        const QString def = QString::fromLatin1(io::defaultColumn(r.signal));
        QString pick = kNone;
        if (want.isNull()) {
            if (cols.contains(def)) pick = def;
        } else if (!want.isEmpty()) {
            if (!cols.contains(want)) box->addItem(want);  // keeps the user's choice; validation names it
            pick = want;
        }
        box->setCurrentText(pick);
    }
    populating_ = false;
}

void ImportDialog::columnChosen(io::Signal s) {
    if (populating_) return;
    const QString t = columnCombos_[idx(s)]->currentText();
    chosen_[idx(s)] = t == kNone ? QStringLiteral("") : t;
    updatePreviewTable();
    settingsChanged();
}

void ImportDialog::setColumn(io::Signal s, const QString& column) {
    QComboBox* box = columnCombos_[idx(s)];
    const QString t = column.isEmpty() ? kNone : column;
    if (box->findText(t) < 0) box->addItem(t);
    box->setCurrentText(t);
    columnChosen(s);
}

QString ImportDialog::column(io::Signal s) const {
    const QString t = columnCombos_[idx(s)]->currentText();
    return t == kNone ? QString() : t;
}

void ImportDialog::setUnit(io::Signal s, const QString& unit) { unitCombos_[idx(s)]->setCurrentText(unit); }

QString ImportDialog::unit(io::Signal s) const { return unitCombos_[idx(s)]->currentText().trimmed(); }

io::ColumnMapping ImportDialog::mapping(QString* error) const {
    io::ColumnMapping m;
    const QStringList fileColumns = columnUnion();
    for (const SignalInfo& r : signalRows()) {
        const QString col = column(r.signal);
        const std::string key = io::signalKey(r.signal);
        if (col.isEmpty()) {
            // "(none)" although a file has the default column: do not read it (time must be read).
            if (r.signal != io::Signal::Time && fileColumns.contains(QLatin1String(io::defaultColumn(r.signal))))
                m.columns[r.signal] = io::kNotMapped;
        } else if (col != QLatin1String(io::defaultColumn(r.signal))) {
            std::string why;
            if (!m.addColumns(key + "=" + col.toStdString(), &why) && error && error->isEmpty())
                *error = tr("Column of %1: %2").arg(QString::fromUtf8(r.label).toLower(), q(why));
        }
        const QString u = unit(r.signal);
        if (u.isEmpty()) {
            if (error && error->isEmpty()) *error = tr("Unit of %1 is empty").arg(QString::fromUtf8(r.label).toLower());
        } else if (u != QLatin1String(io::signalUnit(r.signal))) {
            std::string why;
            if (!m.addUnits(key + "=" + u.toStdString(), &why) && error && error->isEmpty())
                *error = tr("Unit of %1: %2").arg(QString::fromUtf8(r.label).toLower(), q(why));
        }
    }
    return m;
}

std::vector<io::Signal> ImportDialog::unmappedSignals() const {
    std::vector<io::Signal> out;
    const QStringList cols = columnUnion();
    for (const SignalInfo& r : signalRows())
        if (column(r.signal).isEmpty() && cols.contains(QLatin1String(io::defaultColumn(r.signal))))
            out.push_back(r.signal);
    std::sort(out.begin(), out.end());
    return out;
}

QStringList ImportDialog::runSetLines() const {
    QStringList out;
    for (const QString& line : runSets_->toPlainText().split(QLatin1Char('\n'))) {
        const QString t = line.trimmed();
        if (!t.isEmpty() && !t.startsWith(QLatin1Char('#'))) out << t;
    }
    return out;
}

void ImportDialog::setManifestPath(const QString& path) { manifest_->setText(path); }

void ImportDialog::setRunSets(const QStringList& specs) { runSets_->setPlainText(specs.join(QLatin1Char('\n'))); }

void ImportDialog::setSetupChoice(int index) { setup_->setCurrentIndex(index); }

io::DatasetOptions ImportDialog::datasetOptions() const {
    io::DatasetOptions o;
    o.mapping = mapping(nullptr);
    o.manifestPath = manifest_->text().trimmed().toStdString();
    for (const QString& s : runSetLines()) o.runSets.push_back(s.toStdString());
    return o;
}

SetupKind ImportDialog::setup() const {
    if (setup_->currentIndex() == 1) return SetupKind::Prescribed;
    if (setup_->currentIndex() == 2) return SetupKind::Dynamics;
    if (!dataset_.runs.empty()) return dataset_.runs.front().has(io::Signal::SliderDisp) ? SetupKind::Dynamics : SetupKind::Prescribed;
    const QStringList f = files();
    const QString slider = column(io::Signal::SliderDisp);
    if (f.isEmpty() || slider.isEmpty()) return SetupKind::Prescribed;
    const auto it = previews_.find(f.front());
    if (it == previews_.end() || !it->second.ok) return SetupKind::Prescribed;
    const auto& h = it->second.header;
    return std::find(h.begin(), h.end(), slider.toStdString()) != h.end() ? SetupKind::Dynamics : SetupKind::Prescribed;
}

void ImportDialog::updateSetupHint() {
    if (setup_->currentIndex() != 0) {
        setupHint_->clear();
        return;
    }
    setupHint_->setText(setup() == SetupKind::Dynamics ? tr("\u2192 dynamics (slider displacement present)")
                                                       : tr("\u2192 prescribed slip (no slider displacement)"));
}

// --- cleaning settings ------------------------------------------------------------------------

identify::PreprocessSettings ImportDialog::preprocessSettings() const {
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
    s.trim.start_s = trimStart_->value();
    s.trim.end_s = trimEnd_->value();
    s.trim.steadyAmplitude = steadyTrim_->isChecked();
    s.trim.amplitudeFraction = trimFraction_->value();
    return s;
}

void ImportDialog::setPreprocessSettings(const identify::PreprocessSettings& s) {
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
    trimStart_->setValue(s.trim.start_s);
    trimEnd_->setValue(s.trim.end_s);
    steadyTrim_->setChecked(s.trim.steadyAmplitude);
    trimFraction_->setValue(s.trim.amplitudeFraction);
    populating_ = false;
    settingsChanged();
}

void ImportDialog::updateEnabledStates() {
    for (QWidget* w : std::initializer_list<QWidget*>{bandCenter_, bandWidth_, bandOrder_}) w->setEnabled(bandStop_->isChecked());
    for (QWidget* w : std::initializer_list<QWidget*>{lowPassHz_, lowPassOrder_}) w->setEnabled(lowPass_->isChecked());
    trimFraction_->setEnabled(steadyTrim_->isChecked());
}

// --- validation ---------------------------------------------------------------------------------

double ImportDialog::timeScale() const {
    io::ColumnMapping m = mapping(nullptr);
    const auto it = m.scaleToSI.find(io::Signal::Time);
    return it == m.scaleToSI.end() ? 1.0 : it->second;
}

QString ImportDialog::validateFilesAndMapping() const {
    const QStringList f = files();
    if (f.isEmpty()) return tr("Add at least one data file (CSV with a header line of column names).");
    for (const QString& path : f) {
        const auto it = previews_.find(path);
        if (it != previews_.end() && !it->second.ok) return q(it->second.error.what());
    }
    const QString time = column(io::Signal::Time);
    if (time.isEmpty()) return tr("Choose the column that holds time: a time column is required.");
    QString err;
    mapping(&err);
    if (!err.isEmpty()) return err;
    for (const QString& path : f) {
        const auto it = previews_.find(path);
        if (it == previews_.end()) continue;  // still being read
        const FilePreview& p = it->second;
        QString have;
        for (const std::string& h : p.header) have += (have.isEmpty() ? "" : ", ") + q(h);
        for (const SignalInfo& r : signalRows()) {
            const QString col = column(r.signal);
            const bool explicitChoice = !col.isEmpty() && col != QLatin1String(io::defaultColumn(r.signal));
            if (!explicitChoice && r.signal != io::Signal::Time) continue;
            if (std::find(p.header.begin(), p.header.end(), col.toStdString()) == p.header.end())
                return tr("%1:%2: no column '%3' for signal %4 (columns: %5)")
                    .arg(path)
                    .arg(p.headerLine)
                    .arg(col, QString::fromLatin1(io::signalKey(r.signal)), have);
        }
        if (p.rowCount < 8)
            return tr("%1:%2: too few data rows (%3); need at least 8").arg(path).arg(p.headerLine).arg(p.rowCount);
        const auto j = static_cast<size_t>(std::find(p.header.begin(), p.header.end(), time.toStdString()) - p.header.begin());
        if (p.firstNonIncreasing[j] > 0) {
            const double s = timeScale();
            return tr("%1:%2:%3: time does not increase (%4 s then %5 s)")  // worded as the core's loadRun
                .arg(path)
                .arg(p.firstNonIncreasingLine[j])
                .arg(j + 1)
                .arg(q(std::to_string(p.nonIncreasingValues[j].first * s)), q(std::to_string(p.nonIncreasingValues[j].second * s)));
        }
    }
    return QString();
}

QString ImportDialog::validateManifestAndRunSets() {
    const QString path = manifest_->text().trimmed();
    if (!path.isEmpty()) {
        if (path != manifestReadPath_) {  // tiny JSON file: read once per path
            manifestReadPath_ = path;
            manifestData_ = io::Manifest{};
            manifestError_ = io::DatasetError{};
            manifestOk_ = io::readManifest(path.toStdString(), manifestData_, manifestError_);
        }
        if (!manifestOk_) return tr("Manifest %1").arg(q(manifestError_.what()));
        for (const QString& f : files()) {
            const std::string name = QFileInfo(f).fileName().toStdString();
            if (!manifestData_.runs.count(name))
                return tr("%1: the manifest lists no run for data file '%2'").arg(path, q(name));
        }
    }
    io::Dataset names;
    for (const QString& f : files()) {
        io::Run r;
        r.file = f.toStdString();
        names.runs.push_back(std::move(r));
    }
    for (const QString& spec : runSetLines()) {
        std::string why;
        if (!io::applyRunSet(names, spec.toStdString(), &why)) return tr("Per-run settings: %1").arg(q(why));
    }
    return QString();
}

QString ImportDialog::validateCleaning() const {
    double fsMin = 0.0;
    const QString time = column(io::Signal::Time);
    for (const QString& f : files()) {
        const auto it = previews_.find(f);
        if (it == previews_.end() || !it->second.ok) continue;
        const auto& h = it->second.header;
        const auto j = static_cast<size_t>(std::find(h.begin(), h.end(), time.toStdString()) - h.begin());
        if (j >= h.size() || !(it->second.medianStep[j] > 0)) continue;
        const double fs = 1.0 / (it->second.medianStep[j] * timeScale());
        fsMin = fsMin > 0 ? std::min(fsMin, fs) : fs;
    }
    if (!(fsMin > 0)) return QString();
    const std::vector<std::string> bad = preprocessSettings().validate(fsMin);
    if (bad.empty()) return QString();
    QString all;
    for (const std::string& b : bad) all += (all.isEmpty() ? "" : "; ") + q(b);
    return tr("Cleaning (sampling at %1 Hz): %2").arg(fsMin, 0, 'g', 6).arg(all);
}

QString ImportDialog::summaryText() const {
    const QStringList f = files();
    size_t rows = 0;
    for (const QString& p : f) {
        const auto it = previews_.find(p);
        if (it != previews_.end()) rows += it->second.rowCount;
    }
    QString s = tr("%n file(s), %1 data rows", "", static_cast<int>(f.size())).arg(rows);
    s += tr(" \u00b7 set-up: %1").arg(setup() == SetupKind::Dynamics ? tr("dynamics") : tr("prescribed slip"));
    const auto unm = unmappedSignals();
    if (!unm.empty()) {
        QStringList names;
        for (io::Signal u : unm) names << QString::fromLatin1(io::signalKey(u));
        s += tr(" \u00b7 not used: %1").arg(names.join(QStringLiteral(", ")));
    }
    return s;
}

bool ImportDialog::isBusy() const {
    // Flags cleared when the finished signal is handled (not when the thread ends), so idle
    // means every result has reached the dialog.
    return scanning_ || rescanPending_ || cleaningRunning_ || cleaningTimer_->isActive() || cleaningPending_ || loading_;
}

QString ImportDialog::errorText() const { return error_; }

void ImportDialog::settingsChanged() {
    if (populating_) return;
    loadError_.clear();
    updateEnabledStates();
    updateSetupHint();
    revalidate();
    scheduleCleaning();
}

void ImportDialog::revalidate() {
    QString err = validateFilesAndMapping();
    if (err.isEmpty()) err = validateManifestAndRunSets();
    if (err.isEmpty()) err = validateCleaning();
    if (err.isEmpty()) err = loadError_;
    error_ = err;
    bool scanning = scanning_ || rescanPending_;
    for (const QString& f : files()) scanning = scanning || !previews_.count(f);
    valid_ = err.isEmpty() && !scanning && !loading_;
    okButton_->setEnabled(valid_);
    if (!err.isEmpty()) {
        message_->setStyleSheet(QStringLiteral("QLabel { color: #b00020; }"));
        message_->setText(QStringLiteral("\u26a0 ") + err);
    } else if (loading_) {
        message_->setStyleSheet(QString());
        message_->setText(tr("Loading %n file(s)\u2026", "", static_cast<int>(files().size())));
    } else if (scanning) {
        message_->setStyleSheet(QString());
        message_->setText(tr("Reading files\u2026"));
    } else {
        message_->setStyleSheet(QStringLiteral("QLabel { color: palette(dark); }"));
        message_->setText(summaryText());
    }
}

// --- preview table ------------------------------------------------------------------------------

void ImportDialog::updatePreviewTable() {
    const FilePreview* p = selectedPreview();
    preview_->clear();
    if (!p) {
        preview_->setRowCount(0);
        preview_->setColumnCount(0);
        previewCaption_->setText(files().isEmpty() ? tr("No file.") : tr("Reading\u2026"));
        return;
    }
    const QString name = QFileInfo(p->path).fileName();
    if (!p->ok) {
        preview_->setRowCount(0);
        preview_->setColumnCount(0);
        previewCaption_->setText(tr("<b>%1</b> cannot be read.").arg(name.toHtmlEscaped()));
        return;
    }
    // Which signal each column feeds (by the current mapping).
    std::map<std::string, QStringList> feeds;
    for (const SignalInfo& r : signalRows()) {
        const QString col = column(r.signal);
        if (!col.isEmpty()) feeds[col.toStdString()] << QString::fromUtf8(r.symbol).section(QLatin1Char(' '), 0, 0);
    }
    const int nc = static_cast<int>(p->header.size());
    preview_->setColumnCount(nc);
    preview_->setRowCount(static_cast<int>(p->rows.size()));
    for (int j = 0; j < nc; ++j) {
        const auto f = feeds.find(p->header[static_cast<size_t>(j)]);
        const bool used = f != feeds.end();
        auto* h = new QTableWidgetItem(used ? QStringLiteral("%1\n\u2192 %2").arg(q(p->header[static_cast<size_t>(j)]), f->second.join(", "))
                                            : QStringLiteral("%1\n(unused)").arg(q(p->header[static_cast<size_t>(j)])));
        QFont font = h->font();
        font.setBold(used);
        h->setFont(font);
        if (!used) h->setForeground(palette().brush(QPalette::Disabled, QPalette::Text));
        preview_->setHorizontalHeaderItem(j, h);
    }
    for (size_t i = 0; i < p->rows.size(); ++i) {
        preview_->setVerticalHeaderItem(static_cast<int>(i), new QTableWidgetItem(QString::number(p->rowLines[i])));
        for (int j = 0; j < nc; ++j) {
            auto* item = new QTableWidgetItem(QString::number(p->rows[i][static_cast<size_t>(j)], 'g', 7));
            item->setTextAlignment(Qt::AlignRight | Qt::AlignVCenter);
            preview_->setItem(static_cast<int>(i), j, item);
        }
    }
    preview_->resizeColumnsToContents();
    QString caption = tr("<b>%1</b>: %2 data rows \u00d7 %3 columns; first %4 shown (row labels are file lines).")
                          .arg(name.toHtmlEscaped())
                          .arg(p->rowCount)
                          .arg(nc)
                          .arg(p->rows.size());
    previewCaption_->setText(caption);
    QString comments;
    for (const std::string& c : p->comments) comments += (comments.isEmpty() ? "" : "\n") + q(c);
    previewCaption_->setToolTip(comments);
}

// --- raw vs cleaned ------------------------------------------------------------------------------

void ImportDialog::scheduleCleaning() { cleaningTimer_->start(); }

void ImportDialog::startCleaning() {
    if (cleaningRunning_) {
        cleaningPending_ = true;
        return;
    }
    cleaningPending_ = false;
    const FilePreview* p = selectedPreview();
    ++cleaningGeneration_;
    QString err = validateFilesAndMapping();
    if (!p || !p->ok || !err.isEmpty()) {
        cleaning_ = CleaningPreview{};
        cleaning_.generation = cleaningGeneration_;
        plot_->clearAll();
        cleaningStatus_->setText(p ? tr("Fix the problem below to see the cleaned signals.") : QString());
        emit cleaningUpdated();
        return;
    }
    cleaningStatus_->setText(tr("Cleaning %1\u2026").arg(QFileInfo(p->path).fileName()));
    const quint64 gen = cleaningGeneration_;
    cleaningWatcher_.setFuture(QtConcurrent::run(
        [gen, file = p->path, opts = datasetOptions(), settings = preprocessSettings()] {
            CleaningPreview r = computeCleaningPreview(file, opts, settings);
            r.generation = gen;
            return r;
        }));
    cleaningRunning_ = true;
}

void ImportDialog::onCleaningFinished() {
    CleaningPreview r = cleaningWatcher_.result();
    cleaningRunning_ = false;
    if (cleaningPending_ || cleaningTimer_->isActive() || r.generation != cleaningGeneration_) {
        if (cleaningPending_) startCleaning();  // stale: settings changed meanwhile
        return;
    }
    cleaning_ = std::move(r);
    // The signals to choose from: those of the cleaned run (derived ones included).
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
    showCleaning();
    emit cleaningUpdated();
}

void ImportDialog::setPlotSignal(io::Signal s) {
    const int at = plotSignal_->findData(static_cast<int>(s));
    if (at >= 0) plotSignal_->setCurrentIndex(at);
}

void ImportDialog::showCleaning() {
    if (!cleaning_.ok) {
        plot_->clearAll();
        cleaningStatus_->setStyleSheet(QStringLiteral("QLabel { color: #b26b00; }"));
        cleaningStatus_->setText(cleaning_.error.isEmpty() ? QString() : tr("Cannot clean this run: %1").arg(cleaning_.error));
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
    cleaningStatus_->setStyleSheet(QStringLiteral("QLabel { color: palette(dark); }"));
    QString status = tr("%1: step %2 ms%3, fit window %4\u2013%5 s (%6 of %7 samples)")
                         .arg(cleaning_.raw.name().c_str())
                         .arg(c.dt_s * 1e3, 0, 'g', 4)
                         .arg(c.resampled ? tr(" (resampled)") : QString())
                         .arg(cmp.windowBegin_s, 0, 'f', 3)
                         .arg(cmp.windowEnd_s, 0, 'f', 3)
                         .arg(c.end - c.begin)
                         .arg(c.run.size());
    if (c.period_s > 0) status += tr(", drive period %1 s").arg(c.period_s, 0, 'g', 5);
    cleaningStatus_->setText(status);
    QString notes;
    for (const std::string& n : c.notes) notes += (notes.isEmpty() ? "" : "\n") + q(n);
    cleaningStatus_->setToolTip(notes);
}

// --- loading on OK -------------------------------------------------------------------------------

void ImportDialog::accept() {
    revalidate();
    if (!valid_ || loading_) return;
    loading_ = true;
    std::vector<std::string> paths;
    for (const QString& f : files()) paths.push_back(f.toStdString());
    loadWatcher_.setFuture(QtConcurrent::run([paths, opts = datasetOptions()] {
        LoadResult r;
        r.ok = io::loadDataset(paths, opts, r.dataset, r.error);
        return r;
    }));
    revalidate();
}

void ImportDialog::onLoadFinished() {
    LoadResult r = loadWatcher_.result();
    loading_ = false;
    if (!r.ok) {
        dataset_ = io::Dataset{};
        loadError_ = q(r.error.what());
        revalidate();
        emit loadFailed(loadError_);
        return;
    }
    dataset_ = std::move(r.dataset);
    revalidate();
    QDialog::accept();
}

}  // namespace stickslip::gui
