#include "plot_export.hpp"

#include <qwt_matrix_raster_data.h>
#include <qwt_plot.h>
#include <qwt_plot_curve.h>
#include <qwt_plot_renderer.h>
#include <qwt_plot_spectrogram.h>

#include <QBuffer>
#include <QFileInfo>
#include <QImage>
#include <QPageSize>
#include <QPainter>
#include <QPdfWriter>
#include <QSaveFile>
#include <QSvgGenerator>
#include <QTextStream>
#include <algorithm>

namespace stickslip::widgets {

namespace {

void setError(QString* error, const QString& msg) {
    if (error) *error = msg;
}

bool commit(QSaveFile& file, QString* error) {
    if (!file.commit()) {
        setError(error, QStringLiteral("%1: could not write: %2").arg(file.fileName(), file.errorString()));
        return false;
    }
    return true;
}

QString csvField(const QString& s) {
    if (s.contains(QLatin1Char(',')) || s.contains(QLatin1Char('"')) || s.contains(QLatin1Char('\n'))) {
        QString q = s;
        q.replace(QLatin1String("\""), QLatin1String("\"\""));
        return QLatin1Char('"') + q + QLatin1Char('"');
    }
    return s;
}

QString num(double v) { return QString::number(v, 'g', 17); }

void configure(QwtPlotRenderer& r) {
    // Paper-like documents: white page (the widget's grey background is dropped).
    r.setDiscardFlag(QwtPlotRenderer::DiscardBackground, true);
    r.setDiscardFlag(QwtPlotRenderer::DiscardCanvasBackground, false);
    r.setDiscardFlag(QwtPlotRenderer::DiscardCanvasFrame, false);
    r.setLayoutFlag(QwtPlotRenderer::FrameWithScales, true);
}

}  // namespace

// Mirrors QwtPlotRenderer::renderDocument(), but renders into a QSaveFile so the target
// appears only complete (renderDocument writes the final file name directly).
bool exportPlot(const QwtPlot* plot, const QString& path, QString* error, const ExportOptions& options) {
    return exportPlots({plot}, 1, path, error, options);
}

bool exportPlots(const std::vector<const QwtPlot*>& plots, int columns, const QString& path, QString* error,
                 const ExportOptions& options) {
    if (plots.empty() || std::find(plots.begin(), plots.end(), nullptr) != plots.end()) {
        setError(error, QStringLiteral("%1: no plot to export").arg(path));
        return false;
    }
    columns = std::max(1, std::min(columns, static_cast<int>(plots.size())));
    const int rows = (static_cast<int>(plots.size()) + columns - 1) / columns;
    const QString fmt = QFileInfo(path).suffix().toLower();
    if (fmt != QLatin1String("png") && fmt != QLatin1String("svg") && fmt != QLatin1String("pdf")) {
        setError(error, QStringLiteral("%1: unknown export format \"%2\" (use .png, .svg or .pdf)").arg(path, fmt));
        return false;
    }
    if (options.size_mm.isEmpty() || options.resolution_dpi <= 0) {
        setError(error, QStringLiteral("%1: export size and resolution must be positive").arg(path));
        return false;
    }
    constexpr double mmToInch = 1.0 / 25.4;
    const int dpi = options.resolution_dpi;
    const QSizeF size = options.size_mm * mmToInch * dpi;
    const QRectF documentRect(0.0, 0.0, size.width(), size.height());
    QwtPlotRenderer renderer;
    configure(renderer);
    // Each plot in its cell; render() only reads the plot but takes a non-const pointer.
    auto renderAll = [&](QPainter& painter, const QRectF& page) {
        const double cw = page.width() / columns, ch = page.height() / rows;
        for (size_t i = 0; i < plots.size(); ++i) {
            const int r = static_cast<int>(i) / columns, c = static_cast<int>(i) % columns;
            const QRectF cell(page.left() + c * cw, page.top() + r * ch, cw, ch);
            renderer.render(const_cast<QwtPlot*>(plots[i]), &painter, cell.adjusted(2, 2, -2, -2));
        }
    };

    QSaveFile file(path);
    if (!file.open(QIODevice::WriteOnly)) {
        setError(error, QStringLiteral("%1: cannot open for writing: %2").arg(path, file.errorString()));
        return false;
    }
    const QString title = plots.front()->title().text();
    if (fmt == QLatin1String("svg")) {
        QSvgGenerator generator;
        generator.setTitle(title.isEmpty() ? QStringLiteral("StickSlip Lab plot") : title);
        generator.setOutputDevice(&file);
        generator.setResolution(dpi);
        generator.setSize(documentRect.size().toSize());
        generator.setViewBox(documentRect);
        QPainter painter(&generator);
        renderAll(painter, documentRect);
    } else if (fmt == QLatin1String("pdf")) {
        QPdfWriter writer(&file);
        writer.setTitle(title);
        writer.setCreator(QStringLiteral("StickSlip Lab"));
        writer.setPageSize(QPageSize(options.size_mm, QPageSize::Millimeter));
        writer.setPageMargins(QMarginsF(0, 0, 0, 0));
        writer.setResolution(dpi);
        QPainter painter(&writer);
        renderAll(painter, documentRect);
    } else {
        const QRect imageRect = documentRect.toRect();
        const int dotsPerMeter = qRound(dpi * mmToInch * 1000.0);
        QImage image(imageRect.size(), QImage::Format_ARGB32);
        image.setDotsPerMeterX(dotsPerMeter);
        image.setDotsPerMeterY(dotsPerMeter);
        image.fill(QColor(Qt::white).rgb());
        {
            QPainter painter(&image);
            renderAll(painter, QRectF(imageRect));
        }
        if (!image.save(&file, "PNG")) {
            file.cancelWriting();
            setError(error, QStringLiteral("%1: PNG encoding failed").arg(path));
            return false;
        }
    }
    return commit(file, error);
}

bool exportCsv(const QwtPlot* plot, const QString& path, QString* error) {
    if (!plot) {
        setError(error, QStringLiteral("no plot to export"));
        return false;
    }
    QString text;
    QTextStream out(&text);
    const QString title = plot->title().text();
    if (!title.isEmpty()) out << "# " << title << '\n';
    const QString xTitle = plot->axisTitle(QwtPlot::xBottom).text();

    const auto curves = plot->itemList(QwtPlotItem::Rtti_PlotCurve);
    if (!curves.isEmpty()) {
        // One y column name per axis in use; curves on the right axis are named in the rows.
        const QString yTitle = plot->axisTitle(QwtPlot::yLeft).text();
        out << "series," << csvField(xTitle.isEmpty() ? QStringLiteral("x") : xTitle) << ','
            << csvField(yTitle.isEmpty() ? QStringLiteral("y") : yTitle) << '\n';
        for (const auto* item : curves) {
            const auto* c = static_cast<const QwtPlotCurve*>(item);
            QString name = c->title().text();
            if (c->yAxis() == QwtPlot::yRight) {
                name += QStringLiteral(" [right axis: %1]").arg(plot->axisTitle(QwtPlot::yRight).text());
            }
            const QString field = csvField(name);
            for (size_t i = 0; i < c->dataSize(); ++i) {
                const QPointF p = c->sample(static_cast<int>(i));
                out << field << ',' << num(p.x()) << ',' << num(p.y()) << '\n';
            }
        }
    }
    for (const auto* item : plot->itemList(QwtPlotItem::Rtti_PlotSpectrogram)) {
        const auto* s = static_cast<const QwtPlotSpectrogram*>(item);
        const auto* m = dynamic_cast<const QwtMatrixRasterData*>(s->data());
        if (!m) continue;
        const QString yTitle = plot->axisTitle(QwtPlot::yLeft).text();
        out << "series," << csvField(xTitle) << ',' << csvField(yTitle) << ",value\n";
        const int nx = m->numColumns();
        const int ny = m->numRows();
        const QwtInterval ix = m->interval(Qt::XAxis), iy = m->interval(Qt::YAxis);
        const double dx = nx > 0 ? ix.width() / nx : 0.0, dy = ny > 0 ? iy.width() / ny : 0.0;
        const QVector<double> values = m->valueMatrix();
        for (int r = 0; r < ny; ++r) {
            for (int col = 0; col < nx; ++col) {
                out << csvField(s->title().text()) << ',' << num(ix.minValue() + (col + 0.5) * dx) << ','
                    << num(iy.minValue() + (r + 0.5) * dy) << ',' << num(values[r * nx + col]) << '\n';
            }
        }
    }
    out.flush();
    QSaveFile file(path);
    if (!file.open(QIODevice::WriteOnly | QIODevice::Text)) {
        setError(error, QStringLiteral("%1: cannot open for writing: %2").arg(path, file.errorString()));
        return false;
    }
    file.write(text.toUtf8());
    return commit(file, error);
}

}  // namespace stickslip::widgets
