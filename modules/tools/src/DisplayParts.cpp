#include "reamsim/tools/ReamerGeometry.h"

namespace reamsim {

ReamerDisplayParts buildDisplayParts(const ReamerSpec& spec) {
  validateReamerSpec(spec);
  ReamerDisplayParts parts;
  // Display meshes need not match the cutting resolution; a coarser ring keeps the scene light.
  const int n = spec.segments < 48 ? spec.segments : 48;
  parts.guidePin = buildClosedCylinder(spec.guidePinDiameterMm / 2, 0.0, spec.guidePinLengthMm, n);
  const double back = -capHeight(spec) - spec.bodyLengthMm;
  parts.shaft = buildClosedCylinder(spec.shaftDiameterMm / 2, back - spec.shaftLengthMm, back, n);
  return parts;
}

}  // namespace reamsim
