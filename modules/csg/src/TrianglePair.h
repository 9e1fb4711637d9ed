#pragma once
// Whether two triangles of one mesh intersect other than along the vertices and edge they share (by
// index). Exact with an exact-predicates kernel. Included by the CGAL units only.
#include <CGAL/intersections.h>

#include <array>
#include <cstdint>

namespace reamsim::csg {

template <class K, class PointOf>
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
