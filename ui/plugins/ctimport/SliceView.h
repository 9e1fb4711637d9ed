#pragma once
// One orthogonal slice of the volume: grey values through a CT window (level/width) with the threshold
// mask overlaid in a translucent colour, drawn with true proportions (anisotropic voxels), plus a
// crosshair at the other two slices. A click or drag reports the image pixel under the mouse.
#include <QImage>
#include <QWidget>

#include "SliceOrientation.h"

namespace reamsim::ui::ct_import {

class SliceView : public QWidget {
  Q_OBJECT
 public:
  explicit SliceView(QWidget* parent = nullptr);

  void setSlice(ct::SliceImage slice, SliceOrientation orientation);
  void clear();
  void setWindow(double level, double width);
  void setCrosshair(QPoint imagePixel);  // x: column of one other slice, y: row of the other; (-1,-1) = none

  const ct::SliceImage& slice() const { return slice_; }
  int maskPixels() const { return maskPixels_; }
  const QImage& composed() const { return image_; }  // as shown, one pixel per voxel

  QSize sizeHint() const override { return {260, 260}; }
  QSize minimumSizeHint() const override { return {120, 120}; }

 Q_SIGNALS:
  void picked(QPoint imagePixel);

 protected:
  void paintEvent(QPaintEvent* e) override;
  void mousePressEvent(QMouseEvent* e) override;
  void mouseMoveEvent(QMouseEvent* e) override;

 private:
  void compose();
  QRectF imageRect() const;  // where the image is drawn, in widget coordinates
  void pick(const QPointF& at);

  ct::SliceImage slice_;
  SliceOrientation orientation_;
  double level_ = 400, width_ = 2000;
  QPoint crosshair_{-1, -1};
  QImage image_;
  int maskPixels_ = 0;
};

}  // namespace reamsim::ui::ct_import
