// Convex hull of two placements of a convex cutting solid (SweptVolume.h). Only predicates are needed, so
// the inexact-constructions kernel is exact here: the output points are input points.
#include "ExactRationalFastPaths.h"  // before any CGAL kernel: see there
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/convex_hull_3.h>

#include <cmath>
#include <stdexcept>
#include <unordered_map>

#include "reamsim/csg/SweptVolume.h"

namespace reamsim {
namespace {
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using SM = CGAL::Surface_mesh<K::Point_3>;
}  // namespace

bool isConvexSolid(const TriangleMesh& m, double relativeTolerance) {
  if (m.triangles.empty()) return false;
  double scale = 0;
  for (const Vec3& p : m.vertices) scale = std::max({scale, std::abs(p.x), std::abs(p.y), std::abs(p.z)});
  const double tol = relativeTolerance * std::max(1.0, scale);
  for (const Triangle& t : m.triangles) {
    const Vec3 a = m.vertices[t[0]];
    const Vec3 n = cross(m.vertices[t[1]] - a, m.vertices[t[2]] - a);
    const double len = norm(n);
    if (!(len > 0)) continue;  // degenerate facet: no plane to test
    for (const Vec3& p : m.vertices)
      if (dot(n, p - a) / len > tol) return false;
  }
  return true;
}

TriangleMesh sweptByTranslation(const TriangleMesh& solid, const RigidTransform& from, const RigidTransform& to) {
  for (int i = 0; i < 9; ++i)
    if (from.rotation[i] != to.rotation[i])
      throw std::invalid_argument("sweptByTranslation: the two poses have different orientations");
  std::vector<K::Point_3> points;
  points.reserve(2 * solid.vertices.size());
  for (const RigidTransform* t : {&from, &to})
    for (const Vec3& p : solid.vertices) {
      const Vec3 q = t->apply(p);
      points.emplace_back(q.x, q.y, q.z);
    }
  SM hull;
  CGAL::convex_hull_3(points.begin(), points.end(), hull);
  TriangleMesh out;
  std::unordered_map<std::uint32_t, std::uint32_t> index;
  for (SM::Vertex_index v : hull.vertices()) {
    index[v.idx()] = static_cast<std::uint32_t>(out.vertices.size());
    const K::Point_3& p = hull.point(v);
    out.vertices.push_back({p.x(), p.y(), p.z()});
  }
  for (SM::Face_index f : hull.faces()) {
    Triangle t{};
    int k = 0;
    for (SM::Vertex_index v : CGAL::vertices_around_face(hull.halfedge(f), hull)) {
      if (k == 3) throw std::logic_error("sweptByTranslation: the hull has a non-triangular face");
      t[k++] = index.at(v.idx());
    }
    out.triangles.push_back(t);
  }
  return out;
}

}  // namespace reamsim
