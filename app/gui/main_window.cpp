#include "main_window.hpp"

#include <QAction>
#include <QApplication>
#include <QChildEvent>
#include <QCloseEvent>
#include <QDockWidget>
#include <QDragEnterEvent>
#include <QFileDialog>
#include <QFileInfo>
#include <QLabel>
#include <QLayout>
#include <QMenuBar>
#include <QMimeData>
#include <QScreen>
#include <QScrollArea>
#include <QSettings>
#include <QStatusBar>
#include <QTabBar>
#include <QTimer>

#include "core/io/csv_table.hpp"
#include "core/io/run_csv.hpp"
#include "core/presets.hpp"
#include "identify_panel.hpp"
#include "parameter_panel.hpp"
#include "simulation_controller.hpp"
#include "sweep_dialogs.hpp"
#include "view_set.hpp"
#include "widgets/plot_widget.hpp"

namespace stickslip::gui {

MainWindow::MainWindow(bool restoreSettings, QWidget* parent) : QMainWindow(parent), useSettings_(restoreSettings) {
    setWindowTitle(tr("StickSlip Lab"));
    setObjectName("mainWindow");
    setAcceptDrops(true);
    setDockNestingEnabled(true);
    controller_ = new SimulationController(this);
    panel_ = new ParameterPanel;
    views_ = new ViewSet(this);
    sweepDialog_ = new SweepDialog(controller_, [this] { return panel_->settings(); }, this);
    mapDialog_ = new MapDialog(controller_, [this] { return panel_->settings(); }, this);
    identify_ = new IdentifyPanel;
    buildDocks();
    buildMenus();
    runLabel_ = new QLabel(this);
    statusBar()->addPermanentWidget(runLabel_, 1);

    connect(panel_, &ParameterPanel::paramsChanged, controller_, &SimulationController::requestRun);
    connect(controller_, &SimulationController::runFinished, this, &MainWindow::onRun);
    connect(controller_, &SimulationController::poincareFinished, views_, &ViewSet::showPoincare);
    connect(controller_, &SimulationController::sweepFinished, views_, &ViewSet::showSweep);
    connect(controller_, &SimulationController::sweepFinished, this, [this] { raiseView("bifurcation"); });
    connect(controller_, &SimulationController::mapFinished, views_, &ViewSet::showMap);
    connect(controller_, &SimulationController::mapFinished, this, [this] { raiseView("map"); });
    connect(identify_, &IdentifyPanel::statusMessage, this, [this](const QString& m) { statusBar()->showMessage(m, 6000); });

    // The minimum as laid out now: an earlier activation, while the Identify dock was still
    // tabified in view, left the window's minimum at its width (1461 px), and resize() clamps
    // to it. Then the default size, at most the screen's available area (1366×768 laptops).
    layout()->activate();
    QSize size(1280, 800);
    if (const QScreen* sc = screen()) size = size.boundedTo(sc->availableGeometry().size());
    resize(size);
    if (useSettings_) {
        QSettings st;
        restoreGeometry(st.value("window/geometry").toByteArray());
        restoreState(st.value("window/state").toByteArray());
        recent_ = st.value("recentFiles").toStringList();
    }
    rebuildRecentMenu();
    controller_->requestRun(panel_->settings());
}

MainWindow::~MainWindow() = default;

// The tabs of tabified docks (the plot views) keep their whole titles and scroll instead of
// eliding: seven views share one dock area, and elided titles ("P…") could not tell the
// Poincaré section from the periodicity map. QMainWindow makes these tab bars itself, and
// again whenever docks are moved, so each is set up when it is first polished.
bool MainWindow::event(QEvent* e) {
    if (e->type() == QEvent::ChildPolished)
        if (auto* bar = qobject_cast<QTabBar*>(static_cast<QChildEvent*>(e)->child())) {
            bar->setElideMode(Qt::ElideNone);
            bar->setUsesScrollButtons(true);
        }
    return QMainWindow::event(e);
}

void MainWindow::buildDocks() {
    auto* scroll = new QScrollArea;
    scroll->setWidget(panel_);
    scroll->setWidgetResizable(true);
    scroll->setHorizontalScrollBarPolicy(Qt::ScrollBarAlwaysOff);
    scroll->setMinimumWidth(panel_->sizeHint().width() + 20);
    auto* pd = new QDockWidget(tr("Parameters"), this);
    pd->setObjectName("dock_parameters");
    pd->setWidget(scroll);
    addDockWidget(Qt::LeftDockWidgetArea, pd);
    docks_.insert("parameters", pd);

    QDockWidget* first = nullptr;
    QDockWidget* tabHost = nullptr;
    for (const auto& v : views_->views()) {
        auto* d = new QDockWidget(v.title, this);
        d->setObjectName("dock_" + v.id);
        d->setWidget(v.widget);
        docks_.insert(v.id, d);
        // Tabs behind others are not redrawn per result; they catch up when brought to the front.
        connect(d, &QDockWidget::visibilityChanged, views_, [this, id = v.id](bool visible) {
            if (visible) views_->viewBroughtToFront(id);
        });
        if (!first) {
            first = d;
            addDockWidget(Qt::RightDockWidgetArea, d);
        } else if (v.id == "rig") {
            addDockWidget(Qt::RightDockWidgetArea, d);
            splitDockWidget(first, d, Qt::Vertical);
        } else if (!tabHost) {
            tabHost = d;
            addDockWidget(Qt::RightDockWidgetArea, d);
            splitDockWidget(docks_.value("rig"), d, Qt::Horizontal);
        } else {
            tabifyDockWidget(tabHost, d);
        }
    }
    if (tabHost) tabHost->raise();
    // Identify (measured runs): a large workspace over the plot views, hidden until asked for.
    auto* idd = new QDockWidget(tr("Identify"), this);
    idd->setObjectName("dock_identify");
    idd->setWidget(identify_);
    docks_.insert("identify", idd);
    addDockWidget(Qt::RightDockWidgetArea, idd);
    if (first) tabifyDockWidget(first, idd);
    idd->hide();
    if (first) first->raise();
    resizeDocks({pd}, {400}, Qt::Horizontal);
    resizeDocks({first, docks_.value("rig")}, {430, 330}, Qt::Vertical);
    resizeDocks({docks_.value("rig"), tabHost}, {380, 480}, Qt::Horizontal);
}

void MainWindow::buildMenus() {
    QMenu* file = menuBar()->addMenu(tr("&File"));
    QAction* a = file->addAction(tr("&Open session…"), this, [this] {
        const QString p = QFileDialog::getOpenFileName(this, tr("Open session"), {}, tr("Sessions (*.json)"));
        if (!p.isEmpty()) openFile(p);
    });
    a->setShortcut(QKeySequence::Open);
    a = file->addAction(tr("&Save session"), this, [this] {
        QString p = sessionPath_;
        if (p.isEmpty()) p = QFileDialog::getSaveFileName(this, tr("Save session"), "session.json", tr("Sessions (*.json)"));
        if (!p.isEmpty()) saveSessionTo(p);
    });
    a->setShortcut(QKeySequence::Save);
    a = file->addAction(tr("Save session &as…"), this, [this] {
        const QString p = QFileDialog::getSaveFileName(this, tr("Save session"), "session.json", tr("Sessions (*.json)"));
        if (!p.isEmpty()) saveSessionTo(p);
    });
    a->setShortcut(QKeySequence::SaveAs);
    file->addSeparator();
    a = file->addAction(tr("Open &measured CSV…"), this, [this] {
        const QString p = QFileDialog::getOpenFileName(this, tr("Open measured CSV"), {}, tr("CSV (*.csv *.txt)"));
        if (!p.isEmpty()) openFile(p);
    });
    a->setShortcut(QKeySequence(QStringLiteral("Ctrl+M")));
    file->addAction(tr("&Clear measured overlay"), this, [this] {
        views_->clearMeasured();
        measuredPath_.clear();
    });
    recentMenu_ = file->addMenu(tr("&Recent files"));
    file->addSeparator();
    QMenu* exp = file->addMenu(tr("&Export view"));
    for (const auto& v : views_->views()) {
        if (!v.plot) continue;
        const QString id = v.id;
        exp->addAction(v.title + "…", this, [this, id] { exportView(id); });
    }
    a = file->addAction(tr("Export run data as CSV…"), this, &MainWindow::exportRunCsv);
    a->setShortcut(QKeySequence(QStringLiteral("Ctrl+E")));
    file->addSeparator();
    a = file->addAction(tr("&Quit"), this, &QWidget::close);
    a->setShortcut(QKeySequence::Quit);

    QMenu* presets = menuBar()->addMenu(tr("&Presets"));
    for (const auto& p : builtinPresets()) {
        const QString name = QString::fromStdString(p.name);
        QAction* pa = presets->addAction(name, this, [this, name] { panel_->loadPreset(name); });
        pa->setToolTip(QString::fromStdString(p.description));
        pa->setStatusTip(QString::fromStdString(p.description));
    }
    presets->addSeparator();
    a = presets->addAction(tr("&Reset to preset"), panel_, &ParameterPanel::resetToPreset);
    a->setShortcut(QKeySequence(QStringLiteral("Ctrl+R")));

    QMenu* analysis = menuBar()->addMenu(tr("&Analysis"));
    a = analysis->addAction(tr("&Bifurcation sweep…"), this, [this] {
        sweepDialog_->show();
        sweepDialog_->raise();
    });
    a->setShortcut(QKeySequence(QStringLiteral("Ctrl+B")));
    a = analysis->addAction(tr("Periodicity &map…"), this, [this] {
        mapDialog_->show();
        mapDialog_->raise();
    });
    a->setShortcut(QKeySequence(QStringLiteral("Ctrl+Shift+M")));
    a = analysis->addAction(tr("&Cancel all jobs"), controller_, &SimulationController::cancelAll);
    a->setShortcut(QKeySequence(Qt::Key_Escape));

    QMenu* data = menuBar()->addMenu(tr("&Data"));
    a = data->addAction(tr("&Identify…"), this, &MainWindow::showIdentify);
    a->setShortcut(QKeySequence(QStringLiteral("Ctrl+I")));
    data->addAction(tr("Open measured &runs…"), this, [this] {
        showIdentify();
        identify_->openImport();
    });

    QMenu* view = menuBar()->addMenu(tr("&View"));
    for (auto* d : docks_) view->addAction(d->toggleViewAction());
}

QString MainWindow::statusText() const { return runLabel_->text(); }

void MainWindow::showMessage(const QString& text, bool failure) {
    runLabel_->setText(text);
    runLabel_->setStyleSheet(failure ? "QLabel { color: #b00000; }" : QString());
}

void MainWindow::onRun(const RunOutcome& o) {
    views_->showRun(o);
    ++runsShown_;
    QString time = tr("run %1 ms").arg(o.elapsed_ms, 0, 'f', 0);
    if (o.preview)
        time = tr("preview at TOL %1 in %2 ms, refining to TOL %3")
                   .arg(o.settings.tolerance, 0, 'g', 2)
                   .arg(o.elapsed_ms, 0, 'f', 0)
                   .arg(o.requestedTolerance, 0, 'g', 2);
    if (o.ok()) {
        size_t n = 0;
        for (const auto& r : o.runs) n += r.run.samples.size();
        showMessage(tr("%1 — %2 samples, %3").arg(time).arg(n).arg(toString(o.settings.model)), false);
    } else {
        showMessage(tr("%1 — failed: %2").arg(time, o.failureText()), true);
    }
    emit runShown(o);
}

Session MainWindow::session() const {
    Session s;
    s.settings = panel_->settings();
    for (auto it = docks_.begin(); it != docks_.end(); ++it)
        if (it.value()->toggleViewAction()->isChecked()) s.visibleViews << it.key();
    s.visibleViews.sort();
    s.measuredFile = measuredPath_;
    s.windowState = saveState();
    return s;
}

void MainWindow::applySession(const Session& s) {
    if (!s.windowState.isEmpty()) restoreState(s.windowState);
    if (!s.visibleViews.isEmpty())
        for (auto it = docks_.begin(); it != docks_.end(); ++it) it.value()->setVisible(s.visibleViews.contains(it.key()));
    panel_->setSettings(s.settings);
    views_->clearMeasured();
    measuredPath_.clear();
    if (!s.measuredFile.isEmpty()) openMeasured(s.measuredFile);
}

bool MainWindow::saveSessionTo(const QString& path, QString* error) {
    QString why;
    if (!saveSession(session(), path, &why)) {
        showMessage(tr("Could not save the session: %1").arg(why), true);
        if (error) *error = why;
        return false;
    }
    sessionPath_ = path;
    addRecent(path);
    statusBar()->showMessage(tr("Saved %1").arg(path), 4000);
    return true;
}

bool MainWindow::loadSessionFrom(const QString& path, QString* error) {
    Session s;
    QString why;
    if (!loadSession(path, s, &why)) {
        showMessage(tr("Could not open the session: %1").arg(why), true);
        if (error) *error = why;
        return false;
    }
    applySession(s);
    sessionPath_ = path;
    addRecent(path);
    return true;
}

bool MainWindow::openMeasured(const QString& path, QString* error) {
    io::CsvTable table;
    io::CsvError err;
    QString why;
    if (!io::readCsvTable(path.toStdString(), table, err)) why = QString::fromStdString(err.what());
    else views_->overlayMeasured(table, panel_->settings().params.rig.normalForce_N, &why);  // sets why when nothing fits
    if (!why.isEmpty()) {
        showMessage(tr("Could not overlay the measured file: %1").arg(why), true);
        if (error) *error = why;
        return false;
    }
    measuredPath_ = path;
    addRecent(path);
    statusBar()->showMessage(tr("Overlaid %1").arg(path), 4000);
    return true;
}

namespace {
bool isSessionFile(const QString& path) { return QFileInfo(path).suffix().compare("json", Qt::CaseInsensitive) == 0; }
}  // namespace

bool MainWindow::openFile(const QString& path, QString* error) {
    if (isSessionFile(path)) return loadSessionFrom(path, error);
    return openMeasured(path, error);
}

void MainWindow::raiseView(const QString& viewId) {
    if (QDockWidget* d = docks_.value(viewId)) {
        d->show();
        d->raise();
    }
}

void MainWindow::showIdentify() {
    QDockWidget* d = docks_.value("identify");
    const bool wasHidden = d->isHidden();
    d->show();
    d->raise();
    // Give the workspace most of the height the first time it opens.
    // (after the layout has placed the dock, hence queued)
    if (wasHidden && !d->isFloating())
        QTimer::singleShot(0, this, [this, d] { resizeDocks({d, docks_.value("rig")}, {height() * 3 / 4, height() / 5}, Qt::Vertical); });
}

void MainWindow::exportView(const QString& viewId) {
    const ViewSet::View* v = views_->find(viewId);
    if (!v || !v->plot) return;
    const QString p = QFileDialog::getSaveFileName(this, tr("Export %1").arg(v->title), viewId + ".png",
                                                   tr("PNG (*.png);;SVG (*.svg);;PDF (*.pdf);;Data as CSV (*.csv)"));
    if (p.isEmpty()) return;
    QString why;
    if (!v->plot->exportTo(p, &why)) showMessage(tr("Export failed: %1").arg(why), true);
    else statusBar()->showMessage(tr("Exported %1").arg(p), 4000);
}

void MainWindow::exportRunCsv() {
    const std::shared_ptr<const RunOutcome> last = views_->lastRun();
    if (!last || last->runs.empty()) return;
    const QString p = QFileDialog::getSaveFileName(this, tr("Export run data"), "run.csv", tr("CSV (*.csv)"));
    if (p.isEmpty()) return;
    const ModelRun& r = last->runs.front();
    std::string why;
    if (!io::writeRunCsv(p.toStdString(), last->settings.paramsFor(r.law), r.run, &why))
        showMessage(tr("Export failed: %1").arg(QString::fromStdString(why)), true);
    else statusBar()->showMessage(tr("Exported %1").arg(p), 4000);
}

void MainWindow::addRecent(const QString& path) {
    const QString abs = QFileInfo(path).absoluteFilePath();
    recent_.removeAll(abs);
    recent_.prepend(abs);
    while (recent_.size() > 8) recent_.removeLast();
    if (useSettings_) QSettings().setValue("recentFiles", recent_);
    rebuildRecentMenu();
}

void MainWindow::rebuildRecentMenu() {
    recentMenu_->clear();
    for (const QString& p : recent_) recentMenu_->addAction(p, this, [this, p] { openFile(p); });
    recentMenu_->setEnabled(!recent_.isEmpty());
}

void MainWindow::closeEvent(QCloseEvent* e) {
    controller_->cancelAll();
    identify_->cancel();
    if (useSettings_) {
        QSettings st;
        st.setValue("window/geometry", saveGeometry());
        st.setValue("window/state", saveState());
    }
    e->accept();
}

void MainWindow::dragEnterEvent(QDragEnterEvent* e) {
    if (e->mimeData()->hasUrls()) e->acceptProposedAction();
}

// A session (.json) opens; one measured file is overlaid on the plots; several measured files
// are runs of one dataset, so they go to the Identify panel's import, as "Open measured runs…"
// does. The import dialog is modal: it opens after the drop has returned, not inside it.
void MainWindow::dropEvent(QDropEvent* e) {
    QStringList measured;
    for (const QUrl& u : e->mimeData()->urls()) {
        if (!u.isLocalFile()) continue;
        const QString path = u.toLocalFile();
        if (isSessionFile(path)) loadSessionFrom(path);
        else measured << path;
    }
    if (measured.size() == 1) {
        openMeasured(measured.front());
    } else if (measured.size() > 1) {
        QTimer::singleShot(0, this, [this, measured] {
            showIdentify();
            identify_->openImport(measured);
        });
    }
    e->acceptProposedAction();
}

}  // namespace stickslip::gui
