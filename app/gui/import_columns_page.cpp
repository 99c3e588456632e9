#include "import_columns_page.hpp"

#include <algorithm>

#include <QComboBox>
#include <QFontMetrics>
#include <QFileInfo>
#include <QGridLayout>
#include <QGroupBox>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QLabel>
#include <QStyle>
#include <QTableWidget>
#include <QVBoxLayout>
#include <map>

#include "import_signals.hpp"

namespace stickslip::gui {

namespace {

const QString kNone = QStringLiteral("(none)");

QString q(const std::string& s) { return QString::fromStdString(s); }

// Units offered per SI unit (the combo is editable: anything the core's unit parser accepts
// with the right dimension works).
QStringList unitChoices(io::Signal s) {
    const QString si = QString::fromLatin1(io::signalUnit(s));
    if (si == QLatin1String("s")) return {"s", "ms"};
    if (si == QLatin1String("m")) return {"m", "mm", "um", "in"};
    if (si == QLatin1String("m/s")) return {"m/s", "mm/s", "in/s"};
    if (si == QLatin1String("N")) return {"N", "kN", "lbf"};
    return {"m/s^2", "mm/s^2"};
}

QComboBox* columnBox(const SignalInfo& r) {
    auto* col = new QComboBox;
    col->setSizeAdjustPolicy(QComboBox::AdjustToMinimumContentsLengthWithIcon);
    col->setMinimumContentsLength(14);
    col->setToolTip(QObject::tr("Column for %1 (default name \"%2\"; key \"%3\" on the command line)")
                        .arg(QString::fromUtf8(r.label).toLower(), QString::fromLatin1(io::defaultColumn(r.signal)),
                             QString::fromLatin1(io::signalKey(r.signal))));
    return col;
}

QComboBox* unitBox(const SignalInfo& r) {
    auto* unit = new QComboBox;
    unit->setEditable(true);
    unit->addItems(unitChoices(r.signal));
    unit->setMinimumContentsLength(5);
    unit->setSizeAdjustPolicy(QComboBox::AdjustToMinimumContentsLengthWithIcon);
    unit->setToolTip(QObject::tr("Unit of the column (converted to %1); any unit of the right dimension may be typed")
                         .arg(QString::fromLatin1(io::signalUnit(r.signal))));
    return unit;
}

}  // namespace

ImportColumnsPage::ImportColumnsPage(QWidget* parent) : QWidget(parent) {
    auto* layout = new QHBoxLayout(this);
    layout->addWidget(buildMappingBox(), 0);
    layout->addWidget(buildPreviewBox(), 1);
}

QWidget* ImportColumnsPage::buildMappingBox() {
    auto* mapBox = new QGroupBox(tr("Signals"));
    auto* grid = new QGridLayout(mapBox);
    grid->setHorizontalSpacing(8);
    grid->setVerticalSpacing(4);
    auto header = [](const QString& text) { return new QLabel(QStringLiteral("<b>%1</b>").arg(text)); };
    grid->addWidget(header(tr("Signal")), 0, 0, 1, 2);
    grid->addWidget(header(tr("Column")), 0, 2);
    grid->addWidget(header(tr("Unit")), 0, 3);
    int row = 1;
    for (const SignalInfo& r : signalRows()) {
        auto* name = new QLabel(QString::fromUtf8(r.label));
        auto* sym = new QLabel(QString::fromUtf8(r.symbol));
        sym->setStyleSheet(QStringLiteral("color: palette(mid);"));
        QComboBox* col = columnBox(r);
        QComboBox* unit = unitBox(r);
        columnCombos_[idx(r.signal)] = col;
        unitCombos_[idx(r.signal)] = unit;
        grid->addWidget(name, row, 0);
        grid->addWidget(sym, row, 1);
        grid->addWidget(col, row, 2);
        grid->addWidget(unit, row, 3);
        const io::Signal s = r.signal;
        connect(col, QOverload<int>::of(&QComboBox::currentIndexChanged), this, [this, s](int) { columnChosen(s); });
        connect(unit, &QComboBox::currentTextChanged, this, [this](const QString&) { emit unitChanged(); });
        ++row;
    }
    grid->setRowStretch(row, 1);
    mapBox->setSizePolicy(QSizePolicy::Maximum, QSizePolicy::Preferred);
    mapBox->setMaximumWidth(mapBox->sizeHint().width());
    return mapBox;
}

QWidget* ImportColumnsPage::buildPreviewBox() {
    auto* previewBox = new QGroupBox(tr("Preview"));
    auto* pl = new QVBoxLayout(previewBox);
    previewCaption_ = new QLabel;
    previewCaption_->setWordWrap(true);
    preview_ = new QTableWidget;
    preview_->setEditTriggers(QAbstractItemView::NoEditTriggers);
    preview_->setSelectionMode(QAbstractItemView::NoSelection);
    preview_->setAlternatingRowColors(true);
    preview_->verticalHeader()->setDefaultSectionSize(fontMetrics().height() + 4);
    preview_->horizontalHeader()->setDefaultAlignment(Qt::AlignCenter);
    pl->addWidget(previewCaption_);
    pl->addWidget(preview_, 1);
    previewBox->setMinimumWidth(420);
    return previewBox;
}

// --- mapping -----------------------------------------------------------------------------------

void ImportColumnsPage::populate(const QStringList& cols) {
    populating_ = true;
    for (const SignalInfo& r : signalRows()) {
        QComboBox* box = columnCombos_[idx(r.signal)];
        const QSignalBlocker block(box);
        box->clear();
        box->addItem(kNone);
        box->addItems(cols);
        const QString& want = chosen_[idx(r.signal)];
        const QString def = QString::fromLatin1(io::defaultColumn(r.signal));
        QString pick = kNone;
        if (want.isNull()) {
            if (cols.contains(def)) pick = def;
        } else if (!want.isEmpty()) {
            if (!cols.contains(want)) box->addItem(want);  // keeps the user's choice; validation names it
            pick = want;
        }
        box->setCurrentText(pick);
    }
    populating_ = false;
}

void ImportColumnsPage::columnChosen(io::Signal s) {
    if (populating_) return;
    const QString t = columnCombos_[idx(s)]->currentText();
    chosen_[idx(s)] = t == kNone ? QStringLiteral("") : t;
    emit columnChanged();
}

void ImportColumnsPage::setColumn(io::Signal s, const QString& column) {
    QComboBox* box = columnCombos_[idx(s)];
    const QString t = column.isEmpty() ? kNone : column;
    if (box->findText(t) < 0) box->addItem(t);
    box->setCurrentText(t);
    columnChosen(s);
}

QString ImportColumnsPage::column(io::Signal s) const {
    const QString t = columnCombos_[idx(s)]->currentText();
    return t == kNone ? QString() : t;
}

void ImportColumnsPage::setUnit(io::Signal s, const QString& unit) { unitCombos_[idx(s)]->setCurrentText(unit); }

QString ImportColumnsPage::unit(io::Signal s) const { return unitCombos_[idx(s)]->currentText().trimmed(); }

SignalTexts ImportColumnsPage::columns() const {
    SignalTexts out;
    for (size_t i = 0; i < io::kSignalCount; ++i) out[i] = column(static_cast<io::Signal>(i)).toStdString();
    return out;
}

SignalTexts ImportColumnsPage::units() const {
    SignalTexts out;
    for (size_t i = 0; i < io::kSignalCount; ++i) out[i] = unit(static_cast<io::Signal>(i)).toStdString();
    return out;
}

// --- preview table ------------------------------------------------------------------------------

void ImportColumnsPage::showPreview(const FilePreview* p, bool haveFiles) {
    preview_->clear();
    if (!p) {
        preview_->setRowCount(0);
        preview_->setColumnCount(0);
        previewCaption_->setText(haveFiles ? tr("Reading\u2026") : tr("No file."));
        return;
    }
    const QString name = QFileInfo(q(p->path)).fileName();
    if (!p->ok) {
        preview_->setRowCount(0);
        preview_->setColumnCount(0);
        previewCaption_->setText(tr("<b>%1</b> cannot be read.").arg(name.toHtmlEscaped()));
        return;
    }
    const int nc = static_cast<int>(p->header.size());
    preview_->setColumnCount(nc);
    preview_->setRowCount(static_cast<int>(p->rows.size()));
    fillPreviewHeader(*p);
    for (size_t i = 0; i < p->rows.size(); ++i) {
        preview_->setVerticalHeaderItem(static_cast<int>(i), new QTableWidgetItem(QString::number(p->rowLines[i])));
        for (int j = 0; j < nc; ++j) {
            auto* item = new QTableWidgetItem(QString::number(p->rows[i][static_cast<size_t>(j)], 'g', 7));
            item->setTextAlignment(Qt::AlignRight | Qt::AlignVCenter);
            preview_->setItem(static_cast<int>(i), j, item);
        }
    }
    preview_->resizeColumnsToContents();
    fitHeaderWidths();
    QString caption = tr("<b>%1</b>: %2 data rows \u00d7 %3 columns; first %4 shown (row labels are file lines).")
                          .arg(name.toHtmlEscaped())
                          .arg(p->rowCount)
                          .arg(nc)
                          .arg(p->rows.size());
    previewCaption_->setText(caption);
    QString comments;
    for (const std::string& c : p->comments) comments += (comments.isEmpty() ? "" : "\n") + q(c);
    previewCaption_->setToolTip(comments);
}

// Column headers name the signal(s) each column feeds under the current mapping, so a wrong
// choice shows in the table at once.
void ImportColumnsPage::fillPreviewHeader(const FilePreview& p) {
    std::map<std::string, QStringList> feeds;
    for (const SignalInfo& r : signalRows()) {
        const QString col = column(r.signal);
        if (!col.isEmpty()) feeds[col.toStdString()] << QString::fromUtf8(r.symbol).section(QLatin1Char(' '), 0, 0);
    }
    for (int j = 0; j < static_cast<int>(p.header.size()); ++j) {
        const std::string& name = p.header[static_cast<size_t>(j)];
        const auto f = feeds.find(name);
        const bool used = f != feeds.end();
        auto* h = new QTableWidgetItem(used ? QStringLiteral("%1\n\u2192 %2").arg(q(name), f->second.join(", "))
                                            : QStringLiteral("%1\n(unused)").arg(q(name)));
        QFont font = h->font();
        font.setBold(used);
        h->setFont(font);
        if (!used) h->setForeground(palette().brush(QPalette::Disabled, QPalette::Text));
        preview_->setHorizontalHeaderItem(j, h);
    }
}

// The header's own size hint measures a label in the header's font, but the style paints it bold
// (the mapped columns, and any header of a selected column): each column is widened to its label's
// lines in bold plus the style's margins, so no header is clipped.
void ImportColumnsPage::fitHeaderWidths() {
    QHeaderView* header = preview_->horizontalHeader();
    QFont bold = header->font();
    bold.setBold(true);
    const QFontMetrics fm(bold);
    const int margin = 2 * header->style()->pixelMetric(QStyle::PM_HeaderMargin, nullptr, header) + fm.averageCharWidth();
    for (int j = 0; j < preview_->columnCount(); ++j) {
        const QTableWidgetItem* h = preview_->horizontalHeaderItem(j);
        if (!h) continue;
        int text = 0;
        for (const QString& line : h->text().split(QLatin1Char('\n'))) text = std::max(text, fm.horizontalAdvance(line));
        if (preview_->columnWidth(j) < text + margin) preview_->setColumnWidth(j, text + margin);
    }
}

}  // namespace stickslip::gui
