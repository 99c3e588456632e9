#include "import_dialog.hpp"

#include <QDialogButtonBox>
#include <QDir>
#include <QFileInfo>
#include <QHBoxLayout>
#include <QLabel>
#include <QPushButton>
#include <QSplitter>
#include <QTabWidget>
#include <QVBoxLayout>
#include <QtConcurrent/QtConcurrentRun>

#include "import_cleaning_page.hpp"
#include "import_columns_page.hpp"
#include "import_files_page.hpp"

namespace stickslip::gui {

namespace {

QString q(const std::string& s) { return QString::fromStdString(s); }

std::vector<std::string> toStd(const QStringList& list) {
    std::vector<std::string> out;
    for (const QString& s : list) out.push_back(s.toStdString());
    return out;
}

}  // namespace

ImportDialog::ImportDialog(const QStringList& files, QWidget* parent) : QDialog(parent) {
    setWindowTitle(tr("Import measured runs"));
    setSizeGripEnabled(true);
    connect(&loadWatcher_, &QFutureWatcher<LoadResult>::finished, this, &ImportDialog::onLoadFinished);
    buildUi();
    connectPages();
    setPreprocessSettings(identify::PreprocessSettings{});
    offerManifestNextTo(files);
    setFiles(files);
}

ImportDialog::~ImportDialog() {
    // The load holds copies of its inputs only; wait so it does not outlive the dialog (the
    // pages wait for their own jobs).
    loadWatcher_.waitForFinished();
}

// A manifest.json next to the files (as in the synthetic datasets) is offered by default.
void ImportDialog::offerManifestNextTo(const QStringList& files) {
    if (files.isEmpty()) return;
    const QDir dir = QFileInfo(files.front()).absoluteDir();
    bool sameDir = true;
    for (const QString& f : files) sameDir = sameDir && QFileInfo(f).absoluteDir() == dir;
    const QString m = dir.filePath(QStringLiteral("manifest.json"));
    if (sameDir && QFileInfo::exists(m)) filesPage_->setManifestPath(m);
}

// --- UI ----------------------------------------------------------------------------------------

void ImportDialog::buildUi() {
    auto* splitter = new QSplitter(Qt::Horizontal, this);
    splitter->setChildrenCollapsible(false);
    filesPage_ = new ImportFilesPage;
    columnsPage_ = new ImportColumnsPage;
    cleaningPage_ = new ImportCleaningPage;
    auto* tabs = new QTabWidget;
    tabs->addTab(columnsPage_, tr("Columns && units"));
    tabs->addTab(cleaningPage_, tr("Cleaning"));
    splitter->addWidget(filesPage_);
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

void ImportDialog::connectPages() {
    connect(filesPage_, &ImportFilesPage::filesChosen, this, [this](const QStringList& all, int row) {
        setFiles(all);
        if (row >= 0) setSelectedFile(row);
    });
    connect(filesPage_, &ImportFilesPage::selectionChanged, this, [this] {
        updatePreviewTable();
        cleaningPage_->schedule();
    });
    connect(filesPage_, &ImportFilesPage::runSettingsChanged, this, &ImportDialog::settingsChanged);
    connect(filesPage_, &ImportFilesPage::setupChoiceChanged, this, [this] {
        updateSetupHint();
        revalidate();
    });
    connect(filesPage_, &ImportFilesPage::scanStarted, this, &ImportDialog::revalidate);
    connect(filesPage_, &ImportFilesPage::scanFinished, this, &ImportDialog::onScanFinished);
    connect(columnsPage_, &ImportColumnsPage::columnChanged, this, [this] {
        updatePreviewTable();
        settingsChanged();
    });
    connect(columnsPage_, &ImportColumnsPage::unitChanged, this, &ImportDialog::settingsChanged);
    connect(cleaningPage_, &ImportCleaningPage::settingsChanged, this, &ImportDialog::settingsChanged);
    connect(cleaningPage_, &ImportCleaningPage::cleaningUpdated, this, &ImportDialog::cleaningUpdated);
    // Asked when the cleaning job starts, so it cleans with the mapping of that moment.
    cleaningPage_->setSource([this] {
        ImportCleaningPage::Source src;
        const FilePreview* p = filesPage_->selectedPreview();
        src.haveFile = p != nullptr;
        src.ready = p && p->ok &&
                    validateFilesAndMapping(filesPage_->paths(), filesPage_->previews(), columnsPage_->columns(),
                                            columnsPage_->units())
                        .empty();
        if (p) src.file = q(p->path);
        if (src.ready) src.options = datasetOptions();
        return src;
    });
}

// --- pass-through to the pages -------------------------------------------------------------------

QStringList ImportDialog::files() const { return filesPage_->files(); }

void ImportDialog::setFiles(const QStringList& list) {
    filesPage_->setFiles(list);
    filesPage_->scan();
    settingsChanged();
}

void ImportDialog::setSelectedFile(int row) { filesPage_->setSelectedFile(row); }
void ImportDialog::setManifestPath(const QString& path) { filesPage_->setManifestPath(path); }
void ImportDialog::setRunSets(const QStringList& specs) { filesPage_->setRunSets(specs); }
void ImportDialog::setSetupChoice(int index) { filesPage_->setSetupChoice(index); }
void ImportDialog::setColumn(io::Signal s, const QString& column) { columnsPage_->setColumn(s, column); }
QString ImportDialog::column(io::Signal s) const { return columnsPage_->column(s); }
void ImportDialog::setUnit(io::Signal s, const QString& unit) { columnsPage_->setUnit(s, unit); }
QString ImportDialog::unit(io::Signal s) const { return columnsPage_->unit(s); }
QComboBox* ImportDialog::columnCombo(io::Signal s) const { return columnsPage_->columnCombo(s); }
QComboBox* ImportDialog::unitCombo(io::Signal s) const { return columnsPage_->unitCombo(s); }
QTableWidget* ImportDialog::previewTable() const { return columnsPage_->previewTable(); }
widgets::SignalComparePlot* ImportDialog::comparePlot() const { return cleaningPage_->plot(); }
const CleaningPreview& ImportDialog::cleaningPreview() const { return cleaningPage_->preview(); }
void ImportDialog::setPlotSignal(io::Signal s) { cleaningPage_->setPlotSignal(s); }
identify::PreprocessSettings ImportDialog::preprocessSettings() const { return cleaningPage_->settings(); }

void ImportDialog::setPreprocessSettings(const identify::PreprocessSettings& s) {
    cleaningPage_->setSettings(s);
    settingsChanged();
}

void ImportDialog::onScanFinished() {
    columnsPage_->populate(columnUnion());
    updatePreviewTable();
    settingsChanged();
    emit previewsUpdated();
}

void ImportDialog::updatePreviewTable() {
    columnsPage_->showPreview(filesPage_->selectedPreview(), !files().isEmpty());
}

QStringList ImportDialog::columnUnion() const {
    QStringList cols;
    for (const std::string& c : gui::columnUnion(filesPage_->paths(), filesPage_->previews())) cols << q(c);
    return cols;
}

// --- the result --------------------------------------------------------------------------------

io::DatasetOptions ImportDialog::datasetOptions() const {
    io::DatasetOptions o;
    o.mapping = buildMapping(columnsPage_->columns(), columnsPage_->units(), toStd(columnUnion()), nullptr);
    o.manifestPath = filesPage_->manifestPath().toStdString();
    for (const QString& s : filesPage_->runSetLines()) o.runSets.push_back(s.toStdString());
    return o;
}

SetupKind ImportDialog::setup() const {
    if (filesPage_->setupChoice() == 1) return SetupKind::Prescribed;
    if (filesPage_->setupChoice() == 2) return SetupKind::Dynamics;
    if (!dataset_.runs.empty()) return dataset_.runs.front().has(io::Signal::SliderDisp) ? SetupKind::Dynamics : SetupKind::Prescribed;
    return automaticSetup(filesPage_->paths(), filesPage_->previews(), column(io::Signal::SliderDisp).toStdString());
}

std::vector<io::Signal> ImportDialog::unmappedSignals() const {
    return gui::unmappedSignals(columnsPage_->columns(), toStd(columnUnion()));
}

void ImportDialog::updateSetupHint() {
    if (filesPage_->setupChoice() != 0) {
        filesPage_->setSetupHint(QString());
        return;
    }
    filesPage_->setSetupHint(setup() == SetupKind::Dynamics ? tr("\u2192 dynamics (slider displacement present)")
                                                            : tr("\u2192 prescribed slip (no slider displacement)"));
}

// --- validation ---------------------------------------------------------------------------------

QString ImportDialog::validationError() {
    const Paths paths = filesPage_->paths();
    const SignalTexts columns = columnsPage_->columns();
    const SignalTexts units = columnsPage_->units();
    std::string err = validateFilesAndMapping(paths, filesPage_->previews(), columns, units);
    if (err.empty()) err = manifestCheck_.validate(filesPage_->manifestPath().toStdString(), paths);
    if (err.empty()) err = validateRunSets(paths, toStd(filesPage_->runSetLines()));
    if (err.empty()) {
        const double scale = timeScale(buildMapping(columns, units, toStd(columnUnion()), nullptr));
        err = validateCleaning(paths, filesPage_->previews(), columns[idx(io::Signal::Time)], scale, preprocessSettings());
    }
    return err.empty() ? loadError_ : q(err);
}

QString ImportDialog::summaryText() const {
    const QStringList f = files();
    size_t rows = 0;
    for (const std::string& p : filesPage_->paths()) {
        const auto it = filesPage_->previews().find(p);
        if (it != filesPage_->previews().end()) rows += it->second.rowCount;
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
    return filesPage_->isScanning() || cleaningPage_->isBusy() || loading_;
}

QString ImportDialog::errorText() const { return error_; }

void ImportDialog::settingsChanged() {
    loadError_.clear();
    cleaningPage_->updateEnabledStates();
    updateSetupHint();
    revalidate();
    cleaningPage_->schedule();
}

void ImportDialog::revalidate() {
    const QString err = validationError();
    error_ = err;
    bool scanning = filesPage_->isScanning();
    for (const std::string& f : filesPage_->paths()) scanning = scanning || !filesPage_->previews().count(f);
    valid_ = err.isEmpty() && !scanning && !loading_;
    okButton_->setEnabled(valid_);
    showMessage(err, scanning);
}

void ImportDialog::showMessage(const QString& err, bool scanning) {
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

// --- loading on OK -------------------------------------------------------------------------------

void ImportDialog::accept() {
    revalidate();
    if (!valid_ || loading_) return;
    loading_ = true;
    loadWatcher_.setFuture(QtConcurrent::run([paths = filesPage_->paths(), opts = datasetOptions()] {
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
