#include "identify_job_tab.hpp"

#include <QHBoxLayout>
#include <QLabel>
#include <QProgressBar>
#include <QPushButton>
#include <algorithm>
#include <cmath>

namespace stickslip::gui {

IdentifyJobTab::IdentifyJobTab(QWidget* parent) : QWidget(parent) {}

QHBoxLayout* IdentifyJobTab::makeRunRow(const QString& runText, const QString& idleStatus) {
    auto* runRow = new QHBoxLayout;
    run_ = new QPushButton(runText, this);
    cancel_ = new QPushButton(tr("Cancel"), this);
    cancel_->setEnabled(false);
    progress_ = new QProgressBar(this);
    progress_->setRange(0, 1000);
    progress_->setValue(0);
    progress_->setTextVisible(false);
    runRow->addWidget(run_);
    runRow->addWidget(cancel_);
    runRow->addWidget(progress_, 1);
    status_ = new QLabel(idleStatus, this);
    status_->setWordWrap(true);
    connect(run_, &QPushButton::clicked, this, &IdentifyJobTab::runClicked);
    connect(cancel_, &QPushButton::clicked, this, &IdentifyJobTab::cancelClicked);
    return runRow;
}

QHBoxLayout* IdentifyJobTab::makeExportRow() {
    auto* exportRow = new QHBoxLayout;
    auto* exportButton = new QPushButton(tr("Export report…"), this);
    exportRow->addStretch(1);
    exportRow->addWidget(exportButton);
    connect(exportButton, &QPushButton::clicked, this, &IdentifyJobTab::exportClicked);
    return exportRow;
}

QString IdentifyJobTab::status() const { return status_->text(); }

void IdentifyJobTab::setStatus(const QString& text) { status_->setText(text); }

void IdentifyJobTab::setJobState(bool canRun, bool running) {
    run_->setEnabled(canRun);
    cancel_->setEnabled(running);
    if (running) progress_->setValue(0);
}

void IdentifyJobTab::setRunEnabled(bool enabled) { run_->setEnabled(enabled); }

void IdentifyJobTab::setProgress(double fraction) {
    progress_->setValue(static_cast<int>(std::lround(1000 * std::clamp(fraction, 0.0, 1.0))));
}

bool IdentifyJobTab::showJobEnd(const QString& what, bool cancelled, bool ok, const QString& message, double elapsed_ms) {
    if (cancelled) {
        progress_->setValue(0);
        status_->setText(tr("%1 cancelled after %2 s.").arg(what).arg(elapsed_ms / 1000.0, 0, 'f', 1));
        emit statusMessage(tr("%1 cancelled").arg(what));
        return false;
    }
    if (!ok) {
        status_->setText(tr("<span style='color:#b00000'>%1 failed: %2</span>").arg(what, message.toHtmlEscaped()));
        emit statusMessage(tr("%1 failed: %2").arg(what, message));
        return false;
    }
    return true;
}

}  // namespace stickslip::gui
