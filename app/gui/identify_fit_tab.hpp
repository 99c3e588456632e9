// The Identify panel's Fit tab: the law(s), free parameters, robust loss, validation split and
// solver settings of a fit, and its outcome (parameters ± standard error, identifiability,
// NRMSE per run).
#pragma once

#include <QStringList>
#include <map>
#include <string>

#include "identify_job_tab.hpp"
#include "identify_worker.hpp"

class QCheckBox;
class QComboBox;
class QDoubleSpinBox;
class QFormLayout;
class QLabel;
class QSpinBox;
class QTableWidget;

namespace stickslip::gui {

class IdentifyFitTab : public IdentifyJobTab {
    Q_OBJECT
public:
    explicit IdentifyFitTab(QWidget* parent = nullptr);

    // The fit settings from the controls, added to a request whose runs the panel has set.
    void fillRequest(FitRequest& r) const;
    void setModel(const QString& model);
    void setFreeParameters(const QStringList& names);
    void setMultistarts(int n);
    void setMaxIterations(int n);
    void setTimeSplit(double fraction);

    void showOutcome(const FitOutcome& o);
    QTableWidget* parameterTable() const { return params_; }
    QTableWidget* runTable() const { return runs_; }

private:
    void buildSettings(QFormLayout* form);
    void buildLossAndSplit(QFormLayout* form);
    void buildSolver(QFormLayout* form);
    void showParameters(const FitOutcome& o);
    void showIdentifiability(const FitOutcome& o);
    void showRuns(const FitOutcome& o);

    QComboBox* model_ = nullptr;
    std::map<std::string, QCheckBox*> free_;
    QComboBox* loss_ = nullptr;
    QDoubleSpinBox* lossScale_ = nullptr;
    QCheckBox* split_ = nullptr;
    QDoubleSpinBox* splitFraction_ = nullptr;
    QSpinBox *multistarts_ = nullptr, *maxIterations_ = nullptr;
    QCheckBox* jackknife_ = nullptr;
    QLabel* identifiability_ = nullptr;
    QTableWidget* params_ = nullptr;
    QTableWidget* runs_ = nullptr;
};

}  // namespace stickslip::gui
