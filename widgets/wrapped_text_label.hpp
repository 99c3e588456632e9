// A text label in a plot canvas that wraps at the canvas width.
#pragma once

#include <qwt_plot_textlabel.h>

#include <QFont>
#include <QRectF>

namespace stickslip::widgets {

// QwtPlotTextLabel lays its text out at its natural size, so in a narrow dock a long line ran off
// the canvas's right edge. This label is aligned top left and wraps (Qt::TextWordWrap) at the
// canvas width less the margin; its background fills only the text's rectangle.
class WrappedTextLabel : public QwtPlotTextLabel {
public:
    void draw(QPainter* painter, const QwtScaleMap& xMap, const QwtScaleMap& yMap, const QRectF& canvasRect) const override;
    // Where the text goes in a canvas rectangle, with `font` the painter's font: inside the
    // canvas (less the margin), as wide as the text or the canvas, as high as wrapping needs.
    QRectF textRect(const QRectF& canvasRect, const QFont& font) const;
};

}  // namespace stickslip::widgets
