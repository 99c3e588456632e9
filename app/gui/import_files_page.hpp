// The import dialog's left column: the data files, the manifest, the per-run settings (the
// CLI's --run-set) and the set-up. It owns the reading of the files' headers off the GUI
// thread; the dialog asks for a scan when the list changes and hears when the previews are in.
#pragma once

#include <QFutureWatcher>
#include <QStringList>
#include <QWidget>
#include <vector>

#include "file_preview.hpp"
#include "import_validation.hpp"

class QComboBox;
class QLabel;
class QLineEdit;
class QListWidget;
class QPlainTextEdit;
class QPushButton;

namespace stickslip::gui {

class ImportFilesPage : public QWidget {
    Q_OBJECT
public:
    explicit ImportFilesPage(QWidget* parent = nullptr);
    ~ImportFilesPage() override;   // waits for the scan: it must not outlive the page

    QStringList files() const;
    Paths paths() const;                        // files() as the core takes them
    void setFiles(const QStringList& files);    // quietly; the dialog scans and revalidates
    void setSelectedFile(int row);
    QString manifestPath() const;               // trimmed
    void setManifestPath(const QString& path);
    QStringList runSetLines() const;            // non-empty, non-comment lines
    void setRunSets(const QStringList& specs);
    int setupChoice() const;                    // 0 automatic, 1 prescribed, 2 dynamics
    void setSetupChoice(int index);
    void setSetupHint(const QString& text);

    // Starts reading the headers not yet read; when a scan is running, one more follows it.
    void scan();
    bool isScanning() const { return scanning_ || rescanPending_; }
    const PreviewMap& previews() const { return previews_; }
    const FilePreview* selectedPreview() const;

signals:
    void filesChosen(const QStringList& files, int selectRow);   // Add or Remove (row -1: keep the first)
    void selectionChanged();
    void runSettingsChanged();    // manifest or per-run text edited
    void setupChoiceChanged();
    void scanStarted();
    void scanFinished();

private:
    QWidget* buildFilesBox();
    QWidget* buildRunBox();
    void addFilesClicked();
    void removeFileClicked();
    void browseManifest();
    void onScanFinished();

    QListWidget* fileList_ = nullptr;
    QPushButton *addButton_ = nullptr, *removeButton_ = nullptr;
    QLineEdit* manifest_ = nullptr;
    QPlainTextEdit* runSets_ = nullptr;
    QComboBox* setup_ = nullptr;
    QLabel* setupHint_ = nullptr;

    PreviewMap previews_;   // by path
    QFutureWatcher<std::vector<FilePreview>> scanWatcher_;
    bool scanning_ = false;
    bool rescanPending_ = false;
};

}  // namespace stickslip::gui
