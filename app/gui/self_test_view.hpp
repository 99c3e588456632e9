// The recovery self-test in the Identify tab (core/identify/self_test.hpp): its options (on/off,
// replicas, signal levels, effects stated in full) and its table (per effect and size: detected,
// confused, missed, the shape injected; and the false alarms on replicas without an effect).
// The Identify worker runs it with the loop, so it has the loop's progress bar and Cancel.
#pragma once

#include <QWidget>

#include "core/identify/identify.hpp"

class QCheckBox;
class QLabel;
class QLineEdit;
class QSpinBox;
class QTableWidget;

class SelfTestView : public QWidget {
    Q_OBJECT
public:
    explicit SelfTestView(QWidget* parent = nullptr);
    // Writes the self-test options into `o`; false with `why` when the levels or the stated
    // injections do not parse or are out of range.
    bool apply(stickslip::identify::IdentifyOptions& o, QString& why) const;
    void show(const stickslip::identify::SelfTestResult& r);
    void setEnabledTest(bool on);
    void setLevels(const QString& text);
    // Injections stated as the CLI's --self-test-size takes them, separated by spaces, commas or
    // semicolons: EFFECT=VALUE (its size, replacing the levels for that effect) and
    // EFFECT.PARAMETER=VALUE (another of its parameters), e.g. "stick_healing=0.0115
    // stick_healing.tc_s=0.00157".
    void setStated(const QString& text);
    QTableWidget* table() const { return table_; }
    QLabel* summary() const { return summary_; }

private:
    QCheckBox* enabled_ = nullptr;
    QSpinBox* replicas_ = nullptr;
    QLineEdit* levels_ = nullptr;
    QLineEdit* stated_ = nullptr;
    QLabel* summary_ = nullptr;
    QTableWidget* table_ = nullptr;
};
