// The recovery self-test in the Identify tab (core/identify/self_test.hpp): its options (on/off,
// replicas, signal levels) and its table (per effect and size: detected, confused, missed; and
// the false alarms on replicas without an effect). The Identify worker runs it with the loop,
// so it has the loop's progress bar and Cancel.
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
    // Writes the self-test options into `o`; false with `why` when the levels do not parse.
    bool apply(stickslip::identify::IdentifyOptions& o, QString& why) const;
    void show(const stickslip::identify::SelfTestResult& r);
    void setEnabledTest(bool on);
    void setLevels(const QString& text);
    QTableWidget* table() const { return table_; }
    QLabel* summary() const { return summary_; }

private:
    QCheckBox* enabled_ = nullptr;
    QSpinBox* replicas_ = nullptr;
    QLineEdit* levels_ = nullptr;
    QLabel* summary_ = nullptr;
    QTableWidget* table_ = nullptr;
};
