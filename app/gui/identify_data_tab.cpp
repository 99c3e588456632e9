#include "identify_data_tab.hpp"

#include <QCheckBox>
#include <QComboBox>
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
#include <QPushButton>
#include <QTableWidget>
#include <QVBoxLayout>

#include "identify_tables.hpp"
#include "import_dialog.hpp"

namespace stickslip::gui {

using io::Signal;

IdentifyDataTab::IdentifyDataTab(QWidget* parent) : QWidget(parent) {
    auto* w = this;
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
    v->addWidget(buildPreprocessBox());
    v->addWidget(buildMappingBox());
    v->addStretch(1);

    connect(load, &QPushButton::clicked, this, [this] { openImport({}); });
    connect(clear, &QPushButton::clicked, this, [this] { setDataset(io::Dataset{}); });
    connect(runTable_, &QTableWidget::currentCellChanged, this, [this](int row) { showMapping(row); });
    connect(runTable_, &QTableWidget::itemChanged, this, &IdentifyDataTab::validationToggled);
    connect(setupBox_, QOverload<int>::of(&QComboBox::currentIndexChanged), this,
            [this] { runs_.setup = static_cast<SetupKind>(setupBox_->currentData().toInt()); });
    refreshRunTable();
}

QWidget* IdentifyDataTab::buildPreprocessBox() {
    auto* pre = new QGroupBox(tr("Preprocessing (as the paper)"), this);
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
    return pre;
}

QWidget* IdentifyDataTab::buildMappingBox() {
    auto* mapBox = new QGroupBox(tr("Column mapping of the selected run"), this);
    auto* mv = new QVBoxLayout(mapBox);
    mapping_ = new QLabel(tr("No run loaded."), mapBox);
    mapping_->setWordWrap(true);
    mapping_->setTextInteractionFlags(Qt::TextSelectableByMouse);
    mv->addWidget(mapping_);
    return mapBox;
}

void IdentifyDataTab::validationToggled(QTableWidgetItem* item) {
    if (item->column() != 5 || item->row() >= static_cast<int>(runs_.validation.size())) return;
    runs_.validation[static_cast<size_t>(item->row())] = item->checkState() == Qt::Checked;
    dataSummary_->setText(tr("%1 runs: %2 to fit, %3 held out for validation.")
                              .arg(runs_.data.runs.size()).arg(runs_.fitCount()).arg(runs_.validationCount()));
}

bool IdentifyDataTab::loadRuns(const QStringList& files, const QString& manifest, QString* error) {
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
void IdentifyDataTab::openImport(const QStringList& given) {
    QStringList files = given;
    if (files.isEmpty())
        files = QFileDialog::getOpenFileNames(this, tr("Load measured runs"), {}, tr("CSV (*.csv *.txt);;All files (*)"));
    if (files.isEmpty()) return;
    ImportDialog dlg(files, this);
    dlg.setPreprocessSettings(runs().pre);
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

void IdentifyDataTab::setDataset(const io::Dataset& data) {
    runs_.data = data;
    runs_.validation.assign(data.runs.size(), false);
    runs_.setup = guessSetup(data);
    setupBox_->setCurrentIndex(setupBox_->findData(int(runs_.setup)));
    refreshRunTable();
}

int IdentifyDataTab::runCount() const { return static_cast<int>(runs_.data.runs.size()); }

void IdentifyDataTab::setValidationRun(int row, bool validation) {
    if (QTableWidgetItem* it = runTable_->item(row, 5)) it->setCheckState(validation ? Qt::Checked : Qt::Unchecked);
}

MeasuredRuns IdentifyDataTab::runs() const {
    MeasuredRuns r = runs_;
    r.pre.filters.bandStop = bandStop_->isChecked();
    r.pre.filters.lowPass = lowPass_->isChecked();
    r.pre.filters.lowPass_Hz = lowPassHz_->value();
    r.pre.trim.steadyAmplitude = steadyTrim_->isChecked();
    return r;
}

void IdentifyDataTab::fillRunRow(size_t i) {
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

void IdentifyDataTab::refreshRunTable() {
    const QSignalBlocker block(runTable_);
    runTable_->setRowCount(static_cast<int>(runs_.data.runs.size()));
    for (size_t i = 0; i < runs_.data.runs.size(); ++i) fillRunRow(i);
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
    emit runsChanged();
}

void IdentifyDataTab::showMapping(int row) {
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

}  // namespace stickslip::gui
