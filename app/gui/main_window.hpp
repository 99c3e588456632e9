// The main window only wires: the parameter panel's one value goes to the controller, the
// controller's outcomes go to the views; menus, docks, files and the status bar. It never
// computes.
#pragma once

#include <QHash>
#include <QMainWindow>

#include "job_results.hpp"
#include "session.hpp"

class QDockWidget;
class QLabel;
class QMenu;

namespace stickslip::gui {

class ParameterPanel;
class SimulationController;
class ViewSet;
class SweepDialog;
class MapDialog;
class IdentifyPanel;

class MainWindow : public QMainWindow {
    Q_OBJECT
public:
    // restoreSettings: apply QSettings window state and recent files (off for screenshots/tests).
    explicit MainWindow(bool restoreSettings = true, QWidget* parent = nullptr);
    ~MainWindow() override;

    ParameterPanel* panel() const { return panel_; }
    SimulationController* controller() const { return controller_; }
    ViewSet* views() const { return views_; }
    SweepDialog* sweepDialog() const { return sweepDialog_; }
    MapDialog* mapDialog() const { return mapDialog_; }
    IdentifyPanel* identifyPanel() const { return identify_; }
    // Shows and raises the Identify dock (Data ▸ Identify…).
    void showIdentify();
    QDockWidget* dock(const QString& viewId) const { return docks_.value(viewId); }
    QString statusText() const;
    // Number of run outcomes shown so far.
    int runsShown() const { return runsShown_; }

    Session session() const;
    void applySession(const Session& s);
    bool saveSessionTo(const QString& path, QString* error = nullptr);
    bool loadSessionFrom(const QString& path, QString* error = nullptr);
    bool openMeasured(const QString& path, QString* error = nullptr);
    // By extension: a .json session, else a measured CSV (menus, drops, the app's file argument).
    bool openFile(const QString& path, QString* error = nullptr);
    void raiseView(const QString& viewId);

signals:
    // After every run outcome is on the views.
    void runShown(const stickslip::gui::RunOutcome& outcome);

protected:
    bool event(QEvent* e) override;
    void closeEvent(QCloseEvent* e) override;
    void dragEnterEvent(QDragEnterEvent* e) override;
    void dropEvent(QDropEvent* e) override;

private:
    void buildDocks();
    void buildMenus();
    void onRun(const RunOutcome& o);
    void addRecent(const QString& path);
    void rebuildRecentMenu();
    void exportView(const QString& viewId);
    void exportRunCsv();
    void showMessage(const QString& text, bool failure);

    ParameterPanel* panel_ = nullptr;
    SimulationController* controller_ = nullptr;
    ViewSet* views_ = nullptr;
    SweepDialog* sweepDialog_ = nullptr;
    MapDialog* mapDialog_ = nullptr;
    IdentifyPanel* identify_ = nullptr;
    QHash<QString, QDockWidget*> docks_;
    QLabel* runLabel_ = nullptr;
    QMenu* recentMenu_ = nullptr;
    QStringList recent_;
    QString sessionPath_;
    QString measuredPath_;
    int runsShown_ = 0;
    bool useSettings_ = true;
};

}  // namespace stickslip::gui
