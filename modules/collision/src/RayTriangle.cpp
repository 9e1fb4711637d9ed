#include "reamsim/collision/RayTriangle.h"

#include <algorithm>

namespace reamsim {

std::optional<RayHit> intersectRayTriangle(const Vec3& origin, const Vec3& dir, const Vec3& a, const Vec3& b,
                                           const Vec3& c, Culling culling) {
  const Vec3 e1 = b - a, e2 = c - a;
  const Vec3 p = cross(dir, e2);
  const double det = dot(e1, p);  // = -dir . (e1 x e2): positive when the ray enters through the front
  // Scale-free parallel test (see header): also rejects zero-area triangles and coplanar rays.
  const double threshold = kParallelEpsilon * norm(dir) * norm(e1) * norm(e2);
  if (!(std::abs(det) > threshold)) return std::nullopt;
  if (culling == Culling::BackFaces && det < 0) return std::nullopt;

  const double invDet = 1.0 / det;
  const Vec3 s = origin - a;
  // Written so that a NaN (a non-finite ray) fails each test rather than passing it.
  const double u = dot(s, p) * invDet;
  if (!(u >= -kBarycentricEpsilon && u <= 1 + kBarycentricEpsilon)) return std::nullopt;
  const Vec3 q = cross(s, e1);
  const double v = dot(dir, q) * invDet;
  if (!(v >= -kBarycentricEpsilon && u + v <= 1 + kBarycentricEpsilon)) return std::nullopt;
  const double t = dot(e2, q) * invDet;
  if (!(t >= -kRayStartEpsilon)) return std::nullopt;
  return RayHit{std::max(t, 0.0), u, v, det > 0};
}

}  // namespace reamsim
