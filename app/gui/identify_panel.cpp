#include "identify_panel.hpp"

#include <QDragEnterEvent>
#include <QDropEvent>
#include <QFileDialog>
#include <QMimeData>
#include <QSaveFile>
#include <QScrollArea>
#include <QScrollBar>
#include <QSplitter>
#include <QTabWidget>
#include <QVBoxLayout>
#include <algorithm>

#include "core/identify/report_html.hpp"
#include "identify_data_tab.hpp"
#include "identify_fit_tab.hpp"
#include "identify_loop_tab.hpp"
#include "identify_plots.hpp"
#include "self_test_view.hpp"

namespace stickslip::gui {

using namespace stickslip::identify;

namespace {

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
    buildTabs();
    plots_ = new IdentifyPlots;
    auto* split = new QSplitter(Qt::Horizontal, this);
    split->addWidget(controls_);
    split->addWidget(plots_);
    split->setStretchFactor(0, 0);
    split->setStretchFactor(1, 1);
    split->setChildrenCollapsible(false);
    auto* top = new QVBoxLayout(this);
    top->setContentsMargins(4, 4, 4, 4);
    top->addWidget(split);
    connectTabs();
    updateRunButtons();
}

IdentifyPanel::~IdentifyPanel() = default;

void IdentifyPanel::buildTabs() {
    controls_ = new QTabWidget(this);
    data_ = new IdentifyDataTab;
    fit_ = new IdentifyFitTab;
    loop_ = new IdentifyLoopTab;
    controls_->addTab(scrolled(data_), tr("Data"));
    controls_->addTab(scrolled(fit_), tr("Fit"));
    controls_->addTab(scrolled(loop_), tr("Identify"));
    // At least as wide as the widest tab's content needs (the scroll areas do not scroll
    // sideways): at 1680 px with both docks open a 430 px minimum clipped the Fit tab's rows and
    // the wrapped identifiability line (seen in a screenshot).
    int need = 430;
    for (int i = 0; i < controls_->count(); ++i)
        if (auto* sa = qobject_cast<QScrollArea*>(controls_->widget(i)); sa && sa->widget())
            need = std::max(need, sa->widget()->minimumSizeHint().width() + sa->verticalScrollBar()->sizeHint().width() + 12);
    controls_->setMinimumWidth(need);
}

void IdentifyPanel::connectTabs() {
    connect(data_, &IdentifyDataTab::runsChanged, this, &IdentifyPanel::updateRunButtons);
    connect(data_, &IdentifyDataTab::statusMessage, this, &IdentifyPanel::statusMessage);
    for (IdentifyJobTab* tab : {static_cast<IdentifyJobTab*>(fit_), static_cast<IdentifyJobTab*>(loop_)}) {
        connect(tab, &IdentifyJobTab::cancelClicked, this, &IdentifyPanel::cancel);
        connect(tab, &IdentifyJobTab::exportClicked, this, &IdentifyPanel::exportDialog);
        connect(tab, &IdentifyJobTab::statusMessage, this, &IdentifyPanel::statusMessage);
    }
    connect(fit_, &IdentifyJobTab::runClicked, this, &IdentifyPanel::startFit);
    connect(loop_, &IdentifyJobTab::runClicked, this, &IdentifyPanel::startIdentify);
    connect(worker_, &IdentifyWorker::progress, this, &IdentifyPanel::onProgress);
    connect(worker_, &IdentifyWorker::fitFinished, this, &IdentifyPanel::onFitFinished);
    connect(worker_, &IdentifyWorker::identifyFinished, this, &IdentifyPanel::onIdentifyFinished);
}

// --- data ------------------------------------------------------------------------------------

bool IdentifyPanel::loadRuns(const QStringList& files, const QString& manifest, QString* error) {
    return data_->loadRuns(files, manifest, error);
}
void IdentifyPanel::openImport(const QStringList& files) { data_->openImport(files); }
void IdentifyPanel::setDataset(const io::Dataset& data) { data_->setDataset(data); }
int IdentifyPanel::runCount() const { return data_->runCount(); }
void IdentifyPanel::setValidationRun(int row, bool validation) { data_->setValidationRun(row, validation); }
SetupKind IdentifyPanel::setup() const { return data_->setup(); }

void IdentifyPanel::updateRunButtons() {
    const bool can = runCount() > 0 && !worker_->isBusy();
    fit_->setRunEnabled(can);
    loop_->setRunEnabled(can);
}

// --- controls ----------------------------------------------------------------------------------

void IdentifyPanel::setModel(const QString& model) { fit_->setModel(model); }
void IdentifyPanel::setFreeParameters(const QStringList& names) { fit_->setFreeParameters(names); }
void IdentifyPanel::setMaxIterations(int n) { fit_->setMaxIterations(n); }
void IdentifyPanel::setTimeSplit(double fraction) { fit_->setTimeSplit(fraction); }
void IdentifyPanel::setIdentifyFree(const QStringList& names) { loop_->setIdentifyFree(names); }
void IdentifyPanel::setCandidates(const QStringList& names) { loop_->setCandidates(names); }
void IdentifyPanel::setMaxEffects(int n) { loop_->setMaxEffects(n); }

void IdentifyPanel::setMultistarts(int n) {
    fit_->setMultistarts(n);
    loop_->setMultistarts(n);
}

FitRequest IdentifyPanel::fitRequest() const {
    FitRequest r;
    r.runs = data_->runs();
    r.settings.setup = r.runs.setup;
    fit_->fillRequest(r);
    return r;
}

IdentifyRequest IdentifyPanel::identifyRequest() const {
    IdentifyRequest r;
    r.runs = data_->runs();
    loop_->fillRequest(r);
    return r;
}

// --- what the panel shows ----------------------------------------------------------------------

QString IdentifyPanel::fitStatus() const { return fit_->status(); }
QString IdentifyPanel::identifyStatus() const { return loop_->status(); }
QTableWidget* IdentifyPanel::fitParameterTable() const { return fit_->parameterTable(); }
QTableWidget* IdentifyPanel::fitRunTable() const { return fit_->runTable(); }
QTableWidget* IdentifyPanel::beforeAfterTable() const { return loop_->beforeAfterTable(); }
QTableWidget* IdentifyPanel::effectsTable() const { return loop_->effectsTable(); }
QTableWidget* IdentifyPanel::candidateTable() const { return loop_->candidateTable(); }
QTableWidget* IdentifyPanel::timelineTable() const { return loop_->timelineTable(); }
SelfTestView* IdentifyPanel::selfTestView() const { return loop_->selfTestView(); }
QLabel* IdentifyPanel::unexplainedLabel() const { return loop_->unexplainedLabel(); }
QLabel* IdentifyPanel::baselineBoundsLabel() const { return loop_->baselineBoundsLabel(); }
QTabWidget* IdentifyPanel::plotTabs() const { return plots_->tabs(); }
widgets::SeriesPlot* IdentifyPanel::overlayPlot() const { return plots_->overlayPlot(); }
QPushButton* IdentifyPanel::fitRunButton() const { return fit_->runButton(); }
QPushButton* IdentifyPanel::fitCancelButton() const { return fit_->cancelButton(); }
QPushButton* IdentifyPanel::identifyRunButton() const { return loop_->runButton(); }
QPushButton* IdentifyPanel::identifyCancelButton() const { return loop_->cancelButton(); }

// --- jobs --------------------------------------------------------------------------------------

void IdentifyPanel::startFit() {
    if (runCount() == 0) {
        fit_->setStatus(tr("Load runs first."));
        return;
    }
    const FitRequest r = fitRequest();
    if (r.settings.free.empty()) {
        fit_->setStatus(tr("<span style='color:#b00000'>Choose at least one free parameter.</span>"));
        return;
    }
    setBusy(true, true);
    fit_->setStatus(tr("Fitting %1 runs…").arg(r.runs.fitCount()));
    worker_->startFit(r);
}

void IdentifyPanel::startIdentify() {
    if (runCount() == 0) {
        loop_->setStatus(tr("Load runs first."));
        return;
    }
    const IdentifyRequest r = identifyRequest();
    if (r.options.freeLaw.empty()) {
        loop_->setStatus(tr("<span style='color:#b00000'>Choose at least one free law parameter.</span>"));
        return;
    }
    if (!loop_->anyCandidate()) {
        loop_->setStatus(tr("<span style='color:#b00000'>Choose at least one candidate effect.</span>"));
        return;
    }
    IdentifyRequest req = r;
    QString why;
    if (!loop_->selfTestView()->apply(req.options, why)) {
        loop_->setStatus(tr("<span style='color:#b00000'>%1</span>").arg(why.toHtmlEscaped()));
        return;
    }
    setBusy(true, false);
    loop_->clearUnexplained();
    loop_->setStatus(tr("Identifying…"));
    worker_->startIdentify(req);
}

void IdentifyPanel::cancel() {
    if (!worker_->isBusy()) return;
    worker_->cancel();
    (fitJob_ ? static_cast<IdentifyJobTab*>(fit_) : loop_)->setStatus(tr("Cancelling…"));
}

void IdentifyPanel::setBusy(bool busy, bool fitJob) {
    fitJob_ = fitJob;
    const bool have = runCount() > 0;
    fit_->setJobState(!busy && have, busy && fitJob);
    loop_->setJobState(!busy && have, busy && !fitJob);
}

void IdentifyPanel::onProgress(double fraction, const QString& stage) {
    IdentifyJobTab* tab = fitJob_ ? static_cast<IdentifyJobTab*>(fit_) : loop_;
    tab->setProgress(fraction);
    if (!worker_->isBusy()) return;
    tab->setStatus(stage.isEmpty() ? tr("Working…") : stage + QStringLiteral("…"));
}

void IdentifyPanel::onFitFinished(const FitOutcome& o) {
    setBusy(false, true);
    if (!fit_->showJobEnd(tr("Fit"), o.cancelled, o.ok, o.message, o.elapsed_ms)) return;
    lastFit_ = o;
    fit_->showOutcome(lastFit_);
    plots_->showFit(&lastFit_);
    emit statusMessage(tr("Fit done"));
    emit fitShown(o);
}

void IdentifyPanel::onIdentifyFinished(const IdentifyOutcome& o) {
    setBusy(false, false);
    if (!loop_->showJobEnd(tr("Identify"), o.cancelled, o.ok, o.message, o.elapsed_ms)) return;
    lastIdentify_ = o;
    loop_->showOutcome(lastIdentify_);
    plots_->showIdentify(&lastIdentify_);
    emit statusMessage(tr("Identify done"));
    emit identifyShown(o);
}

// --- export ------------------------------------------------------------------------------------

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
