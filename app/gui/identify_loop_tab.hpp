// The Identify panel's Identify tab: the residual -> missing effect -> extended model loop
// (free law parameters, candidate effects, loop limits, the recovery self-test) and its
// outcome (error before and after, effects added, every candidate's verdict, where the time went).
#pragma once

#include <QStringList>
#include <map>
#include <string>

#include "identify_job_tab.hpp"
#include "identify_worker.hpp"

class QDoubleSpinBox;
class QFormLayout;
class QCheckBox;
class QLabel;
class QListWidget;
class QSpinBox;
class QTableWidget;
class QVBoxLayout;
class SelfTestView;

namespace stickslip::gui {

class IdentifyLoopTab : public IdentifyJobTab {
    Q_OBJECT
public:
    explicit IdentifyLoopTab(QWidget* parent = nullptr);

    // The loop settings from the controls, added to a request whose runs the panel has set.
    void fillRequest(IdentifyRequest& r) const;
    bool anyCandidate() const;
    void setIdentifyFree(const QStringList& names);
    void setCandidates(const QStringList& names);    // empty: all
    void setMaxEffects(int n);
    void setMultistarts(int n);

    void clearUnexplained();
    void showOutcome(const IdentifyOutcome& o);
    QTableWidget* beforeAfterTable() const { return beforeAfter_; }
    QTableWidget* effectsTable() const { return effects_; }
    QTableWidget* candidateTable() const { return candidates_; }
    QTableWidget* timelineTable() const { return timeline_; }
    SelfTestView* selfTestView() const { return selfTest_; }
    QLabel* unexplainedLabel() const { return unexplained_; }
    QLabel* baselineBoundsLabel() const { return baselineBounds_; }

private:
    void buildFreeLaw(QFormLayout* form);
    void buildCandidates(QFormLayout* form);
    void buildLoopLimits(QFormLayout* form);
    void buildTables(QVBoxLayout* v);
    void showBeforeAfter(const identify::IdentifyResult& r, const QStringList& added);
    void showEffects(const identify::IdentifyResult& r);
    void showCandidates(const identify::IdentifyResult& r);
    void showTimeline(const identify::IdentifyResult& r);

    std::map<std::string, QCheckBox*> free_;
    QListWidget* candidateList_ = nullptr;
    QSpinBox *maxEffects_ = nullptr, *multistarts_ = nullptr;
    QDoubleSpinBox *bicMargin_ = nullptr, *minHeldOutGain_ = nullptr;
    QTableWidget* beforeAfter_ = nullptr;
    QTableWidget* effects_ = nullptr;
    QTableWidget* candidates_ = nullptr;
    QTableWidget* timeline_ = nullptr;  // where the time went: the loop's stages (IdentifyResult::timeline)
    SelfTestView* selfTest_ = nullptr;
    QLabel* unexplained_ = nullptr;
    QLabel* baselineBounds_ = nullptr;  // baseline parameters that ended on a bound, and the verdict
};

}  // namespace stickslip::gui
