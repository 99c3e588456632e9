// The Identify panel's Data tab: the measured runs (loaded directly or through the import
// dialog, or dropped on the panel), which are held out for validation, the set-up, the
// preprocessing switches and the column mapping of the selected run. It owns the runs; the
// Fit and Identify tabs read them through runs().
#pragma once

#include <QStringList>
#include <QWidget>

#include "identify_worker.hpp"

class QCheckBox;
class QComboBox;
class QDoubleSpinBox;
class QLabel;
class QTableWidget;
class QTableWidgetItem;

namespace stickslip::gui {

class IdentifyDataTab : public QWidget {
    Q_OBJECT
public:
    explicit IdentifyDataTab(QWidget* parent = nullptr);

    // See IdentifyPanel.
    bool loadRuns(const QStringList& files, const QString& manifest, QString* error);
    void openImport(const QStringList& files);
    void setDataset(const io::Dataset& data);
    int runCount() const;
    void setValidationRun(int row, bool validation);
    SetupKind setup() const { return runs_.setup; }
    // The runs with the preprocessing switches applied, as a job takes them.
    MeasuredRuns runs() const;

signals:
    void runsChanged();   // loaded or cleared
    void statusMessage(const QString& text);

private:
    QWidget* buildPreprocessBox();
    QWidget* buildMappingBox();
    void refreshRunTable();
    void fillRunRow(size_t i);
    void showMapping(int row);
    void validationToggled(QTableWidgetItem* item);

    MeasuredRuns runs_;
    QTableWidget* runTable_ = nullptr;
    QComboBox* setupBox_ = nullptr;
    QLabel* mapping_ = nullptr;
    QLabel* dataSummary_ = nullptr;
    QCheckBox *bandStop_ = nullptr, *lowPass_ = nullptr, *steadyTrim_ = nullptr;
    QDoubleSpinBox* lowPassHz_ = nullptr;
};

}  // namespace stickslip::gui
