#include "wrapped_text_label.hpp"

#include <qwt_text.h>

#include <QPainter>
#include <algorithm>

namespace stickslip::widgets {

QRectF WrappedTextLabel::textRect(const QRectF& canvasRect, const QFont& font) const {
    QwtText t = text();
    if (t.isEmpty()) return {};
    t.setRenderFlags(t.renderFlags() | Qt::TextWordWrap);
    const double m = margin();
    const QRectF area = canvasRect.adjusted(m, m, -m, -m);
    const QFont f = t.usedFont(font);
    const double w = std::max(0.0, std::min(t.textSize(f).width(), area.width()));
    return {area.left(), area.top(), w, t.heightForWidth(w, f)};
}

void WrappedTextLabel::draw(QPainter* painter, const QwtScaleMap&, const QwtScaleMap&, const QRectF& canvasRect) const {
    QwtText t = text();
    if (t.isEmpty()) return;
    t.setRenderFlags(t.renderFlags() | Qt::TextWordWrap);
    t.draw(painter, textRect(canvasRect, painter->font()));
}

}  // namespace stickslip::widgets
