// Sub-steps of a move that turns the reamer (SweptVolume.h): plain rotation arithmetic, no CGAL.
#include <algorithm>
#include <cmath>

#include "reamsim/csg/SweptVolume.h"

namespace reamsim {
namespace {

using Mat = std::array<double, 9>;  // row-major, as RigidTransform::rotation

Mat multiply(const Mat& a, const Mat& b) {
  Mat c{};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) c[3 * i + j] = a[3 * i] * b[j] + a[3 * i + 1] * b[3 + j] + a[3 * i + 2] * b[6 + j];
  return c;
}

// Rotation by `angle` about the unit axis k (Rodrigues).
Mat rotationAbout(const Vec3& k, double angle) {
  const double c = std::cos(angle), s = std::sin(angle), v = 1 - c;
  return {c + k.x * k.x * v,       k.x * k.y * v - k.z * s, k.x * k.z * v + k.y * s,
          k.y * k.x * v + k.z * s, c + k.y * k.y * v,       k.y * k.z * v - k.x * s,
          k.z * k.x * v - k.y * s, k.z * k.y * v + k.x * s, c + k.z * k.z * v};
}

Vec3 axisOf(const RigidTransform& t) { return t.applyToDirection({0, 0, 1}); }

}  // namespace

TurnPath::TurnPath(const RigidTransform& from, const RigidTransform& to) : from_(from), to_(to) {
  const Vec3 a0 = axisOf(from), a1 = axisOf(to);
  const Vec3 k = cross(a0, a1);
  const double angle = std::atan2(norm(k), dot(a0, a1));
  if (!isFinite(k) || !isFinite(to.translation - from.translation) || !std::isfinite(angle) || !(norm(k) > 1e-12) ||
      !(angle < M_PI - 1e-6))
    return;
  k_ = k / norm(k);
  angle_ = angle;
}

RigidTransform TurnPath::at(double s) const {
  if (s >= 1) return to_;
  RigidTransform t;
  t.rotation = multiply(rotationAbout(k_, s * angle_), from_.rotation);
  t.translation = from_.translation + (to_.translation - from_.translation) * s;
  return t;
}

double TurnPath::sidewaysTravelMm() const {
  const Vec3 d = to_.translation - from_.translation, axis = axisOf(to_);
  return norm(d - axis * dot(d, axis));
}

int turnSubSteps(const TurnPath& path, double radiusMm, double maxTravelMm, bool countSidewaysTravel, int maxSteps) {
  // A point q of the solid moves by at most |travel| + angle |q| over the whole move, and evenly spaced
  // sub-steps split both parts evenly.
  const double farthest =
      (countSidewaysTravel ? path.sidewaysTravelMm() : 0.0) + path.angle() * std::max(0.0, radiusMm);
  const double n = maxTravelMm > 0 ? std::ceil(farthest / maxTravelMm) : 1.0;
  return static_cast<int>(std::clamp(std::isfinite(n) ? n : 1.0, 1.0, static_cast<double>(std::max(1, maxSteps))));
}

}  // namespace reamsim
