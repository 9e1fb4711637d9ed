#include "reamsim/core/Pose.h"

#include <cmath>
#include <stdexcept>

namespace reamsim {

namespace {
constexpr double kPi = 3.14159265358979323846;

Vec3 unitAxis(const Pose& pose) {
  const double n = norm(pose.axis);
  if (!(n > 0) || !std::isfinite(n)) throw std::invalid_argument("Pose axis must be a finite, non-zero vector");
  return pose.axis / n;
}
}  // namespace

RigidTransform toTransform(const Pose& pose) {
  const Vec3 z = unitAxis(pose);
  if (!isFinite(pose.tip)) throw std::invalid_argument("Pose tip must be finite (NaN or infinity in it)");
  if (!std::isfinite(pose.rollDeg)) throw std::invalid_argument("Pose roll must be a finite angle");
  // Reference: the world axis least aligned with z, so the projection below never degenerates and
  // the same axis always yields the same frame (identity for +Z).
  const double ax = std::abs(z.x), ay = std::abs(z.y), az = std::abs(z.z);
  const Vec3 ref = (ax <= ay && ax <= az) ? Vec3{1, 0, 0} : (ay <= az ? Vec3{0, 1, 0} : Vec3{0, 0, 1});
  const Vec3 x0 = normalized(ref - z * dot(ref, z));
  const Vec3 y0 = cross(z, x0);
  const double roll = pose.rollDeg * kPi / 180.0;
  const Vec3 x = x0 * std::cos(roll) + y0 * std::sin(roll);
  const Vec3 y = cross(z, x);

  RigidTransform t;  // columns are the images of local X, Y, Z
  t.rotation = {x.x, y.x, z.x, x.y, y.y, z.y, x.z, y.z, z.z};
  t.translation = pose.tip;
  return t;
}

Pose advancedAlongAxis(const Pose& pose, double distanceMm) {
  Pose out = pose;
  out.tip = pose.tip + unitAxis(pose) * distanceMm;
  return out;
}

}  // namespace reamsim
