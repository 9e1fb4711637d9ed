#include "SliceView.h"

#include <QMouseEvent>
#include <QPainter>
#include <algorithm>
#include <cmath>

namespace reamsim::ui::ct_import {
namespace {

// The threshold overlay: orange at 45 % over the grey, so the anatomy stays readable under it.
constexpr int kOverlayR = 255, kOverlayG = 140, kOverlayB = 0;
constexpr double kOverlayAlpha = 0.45;

}  // namespace

SliceView::SliceView(QWidget* parent) : QWidget(parent) {
  setMouseTracking(false);
  setSizePolicy(QSizePolicy::Expanding, QSizePolicy::Expanding);
  setAttribute(Qt::WA_OpaquePaintEvent);
}

void SliceView::setSlice(ct::SliceImage slice, SliceOrientation orientation) {
  slice_ = std::move(slice);
  orientation_ = orientation;
  compose();
}

void SliceView::clear() {
  slice_ = {};
  image_ = {};
  maskPixels_ = 0;
  update();
}

void SliceView::setWindow(double level, double width) {
  level_ = level;
  width_ = std::max(width, 1.0);
  compose();
}

void SliceView::setCrosshair(QPoint imagePixel) {
  crosshair_ = imagePixel;
  update();
}

void SliceView::compose() {
  maskPixels_ = 0;
  if (slice_.width <= 0 || slice_.height <= 0) {
    image_ = {};
    update();
    return;
  }
  const QSize d = orientation_.displaySize(slice_.width, slice_.height);
  image_ = QImage(d, QImage::Format_RGB32);
  const double low = level_ - width_ / 2;
  for (int y = 0; y < slice_.height; ++y)
    for (int x = 0; x < slice_.width; ++x) {
      const std::size_t p = std::size_t(y) * slice_.width + x;
      const double g = std::clamp((slice_.values[p] - low) / width_, 0.0, 1.0) * 255.0;
      double r = g, gr = g, b = g;
      if (slice_.mask[p]) {
        ++maskPixels_;
        r = g * (1 - kOverlayAlpha) + kOverlayR * kOverlayAlpha;
        gr = g * (1 - kOverlayAlpha) + kOverlayG * kOverlayAlpha;
        b = g * (1 - kOverlayAlpha) + kOverlayB * kOverlayAlpha;
      }
      const QPoint at = orientation_.imageToDisplay({x, y}, slice_.width, slice_.height);
      image_.setPixel(at, qRgb(int(std::lround(r)), int(std::lround(gr)), int(std::lround(b))));
    }
  update();
}

QRectF SliceView::imageRect() const {
  if (image_.isNull()) return {};
  // True proportions: millimetres, not voxels, decide the aspect ratio.
  const double wMm = image_.width() * orientation_.displaySpacingX(slice_);
  const double hMm = image_.height() * orientation_.displaySpacingY(slice_);
  const double scale = std::min(width() / wMm, height() / hMm);
  const QSizeF size(wMm * scale, hMm * scale);
  return {QPointF((width() - size.width()) / 2, (height() - size.height()) / 2), size};
}

void SliceView::paintEvent(QPaintEvent*) {
  QPainter p(this);
  p.fillRect(rect(), Qt::black);
  if (image_.isNull()) return;
  const QRectF target = imageRect();
  p.drawImage(target, image_);  // nearest neighbour: voxels stay visible as voxels
  if (crosshair_.x() < 0 || crosshair_.y() < 0) return;
  // The other two slices: a vertical and a horizontal line through the crosshair pixel's centre.
  const QPoint d = orientation_.imageToDisplay(crosshair_, slice_.width, slice_.height);
  const double sx = target.width() / image_.width(), sy = target.height() / image_.height();
  const double cx = target.left() + (d.x() + 0.5) * sx, cy = target.top() + (d.y() + 0.5) * sy;
  p.setPen(QPen(QColor(80, 200, 255, 160), 1));
  p.drawLine(QPointF(cx, target.top()), QPointF(cx, target.bottom()));
  p.drawLine(QPointF(target.left(), cy), QPointF(target.right(), cy));
}

void SliceView::pick(const QPointF& at) {
  const QRectF target = imageRect();
  if (target.isEmpty() || !target.contains(at)) return;
  const int dx = std::clamp(int((at.x() - target.left()) / target.width() * image_.width()), 0, image_.width() - 1);
  const int dy = std::clamp(int((at.y() - target.top()) / target.height() * image_.height()), 0, image_.height() - 1);
  Q_EMIT picked(orientation_.displayToImage({dx, dy}, slice_.width, slice_.height));
}

void SliceView::mousePressEvent(QMouseEvent* e) {
  if (e->button() == Qt::LeftButton) pick(e->localPos());
}

void SliceView::mouseMoveEvent(QMouseEvent* e) {
  if (e->buttons() & Qt::LeftButton) pick(e->localPos());
}

}  // namespace reamsim::ui::ct_import
