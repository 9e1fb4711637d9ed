#include "SliceOrientation.h"

#include <cmath>

namespace reamsim::ui::ct_import {
namespace {

// Screen right and screen down for each kind, in LPS (x left, y posterior, z superior).
void screenAxesLps(SliceKind kind, Vec3& right, Vec3& down) {
  switch (kind) {
    case SliceKind::Axial: right = {1, 0, 0}; down = {0, 1, 0}; break;      // from the feet, anterior up
    case SliceKind::Coronal: right = {1, 0, 0}; down = {0, 0, -1}; break;   // from the front
    case SliceKind::Sagittal: right = {0, 1, 0}; down = {0, 0, -1}; break;  // anterior on the left
    case SliceKind::Plain: right = {0, 0, 0}; down = {0, 0, 0}; break;
  }
}

}  // namespace

SliceKind sliceKind(const ct::CtVolume& volume, int axis) {
  if (volume.space == ct::PatientSpace::Unspecified) return SliceKind::Plain;
  const Vec3 n = volume.axis(axis);
  const double ax = std::abs(n.x), ay = std::abs(n.y), az = std::abs(n.z);
  if (az >= ax && az >= ay) return SliceKind::Axial;
  if (ay >= ax) return SliceKind::Coronal;
  return SliceKind::Sagittal;
}

QString sliceKindName(SliceKind kind, int axis) {
  switch (kind) {
    case SliceKind::Axial: return QStringLiteral("axial");
    case SliceKind::Coronal: return QStringLiteral("coronal");
    case SliceKind::Sagittal: return QStringLiteral("sagittal");
    case SliceKind::Plain: break;
  }
  return QStringLiteral("%1 slice").arg(QChar("ijk"[axis]));
}

SliceOrientation sliceOrientation(const ct::SliceImage& s, SliceKind kind) {
  SliceOrientation o;
  if (kind == SliceKind::Plain) return o;  // no anatomy to go by: as stored
  Vec3 right, down;
  screenAxesLps(kind, right, down);
  if (s.space == ct::PatientSpace::RAS) {  // the same anatomical directions in RAS coordinates
    right = {-right.x, -right.y, right.z};
    down = {-down.x, -down.y, down.z};
  }
  const Vec3 r = s.rowDirection, c = s.columnDirection;
  o.transpose = std::abs(dot(c, right)) + std::abs(dot(r, down)) > std::abs(dot(r, right)) + std::abs(dot(c, down));
  const Vec3 screenX = o.transpose ? c : r, screenY = o.transpose ? r : c;
  o.flipX = dot(screenX, right) < 0;
  o.flipY = dot(screenY, down) < 0;
  return o;
}

QPoint SliceOrientation::imageToDisplay(QPoint image, int width, int height) const {
  const QSize d = displaySize(width, height);
  int ux = transpose ? image.y() : image.x();
  int uy = transpose ? image.x() : image.y();
  if (flipX) ux = d.width() - 1 - ux;
  if (flipY) uy = d.height() - 1 - uy;
  return {ux, uy};
}

QPoint SliceOrientation::displayToImage(QPoint display, int width, int height) const {
  const QSize d = displaySize(width, height);
  const int ux = flipX ? d.width() - 1 - display.x() : display.x();
  const int uy = flipY ? d.height() - 1 - display.y() : display.y();
  return transpose ? QPoint(uy, ux) : QPoint(ux, uy);
}

}  // namespace reamsim::ui::ct_import
