#pragma once
// Internal: the preconditions the queries check first. A pose with a NaN or an infinity, or whose rotation
// part is not a rotation, has no answer; without this check the bounds compare false and a query would
// answer "no contact", which would let a reamer driven by a faulty device pass through the bone. A ray with
// a NaN or an infinity, or no direction, has none either (a NaN origin made every triangle a "hit").
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "reamsim/core/Pose.h"
#include "reamsim/mesh/Vec3.h"

namespace reamsim::detail {

// Throws std::invalid_argument naming `query` and `which` ("pose", "start pose", ...) unless every number of
// `pose` is finite and its rotation is orthonormal with determinant +1 (to 1e-6: rotations built by
// toTransform or interpolated along a motion are so to rounding).
inline void requireRigidPose(const RigidTransform& pose, const char* query, const char* which) {
  const auto& r = pose.rotation;
  bool finite = isFinite(pose.translation);
  for (double v : r) finite = finite && std::isfinite(v);
  if (!finite)
    throw std::invalid_argument(std::string(query) + ": the " + which + " is not finite (NaN or infinity in it)");
  double off = 0;  // largest entry of R R^T - I
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      const double d = r[3 * i] * r[3 * j] + r[3 * i + 1] * r[3 * j + 1] + r[3 * i + 2] * r[3 * j + 2] - (i == j ? 1.0 : 0.0);
      off = std::max(off, std::abs(d));
    }
  const double det = r[0] * (r[4] * r[8] - r[5] * r[7]) - r[1] * (r[3] * r[8] - r[5] * r[6]) + r[2] * (r[3] * r[7] - r[4] * r[6]);
  if (!(off <= 1e-6) || !(det > 0))
    throw std::invalid_argument(std::string(query) + ": the " + which + "'s rotation is not a rotation (not orthonormal, or a reflection)");
}

// Throws std::invalid_argument naming `query` unless the ray's origin and direction are finite and the
// direction is not zero.
inline void requireRay(const Vec3& origin, const Vec3& dir, const char* query) {
  if (!isFinite(origin) || !isFinite(dir))
    throw std::invalid_argument(std::string(query) + ": the ray's origin or direction is not finite (NaN or infinity in it)");
  if (dir.x == 0 && dir.y == 0 && dir.z == 0) throw std::invalid_argument(std::string(query) + ": the ray has no direction (zero vector)");
}

}  // namespace reamsim::detail
