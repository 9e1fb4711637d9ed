#pragma once
// Generalized winding number of a triangle soup at a point (Jacobson et al. 2013): the sum of the
// signed solid angles of the triangles over 4π. ≈1 inside, ≈0 outside, and it degrades gracefully with
// holes, overlaps and flipped faces, which is why the remesher uses it to decide inside/outside.
#include <cmath>

#include "reamsim/mesh/TriangleMesh.h"

namespace reamsim {

inline double solidAngle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  // Van Oosterom & Strackee (1983).
  const Vec3 ra = a - p, rb = b - p, rc = c - p;
  const double la = norm(ra), lb = norm(rb), lc = norm(rc);
  const double numerator = dot(ra, cross(rb, rc));
  const double denominator = la * lb * lc + dot(ra, rb) * lc + dot(rb, rc) * la + dot(rc, ra) * lb;
  return 2.0 * std::atan2(numerator, denominator);
}

inline double windingNumber(const TriangleMesh& mesh, const Vec3& p) {
  double sum = 0;
  for (const Triangle& t : mesh.triangles)
    sum += solidAngle(p, mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]]);
  return sum / (4.0 * M_PI);
}

}  // namespace reamsim
