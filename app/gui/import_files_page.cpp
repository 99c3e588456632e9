#include "import_files_page.hpp"

#include <QComboBox>
#include <QFileDialog>
#include <QFileInfo>
#include <QFormLayout>
#include <QGroupBox>
#include <QHBoxLayout>
#include <QLabel>
#include <QLineEdit>
#include <QListWidget>
#include <QPlainTextEdit>
#include <QPushButton>
#include <QVBoxLayout>
#include <QtConcurrent/QtConcurrentRun>
#include <algorithm>

namespace stickslip::gui {

ImportFilesPage::ImportFilesPage(QWidget* parent) : QWidget(parent) {
    setMaximumWidth(340);
    auto* layout = new QVBoxLayout(this);
    layout->setContentsMargins(0, 0, 6, 0);
    layout->addWidget(buildFilesBox(), 1);
    layout->addWidget(buildRunBox(), 0);
    connect(&scanWatcher_, &QFutureWatcher<std::vector<FilePreview>>::finished, this, &ImportFilesPage::onScanFinished);
}

ImportFilesPage::~ImportFilesPage() {
    // The scan holds copies of its inputs only; wait so it does not outlive the page.
    scanWatcher_.waitForFinished();
}

QWidget* ImportFilesPage::buildFilesBox() {
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
    connect(addButton_, &QPushButton::clicked, this, &ImportFilesPage::addFilesClicked);
    connect(removeButton_, &QPushButton::clicked, this, &ImportFilesPage::removeFileClicked);
    connect(fileList_, &QListWidget::currentRowChanged, this, [this](int) {
        removeButton_->setEnabled(fileList_->currentRow() >= 0);
        emit selectionChanged();
    });
    return filesBox;
}

QWidget* ImportFilesPage::buildRunBox() {
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
    connect(browse, &QPushButton::clicked, this, &ImportFilesPage::browseManifest);
    connect(manifest_, &QLineEdit::textChanged, this, &ImportFilesPage::runSettingsChanged);

    runSets_ = new QPlainTextEdit;
    runSets_->setPlaceholderText(tr("one per line, e.g.\nrun_01.csv:tN=6.2N\nrun_02.csv:k=8.4kN/m"));
    runSets_->setToolTip(tr("Known settings of single runs, as the command line's --run-set FILE:KEY=VALUE "
                            "(keys k, A, f, tN, m, c, \u2026; values may carry a unit). They override the "
                            "manifest and the columns."));
    runSets_->setTabChangesFocus(true);
    runSets_->setMaximumHeight(fontMetrics().lineSpacing() * 5 + 12);
    rf->addRow(tr("Per run:"), runSets_);
    connect(runSets_, &QPlainTextEdit::textChanged, this, &ImportFilesPage::runSettingsChanged);

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
    connect(setup_, QOverload<int>::of(&QComboBox::currentIndexChanged), this, [this](int) { emit setupChoiceChanged(); });
    return runBox;
}

// --- files -------------------------------------------------------------------------------------

QStringList ImportFilesPage::files() const {
    QStringList out;
    for (int i = 0; i < fileList_->count(); ++i) out << fileList_->item(i)->data(Qt::UserRole).toString();
    return out;
}

Paths ImportFilesPage::paths() const {
    Paths out;
    for (const QString& f : files()) out.push_back(f.toStdString());
    return out;
}

void ImportFilesPage::setFiles(const QStringList& list) {
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
}

void ImportFilesPage::addFilesClicked() {
    const QStringList more = QFileDialog::getOpenFileNames(this, tr("Add measured runs"), QString(),
                                                           tr("CSV files (*.csv *.txt *.tsv);;All files (*)"));
    if (more.isEmpty()) return;
    QStringList all = files();
    for (const QString& f : more)
        if (!all.contains(f)) all << f;
    emit filesChosen(all, fileList_->currentRow());
}

void ImportFilesPage::removeFileClicked() {
    const int row = fileList_->currentRow();
    if (row < 0) return;
    QStringList all = files();
    all.removeAt(row);
    emit filesChosen(all, all.isEmpty() ? -1 : std::min(row, static_cast<int>(all.size()) - 1));
}

void ImportFilesPage::setSelectedFile(int row) { fileList_->setCurrentRow(row); }

void ImportFilesPage::browseManifest() {
    const QString start = manifest_->text().isEmpty() && !files().isEmpty() ? QFileInfo(files().front()).absolutePath()
                                                                             : manifest_->text();
    const QString f = QFileDialog::getOpenFileName(this, tr("Manifest"), start, tr("JSON (*.json);;All files (*)"));
    if (!f.isEmpty()) manifest_->setText(f);
}

QString ImportFilesPage::manifestPath() const { return manifest_->text().trimmed(); }

void ImportFilesPage::setManifestPath(const QString& path) { manifest_->setText(path); }

QStringList ImportFilesPage::runSetLines() const {
    QStringList out;
    for (const QString& line : runSets_->toPlainText().split(QLatin1Char('\n'))) {
        const QString t = line.trimmed();
        if (!t.isEmpty() && !t.startsWith(QLatin1Char('#'))) out << t;
    }
    return out;
}

void ImportFilesPage::setRunSets(const QStringList& specs) { runSets_->setPlainText(specs.join(QLatin1Char('\n'))); }

int ImportFilesPage::setupChoice() const { return setup_->currentIndex(); }

void ImportFilesPage::setSetupChoice(int index) { setup_->setCurrentIndex(index); }

void ImportFilesPage::setSetupHint(const QString& text) { setupHint_->setText(text); }

// --- scan --------------------------------------------------------------------------------------

void ImportFilesPage::scan() {
    if (scanning_) {
        rescanPending_ = true;
        return;
    }
    std::vector<std::string> todo;
    for (const std::string& f : paths())
        if (!previews_.count(f)) todo.push_back(f);
    if (todo.empty()) return;
    scanning_ = true;
    scanWatcher_.setFuture(QtConcurrent::run([todo] {
        std::vector<FilePreview> out;
        for (const std::string& f : todo) out.push_back(readFilePreview(f));
        return out;
    }));
    emit scanStarted();
}

void ImportFilesPage::onScanFinished() {
    scanning_ = false;
    for (FilePreview& p : scanWatcher_.result()) previews_[p.path] = std::move(p);
    if (rescanPending_) {
        rescanPending_ = false;
        scan();
    }
    emit scanFinished();
}

const FilePreview* ImportFilesPage::selectedPreview() const {
    const int row = fileList_->currentRow();
    if (row < 0) return nullptr;
    const auto it = previews_.find(fileList_->item(row)->data(Qt::UserRole).toString().toStdString());
    return it == previews_.end() ? nullptr : &it->second;
}

}  // namespace stickslip::gui
