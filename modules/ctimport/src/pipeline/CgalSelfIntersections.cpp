// CGAL translation unit (Epick: exact predicates, which is all an intersection test needs).
// Grid broad phase + exact narrow phase; see SelfIntersections.h for the rules.
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/intersections.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <initializer_list>

#include "TriangleIntersection.h"
#include "reamsim/ctimport/SelfIntersections.h"

namespace reamsim::ct {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = K::Point_3;

struct Box {
  float lo[3], hi[3];  // rounded outward from the double coordinates
};

bool boxesOverlap(const Box& a, const Box& b) {
  for (int d = 0; d < 3; ++d)
    if (a.lo[d] > b.hi[d] || b.lo[d] > a.hi[d]) return false;
  return true;
}

// Sign of orient3d(a, b, c, d) when double arithmetic is sure of it, else 0. The error bound is ~100 times
// Shewchuk's orient3d bound A, so a non-zero answer is the exact sign; 0 sends the pair to CGAL.
int orientSign(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
  const double bx = b.x - a.x, by = b.y - a.y, bz = b.z - a.z;
  const double cx = c.x - a.x, cy = c.y - a.y, cz = c.z - a.z;
  const double dx = d.x - a.x, dy = d.y - a.y, dz = d.z - a.z;
  const double m1 = by * cz - bz * cy, m2 = bz * cx - bx * cz, m3 = bx * cy - by * cx;
  const double det = m1 * dx + m2 * dy + m3 * dz;
  const double permanent = (std::abs(by * cz) + std::abs(bz * cy)) * std::abs(dx) +
                           (std::abs(bz * cx) + std::abs(bx * cz)) * std::abs(dy) +
                           (std::abs(bx * cy) + std::abs(by * cx)) * std::abs(dz);
  const double bound = 1e-13 * permanent;
  return det > bound ? 1 : (det < -bound ? -1 : 0);
}

// True if the points q[0..n) are certainly all strictly on one side of the plane (a, b, c).
bool strictlyOneSide(const Vec3& a, const Vec3& b, const Vec3& c, std::initializer_list<const Vec3*> q) {
  int first = 0;
  for (const Vec3* p : q) {
    const int s = orientSign(a, b, c, *p);
    if (s == 0) return false;
    if (first == 0) first = s;
    else if (s != first) return false;
  }
  return true;
}

// True if the line through (s0, s1) certainly misses the triangle (t0, t1, t2): the three signed volumes
// it forms with the triangle's edges have certain, mixed signs.
bool lineCertainlyMisses(const Vec3& s0, const Vec3& s1, const Vec3& t0, const Vec3& t1, const Vec3& t2) {
  const int o1 = orientSign(s0, s1, t0, t1), o2 = orientSign(s0, s1, t1, t2), o3 = orientSign(s0, s1, t2, t0);
  return (o1 > 0 || o2 > 0 || o3 > 0) && (o1 < 0 || o2 < 0 || o3 < 0);
}

Point point(const Vec3& v) { return Point(v.x, v.y, v.z); }

}  // namespace

namespace detail {

bool triangleIsDegenerate(const Corners& p) { return CGAL::collinear(point(p[0]), point(p[1]), point(p[2])); }

// The same decision as CGAL PMP's do_faces_intersect: floating-point filters settle the common cases
// (neighbours meeting at an angle, separated faces), CGAL's exact predicates the rest.
bool trianglesIntersect(const Triangle& a, const Corners& pa, const Triangle& b, const Corners& pb) {
  int shared = 0, ai = -1, bj = -1;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (a[i] == b[j]) {
        ++shared;
        ai = i;
        bj = j;
      }
  if (shared >= 3) return true;  // the same face twice
  if (shared == 2) {
    // The corner of each face that is not shared, and the shared edge (s0, s1) as seen from a.
    int oa = 0, ob = 0;
    for (int i = 0; i < 3; ++i)
      if (a[i] != b[0] && a[i] != b[1] && a[i] != b[2]) oa = i;
    for (int j = 0; j < 3; ++j)
      if (b[j] != a[0] && b[j] != a[1] && b[j] != a[2]) ob = j;
    const Vec3 &s0 = pa[(oa + 1) % 3], &s1 = pa[(oa + 2) % 3];
    if (orientSign(s0, s1, pa[oa], pb[ob]) != 0) return false;  // not coplanar
    return CGAL::coplanar(point(s0), point(s1), point(pa[oa]), point(pb[ob])) &&
           CGAL::coplanar_orientation(point(s0), point(s1), point(pa[oa]), point(pb[ob])) == CGAL::POSITIVE;
  }
  if (shared == 1) {
    const Vec3& p1 = pa[(ai + 1) % 3];
    const Vec3& q1 = pa[(ai + 2) % 3];
    const Vec3& p2 = pb[(bj + 1) % 3];
    const Vec3& q2 = pb[(bj + 2) % 3];
    // The opposite edge of each face away from the other face: only the vertex is shared.
    const bool bClear = strictlyOneSide(pa[0], pa[1], pa[2], {&p2, &q2}) || lineCertainlyMisses(p2, q2, pa[0], pa[1], pa[2]);
    const bool aClear = strictlyOneSide(pb[0], pb[1], pb[2], {&p1, &q1}) || lineCertainlyMisses(p1, q1, pb[0], pb[1], pb[2]);
    if (bClear && aClear) return false;
    const K::Triangle_3 ta(point(pa[0]), point(pa[1]), point(pa[2]));
    const K::Triangle_3 tb(point(pb[0]), point(pb[1]), point(pb[2]));
    return (!bClear && CGAL::do_intersect(ta, K::Segment_3(point(p2), point(q2)))) ||
           (!aClear && CGAL::do_intersect(tb, K::Segment_3(point(p1), point(q1))));
  }
  if (strictlyOneSide(pa[0], pa[1], pa[2], {&pb[0], &pb[1], &pb[2]}) ||
      strictlyOneSide(pb[0], pb[1], pb[2], {&pa[0], &pa[1], &pa[2]}))
    return false;
  return CGAL::do_intersect(K::Triangle_3(point(pa[0]), point(pa[1]), point(pa[2])),
                            K::Triangle_3(point(pb[0]), point(pb[1]), point(pb[2])));
}

}  // namespace detail

namespace {

detail::Corners corners(const TriangleMesh& m, const Triangle& t) {
  return {m.vertices[t[0]], m.vertices[t[1]], m.vertices[t[2]]};
}

}  // namespace

SelfIntersectionResult findSelfIntersections(const TriangleMesh& mesh, std::size_t maxPairs,
                                             const std::vector<std::uint8_t>* onlyFaces) {
  SelfIntersectionResult result;
  const std::size_t n = mesh.triangles.size();
  const bool restricted = onlyFaces && onlyFaces->size() == n;

  std::vector<Box> boxes(n);
  std::vector<std::uint8_t> usable(n, 0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t f = r.begin(); f != r.end(); ++f) {
      const Triangle& t = mesh.triangles[f];
      if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2] || detail::triangleIsDegenerate(corners(mesh, t))) continue;
      Box& b = boxes[f];
      for (int d = 0; d < 3; ++d) {
        const double x0 = mesh.vertices[t[0]][d], x1 = mesh.vertices[t[1]][d], x2 = mesh.vertices[t[2]][d];
        b.lo[d] = std::nextafter(float(std::min({x0, x1, x2})), -HUGE_VALF);
        b.hi[d] = std::nextafter(float(std::max({x0, x1, x2})), HUGE_VALF);
      }
      usable[f] = 1;
    }
  });
  for (std::size_t f = 0; f < n; ++f)
    if (!usable[f]) result.degenerateFaces.push_back(std::uint32_t(f));

  // Grid: cells about 1.5 times the mean triangle extent, so each face covers a few cells.
  double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  double extentSum = 0;
  std::size_t usableCount = 0;
  for (std::size_t f = 0; f < n; ++f) {
    if (!usable[f]) continue;
    ++usableCount;
    double e = 0;
    for (int d = 0; d < 3; ++d) {
      lo[d] = std::min(lo[d], double(boxes[f].lo[d]));
      hi[d] = std::max(hi[d], double(boxes[f].hi[d]));
      e = std::max(e, double(boxes[f].hi[d]) - double(boxes[f].lo[d]));
    }
    extentSum += e;
  }
  if (usableCount < 2) return result;
  double h = std::max(1.5 * extentSum / double(usableCount), 1e-12);
  std::size_t g[3];
  const std::size_t maxCells = 8 * usableCount + 1024;
  for (;;) {
    for (int d = 0; d < 3; ++d) g[d] = std::size_t((hi[d] - lo[d]) / h) + 1;
    if (g[0] * g[1] * g[2] <= maxCells) break;
    h *= 1.5;
  }
  const auto cellOf = [&](double x, int d) {
    return std::min<std::size_t>(g[d] - 1, std::size_t(std::max(0.0, (x - lo[d]) / h)));
  };

  // Counting sort of (cell, face) entries.
  const std::size_t cells = g[0] * g[1] * g[2];
  std::vector<std::uint32_t> start(cells + 1, 0);
  // Low cell of each face: a pair belongs to the cell at the per-axis maximum of its two low cells.
  std::vector<std::array<std::uint32_t, 3>> lowCell(n);
  const auto forEachCell = [&](std::size_t f, auto&& fn) {
    const Box& b = boxes[f];
    const std::size_t x0 = cellOf(b.lo[0], 0), x1 = cellOf(b.hi[0], 0), y0 = cellOf(b.lo[1], 1),
                      y1 = cellOf(b.hi[1], 1), z0 = cellOf(b.lo[2], 2), z1 = cellOf(b.hi[2], 2);
    lowCell[f] = {std::uint32_t(x0), std::uint32_t(y0), std::uint32_t(z0)};
    for (std::size_t z = z0; z <= z1; ++z)
      for (std::size_t y = y0; y <= y1; ++y)
        for (std::size_t x = x0; x <= x1; ++x) fn((z * g[1] + y) * g[0] + x);
  };
  for (std::size_t f = 0; f < n; ++f)
    if (usable[f]) forEachCell(f, [&](std::size_t c) { ++start[c + 1]; });
  for (std::size_t c = 0; c < cells; ++c) start[c + 1] += start[c];
  std::vector<std::uint32_t> entries(start[cells]);
  {
    std::vector<std::uint32_t> fill(start.begin(), start.end() - 1);
    for (std::size_t f = 0; f < n; ++f)
      if (usable[f]) forEachCell(f, [&](std::size_t c) { entries[fill[c]++] = std::uint32_t(f); });
  }

  // Each pair is examined in the one cell holding the low corner of the overlap of the two boxes.
  std::atomic<std::size_t> found{0};
  const std::size_t limit = std::max<std::size_t>(maxPairs, 1);
  tbb::enumerable_thread_specific<std::vector<std::pair<std::uint32_t, std::uint32_t>>> local;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, cells, 256), [&](const tbb::blocked_range<std::size_t>& r) {
    auto& out = local.local();
    for (std::size_t c = r.begin(); c != r.end(); ++c) {
      const std::uint32_t b = start[c], e = start[c + 1];
      if (e - b < 2) continue;
      if (restricted) {
        bool any = false;
        for (std::uint32_t k = b; k < e && !any; ++k) any = (*onlyFaces)[entries[k]] != 0;
        if (!any) continue;
      }
      if (found.load(std::memory_order_relaxed) > limit) return;
      const std::uint32_t cx = std::uint32_t(c % g[0]), cy = std::uint32_t((c / g[0]) % g[1]),
                          cz = std::uint32_t(c / (g[0] * g[1]));
      for (std::uint32_t k1 = b; k1 < e; ++k1) {
        const std::uint32_t f1 = entries[k1];
        const Box& b1 = boxes[f1];
        for (std::uint32_t k2 = k1 + 1; k2 < e; ++k2) {
          const std::uint32_t f2 = entries[k2];
          if (restricted && !(*onlyFaces)[f1] && !(*onlyFaces)[f2]) continue;
          const Box& b2 = boxes[f2];
          if (!boxesOverlap(b1, b2)) continue;
          const auto &l1 = lowCell[f1], &l2 = lowCell[f2];
          if (std::max(l1[0], l2[0]) != cx || std::max(l1[1], l2[1]) != cy || std::max(l1[2], l2[2]) != cz) continue;
          const Triangle &t1 = mesh.triangles[f1], &t2 = mesh.triangles[f2];
          if (detail::trianglesIntersect(t1, corners(mesh, t1), t2, corners(mesh, t2))) {
            out.emplace_back(std::min(f1, f2), std::max(f1, f2));
            ++found;
          }
        }
      }
    }
  });
  for (auto& v : local) result.pairs.insert(result.pairs.end(), v.begin(), v.end());
  std::sort(result.pairs.begin(), result.pairs.end());
  if (result.pairs.size() > maxPairs) {
    result.pairs.resize(maxPairs);
    result.truncated = true;
  } else if (found > limit) {
    result.truncated = true;
  }
  return result;
}

}  // namespace reamsim::ct
