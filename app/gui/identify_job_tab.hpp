// What the Fit and Identify tabs share: a Run button, a Cancel button, a progress bar and a
// status line for one job on the panel's worker. The panel decides when a job may run; the
// tab only shows it.
#pragma once

#include <QWidget>

class QHBoxLayout;
class QLabel;
class QProgressBar;
class QPushButton;

namespace stickslip::gui {

class IdentifyJobTab : public QWidget {
    Q_OBJECT
public:
    explicit IdentifyJobTab(QWidget* parent = nullptr);

    QPushButton* runButton() const { return run_; }
    QPushButton* cancelButton() const { return cancel_; }
    QString status() const;
    void setStatus(const QString& text);
    // Run enabled when a job may start; Cancel and a reset bar while this tab's job runs.
    void setJobState(bool canRun, bool running);
    void setRunEnabled(bool enabled);
    void setProgress(double fraction);   // 0..1
    // Shows a cancelled or failed job in the bar and status line; true when it succeeded.
    bool showJobEnd(const QString& what, bool cancelled, bool ok, const QString& message, double elapsed_ms);

signals:
    void runClicked();
    void cancelClicked();
    void exportClicked();
    void statusMessage(const QString& text);

protected:
    // The Run/Cancel/progress row and the status line, created by the subclass where it wants them.
    QHBoxLayout* makeRunRow(const QString& runText, const QString& idleStatus);
    QLabel* statusLabel() const { return status_; }
    QHBoxLayout* makeExportRow();

private:
    QPushButton *run_ = nullptr, *cancel_ = nullptr;
    QProgressBar* progress_ = nullptr;
    QLabel* status_ = nullptr;
};

}  // namespace stickslip::gui
