#pragma once
// How a volume slice is laid on the screen. Slices are shown the way radiologists read them when the
// volume names its patient frame: axial from the feet (patient's right on the screen's left, anterior
// up), coronal from the front (superior up), sagittal from the patient's left (anterior on the left,
// superior up). Oblique volumes get the nearest of these; a volume without a frame is shown as stored
// (columns to the right, rows down).
#include <QPoint>
#include <QSize>
#include <QString>

#include "reamsim/ctimport/Preview.h"

namespace reamsim::ui::ct_import {

enum class SliceKind { Axial, Coronal, Sagittal, Plain };

// The kind of the slices across `axis` (0 = i, 1 = j, 2 = k): by the world axis nearest the slice normal.
SliceKind sliceKind(const ct::CtVolume& volume, int axis);
QString sliceKindName(SliceKind kind, int axis);  // "axial", … or "i slice" for Plain

// Display pixel (dx, dy) ↔ image pixel (x, y) of ct::SliceImage (x along rowDirection, y along columnDirection).
struct SliceOrientation {
  bool transpose = false;  // screen x runs along the image's y
  bool flipX = false, flipY = false;  // applied after the transpose, on screen axes

  QSize displaySize(int width, int height) const { return transpose ? QSize(height, width) : QSize(width, height); }
  QPoint imageToDisplay(QPoint image, int width, int height) const;
  QPoint displayToImage(QPoint display, int width, int height) const;
  // Millimetres per display pixel along screen x and y.
  double displaySpacingX(const ct::SliceImage& s) const { return s.pixelSpacing[transpose ? 1 : 0]; }
  double displaySpacingY(const ct::SliceImage& s) const { return s.pixelSpacing[transpose ? 0 : 1]; }
};

SliceOrientation sliceOrientation(const ct::SliceImage& slice, SliceKind kind);

}  // namespace reamsim::ui::ct_import
