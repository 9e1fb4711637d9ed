#pragma once
// Whether two triangles of one mesh intersect other than along the vertices and edge they share (by
// index). Exact with an exact-predicates kernel whose points have double coordinates (Epick). Included by
// the CGAL units only.
#include <CGAL/intersections.h>

#include <array>
#include <cstdint>

#include "PlaneSide.h"

namespace reamsim::csg {

// kPlaneFilter = false skips the filter below (its test compares the two).
template <class K, bool kPlaneFilter = true, class PointOf>
bool trianglesIntersectBeyondShared(const std::array<std::uint32_t, 3>& s, const std::array<std::uint32_t, 3>& t,
                                    PointOf&& pt) {
  using Triangle3 = typename K::Triangle_3;
  using Segment3 = typename K::Segment_3;
  int shared = 0;
  std::uint32_t only = 0;
  for (std::uint32_t u : s)
    for (std::uint32_t v : t)
      if (u == v) {
        ++shared;
        only = u;
      }
  if (shared == 3) return false;  // the same face
  // Most pairs the callers test are apart by far more than rounding: one triangle's corners (other than a
  // shared one) strictly on one side of the other's plane, proven in doubles (PlaneSide.h), meet it nowhere
  // else. Only the pairs this does not settle build CGAL triangles.
  auto v = [&](std::uint32_t i) {
    const auto& p = pt(i);
    return Vec3{p.x(), p.y(), p.z()};
  };
  if (kPlaneFilter && shared != 2) {
    const Vec3 sv[3] = {v(s[0]), v(s[1]), v(s[2])}, tv[3] = {v(t[0]), v(t[1]), v(t[2])};
    // b's corners (but the shared one) strictly on one side of a's plane.
    auto apart = [&](const Vec3 (&a)[3], const Vec3 (&b)[3], const std::array<std::uint32_t, 3>& bi) {
      const PlaneSide plane(a[0], a[1], a[2]);
      if (shared == 0) return plane.separates(b[0], b[1], b[2]);
      int k = 0;
      Vec3 other[2];
      for (int i = 0; i < 3; ++i)
        if (bi[i] != only) other[k++] = b[i];
      return plane.separates(other[0], other[1]);
    };
    if (apart(sv, tv, t) || apart(tv, sv, s)) return false;
  }
  const Triangle3 ts(pt(s[0]), pt(s[1]), pt(s[2])), tt(pt(t[0]), pt(t[1]), pt(t[2]));
  if (shared == 0) return CGAL::do_intersect(ts, tt);
  if (shared == 2) {
    // Along the shared edge only, unless the faces are coplanar and fold onto the same side of it.
    std::uint32_t ps = 0, pk = 0;
    std::array<std::uint32_t, 2> e{};
    int n = 0;
    for (std::uint32_t u : s)
      if (u != t[0] && u != t[1] && u != t[2]) ps = u; else e[n++] = u;
    for (std::uint32_t v : t)
      if (v != s[0] && v != s[1] && v != s[2]) pk = v;
    return CGAL::coplanar(pt(e[0]), pt(e[1]), pt(ps), pt(pk)) &&
           CGAL::coplanar_orientation(pt(e[0]), pt(e[1]), pt(ps), pt(pk)) == CGAL::POSITIVE;
  }
  // One shared vertex: the opposite edge of either must miss the other triangle.
  auto opposite = [&](const std::array<std::uint32_t, 3>& f) {
    std::array<std::uint32_t, 2> e{};
    int n = 0;
    for (std::uint32_t u : f)
      if (u != only) e[n++] = u;
    return Segment3(pt(e[0]), pt(e[1]));
  };
  return CGAL::do_intersect(opposite(s), tt) || CGAL::do_intersect(opposite(t), ts);
}

}  // namespace reamsim::csg
