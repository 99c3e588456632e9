#include "wrapped_text_label.hpp"

#include <qwt_text.h>

#include <QPainter>
#include <algorithm>

namespace stickslip::widgets {

namespace {

// The label's text with wrapping on, whatever flags it was given.
QwtText wrapping(QwtText t) {
    t.setRenderFlags(t.renderFlags() | Qt::TextWordWrap);
    return t;
}

QRectF rectIn(const QwtText& t, const QRectF& canvasRect, double margin, const QFont& font) {
    if (t.isEmpty()) return {};
    const QRectF area = canvasRect.adjusted(margin, margin, -margin, -margin);
    const QFont f = t.usedFont(font);
    const double w = std::max(0.0, std::min(t.textSize(f).width(), area.width()));
    return {area.left(), area.top(), w, t.heightForWidth(w, f)};
}

}  // namespace

QRectF WrappedTextLabel::textRect(const QRectF& canvasRect, const QFont& font) const {
    return rectIn(wrapping(text()), canvasRect, margin(), font);
}

void WrappedTextLabel::draw(QPainter* painter, const QwtScaleMap&, const QwtScaleMap&, const QRectF& canvasRect) const {
    const QwtText t = wrapping(text());
    if (!t.isEmpty()) t.draw(painter, rectIn(t, canvasRect, margin(), painter->font()));
}

}  // namespace stickslip::widgets
