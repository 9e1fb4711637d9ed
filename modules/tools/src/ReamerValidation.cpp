#include <cmath>
#include <stdexcept>
#include <string>

#include "reamsim/tools/ReamerGeometry.h"

namespace reamsim {

namespace {
[[noreturn]] void fail(const ReamerSpec& spec, const std::string& problem) {
  throw std::invalid_argument("reamer '" + spec.name + "': " + problem);
}
bool positiveFinite(double v) { return std::isfinite(v) && v > 0; }
bool nonNegativeFinite(double v) { return std::isfinite(v) && v >= 0; }
}  // namespace

void validateReamerSpec(const ReamerSpec& spec) {
  if (!positiveFinite(spec.diameterMm)) fail(spec, "diameterMm must be a positive finite number");
  if (std::isnan(spec.sphereRadiusMm) || !(spec.sphereRadiusMm > 0))
    fail(spec, "sphereRadiusMm must be positive (or infinite for a flat reamer)");
  if (!spec.isFlat() && spec.diameterMm / 2 > spec.sphereRadiusMm)
    fail(spec, "diameter " + std::to_string(spec.diameterMm) + " mm needs a sphere radius of at least " +
                   std::to_string(spec.diameterMm / 2) + " mm (D/2 <= R), got " +
                   std::to_string(spec.sphereRadiusMm) + " mm");
  if (!nonNegativeFinite(spec.bodyLengthMm)) fail(spec, "bodyLengthMm must be a finite number >= 0");
  if (spec.isFlat() && spec.bodyLengthMm <= 0)
    fail(spec, "a flat reamer needs bodyLengthMm > 0 (otherwise it has no volume)");
  if (!nonNegativeFinite(spec.guidePinDiameterMm) || !nonNegativeFinite(spec.guidePinLengthMm))
    fail(spec, "guide pin diameter and length must be finite numbers >= 0");
  if (!nonNegativeFinite(spec.shaftDiameterMm) || !nonNegativeFinite(spec.shaftLengthMm))
    fail(spec, "shaft diameter and length must be finite numbers >= 0");
  if (spec.segments < 3) fail(spec, "segments must be at least 3");
  if (spec.rings < 1) fail(spec, "rings must be at least 1");
  // Keeps vertex indices far inside uint32 and memory bounded.
  if (spec.segments > 100000 || spec.rings > 100000 ||
      static_cast<double>(spec.segments) * spec.rings > 5.0e7)
    fail(spec, "segments x rings is too large");
}

double capHeight(const ReamerSpec& spec) {
  if (spec.isFlat()) return 0.0;
  const double r = spec.diameterMm / 2, R = spec.sphereRadiusMm;
  // R - sqrt(R^2 - r^2) written as r^2 / (R + sqrt(R^2 - r^2)) to avoid cancellation for large R.
  return r * r / (R + std::sqrt(std::max(0.0, R * R - r * r)));
}

double idealCuttingVolume(const ReamerSpec& spec) {
  validateReamerSpec(spec);
  constexpr double kPi = 3.14159265358979323846;
  const double r = spec.diameterMm / 2;
  const double body = kPi * r * r * spec.bodyLengthMm;
  if (spec.isFlat()) return body;
  const double h = capHeight(spec);
  return body + kPi * h * h * (3 * spec.sphereRadiusMm - h) / 3;
}

}  // namespace reamsim
