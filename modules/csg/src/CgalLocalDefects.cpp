// CGAL translation unit: the local engine's construction-time defect scan. Epick suffices: only
// predicates are evaluated, and Epick's predicates are exact.
#include "ExactRationalFastPaths.h"  // before any CGAL kernel: see there
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/box_intersection_d.h>

#include <unordered_map>

#include "LocalDefectScan.h"
#include "TrianglePair.h"

namespace reamsim::csg {
namespace {
using K = CGAL::Exact_predicates_inexact_constructions_kernel;

std::uint64_t edgeKey(std::uint32_t a, std::uint32_t b) { return (std::uint64_t(a) << 32) | b; }

}  // namespace

DefectScan scanDefects(const TriangleMesh& mesh) {
  DefectScan scan;
  const std::size_t n = mesh.triangles.size();
  scan.flags.assign(n, 0);
  std::vector<K::Point_3> points;
  points.reserve(mesh.vertices.size());
  for (const Vec3& p : mesh.vertices) points.emplace_back(p.x, p.y, p.z);

  // Directed-edge use: an undirected edge used by 3+ faces, or twice in one direction, is non-manifold.
  std::unordered_map<std::uint64_t, std::uint32_t> directed;
  directed.reserve(3 * n);
  for (const Triangle& t : mesh.triangles)
    for (int i = 0; i < 3; ++i) ++directed[edgeKey(t[i], t[(i + 1) % 3])];
  for (std::size_t f = 0; f < n; ++f) {
    const Triangle& t = mesh.triangles[f];
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2] || CGAL::collinear(points[t[0]], points[t[1]], points[t[2]])) {
      scan.flags[f] |= kDegenerate;
      continue;
    }
    for (int i = 0; i < 3; ++i) {
      const std::uint32_t a = t[i], b = t[(i + 1) % 3];
      const auto same = directed.find(edgeKey(a, b))->second;
      const auto it = directed.find(edgeKey(b, a));
      const std::uint32_t opposite = it == directed.end() ? 0 : it->second;
      if (same > 1 || same + opposite > 2) scan.flags[f] |= kNonManifold;
      if (opposite == 0) ++scan.borderEdges;
    }
  }

  // Self-intersections by index-aware pair tests on the original connectivity: splitting the soup for a
  // halfedge structure would turn faces meeting at a non-manifold vertex into false "intersections".
  using Box = CGAL::Box_intersection_d::Box_with_handle_d<double, 3, std::size_t, CGAL::Box_intersection_d::ID_EXPLICIT>;
  std::vector<Box> boxes;
  boxes.reserve(n);
  for (std::size_t f = 0; f < n; ++f) {
    if (scan.flags[f] & kDegenerate) continue;
    const Triangle& t = mesh.triangles[f];
    boxes.emplace_back(points[t[0]].bbox() + points[t[1]].bbox() + points[t[2]].bbox(), f);
  }
  auto pt = [&](std::uint32_t v) -> const K::Point_3& { return points[v]; };
  CGAL::box_self_intersection_d(boxes.begin(), boxes.end(), [&](const Box& a, const Box& b) {
    const Triangle& s = mesh.triangles[a.handle()];
    const Triangle& t = mesh.triangles[b.handle()];
    if (trianglesIntersectBeyondShared<K>({s[0], s[1], s[2]}, {t[0], t[1], t[2]}, pt)) {
      scan.flags[a.handle()] |= kSelfIntersecting;
      scan.flags[b.handle()] |= kSelfIntersecting;
      ++scan.selfIntersectingPairs;
    }
  });
  return scan;
}

}  // namespace reamsim::csg
