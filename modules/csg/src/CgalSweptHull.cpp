// Convex hull of two placements of a convex cutting solid (SweptVolume.h). Only predicates are needed, so
// the inexact-constructions kernel is exact here: the output points are input points.
#include "ExactRationalFastPaths.h"  // before any CGAL kernel: see there
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/convex_hull_3.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <stdexcept>
#include <unordered_map>
#include <utility>
#include <vector>

#include "reamsim/csg/SweptVolume.h"

namespace reamsim {
namespace {
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using SM = CGAL::Surface_mesh<K::Point_3>;

// The hull's planar facets (a translated cylinder's sides are rectangles, its ends discs) are split into
// triangles however CGAL happened to process them: each coplanar group of faces (exact test) is a convex
// polygon of hull vertices, and it is written as a fan from its smallest vertex instead. Faces then start
// at their smallest vertex and are sorted.
std::vector<Triangle> canonicalHullFaces(const std::vector<Triangle>& faces, const std::vector<Vec3>& vertices) {
  auto point = [&](std::uint32_t v) { return K::Point_3(vertices[v].x, vertices[v].y, vertices[v].z); };
  std::unordered_map<std::uint64_t, std::uint32_t> faceOfEdge;  // directed edge → face
  auto key = [](std::uint32_t a, std::uint32_t b) { return (std::uint64_t(a) << 32) | b; };
  for (std::uint32_t f = 0; f < faces.size(); ++f)
    for (int i = 0; i < 3; ++i) faceOfEdge[key(faces[f][i], faces[f][(i + 1) % 3])] = f;
  std::vector<std::uint32_t> group(faces.size());
  for (std::uint32_t f = 0; f < faces.size(); ++f) group[f] = f;
  std::function<std::uint32_t(std::uint32_t)> find = [&](std::uint32_t f) {
    return group[f] == f ? f : group[f] = find(group[f]);
  };
  for (std::uint32_t f = 0; f < faces.size(); ++f)
    for (int i = 0; i < 3; ++i) {
      const auto it = faceOfEdge.find(key(faces[f][(i + 1) % 3], faces[f][i]));
      if (it == faceOfEdge.end() || it->second < f) continue;
      const Triangle& g = faces[it->second];
      std::uint32_t d = g[0];
      for (std::uint32_t v : g)
        if (v != faces[f][i] && v != faces[f][(i + 1) % 3]) d = v;
      if (CGAL::coplanar(point(faces[f][0]), point(faces[f][1]), point(faces[f][2]), point(d)))
        group[find(f)] = find(it->second);
    }
  // Each group's boundary (edges whose twin lies in another group) is one cycle: walk it from its smallest
  // vertex and fan.
  std::unordered_map<std::uint32_t, std::vector<std::uint32_t>> members;
  for (std::uint32_t f = 0; f < faces.size(); ++f) members[find(f)].push_back(f);
  std::vector<Triangle> out;
  out.reserve(faces.size());
  for (const auto& [root, fs] : members) {
    std::unordered_map<std::uint32_t, std::uint32_t> next;
    std::uint32_t start = std::numeric_limits<std::uint32_t>::max();
    for (std::uint32_t f : fs)
      for (int i = 0; i < 3; ++i) {
        const std::uint32_t a = faces[f][i], b = faces[f][(i + 1) % 3];
        const auto twin = faceOfEdge.find(key(b, a));
        if (twin != faceOfEdge.end() && find(twin->second) == root) continue;
        next[a] = b;
        start = std::min(start, a);
      }
    std::vector<std::uint32_t> polygon{start};
    for (std::uint32_t v = next.at(start); v != start && polygon.size() <= next.size(); v = next.at(v)) polygon.push_back(v);
    if (polygon.size() != next.size() || polygon.size() != fs.size() + 2)
      throw std::logic_error("sweptByTranslation: a planar facet of the hull is not a convex polygon");
    for (std::size_t i = 1; i + 1 < polygon.size(); ++i) out.push_back({polygon[0], polygon[i], polygon[i + 1]});
  }
  std::sort(out.begin(), out.end());
  return out;
}

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
  // CGAL's hull lists its vertices and faces in an order that follows memory addresses (it differs from run
  // to run when other threads allocate), and the cutting engine's tie-breaks follow the tool's order: the
  // hull is written in a canonical order instead, vertices by their first index in `points` (hull points
  // are input points) and faces from their smallest vertex, sorted. The same move always cuts the same.
  struct PointHash {
    std::size_t operator()(const K::Point_3& p) const {
      return std::hash<double>()(p.x()) * 31 + std::hash<double>()(p.y()) * 17 + std::hash<double>()(p.z());
    }
  };
  std::unordered_map<K::Point_3, std::uint32_t, PointHash> firstIndex;
  for (std::uint32_t i = 0; i < points.size(); ++i) firstIndex.emplace(points[i], i);
  std::vector<std::pair<std::uint32_t, std::uint32_t>> order;  // (input index, hull vertex)
  for (SM::Vertex_index v : hull.vertices()) order.emplace_back(firstIndex.at(hull.point(v)), v.idx());
  std::sort(order.begin(), order.end());
  TriangleMesh out;
  std::unordered_map<std::uint32_t, std::uint32_t> index;
  for (const auto& [input, v] : order) {
    index[v] = static_cast<std::uint32_t>(out.vertices.size());
    const K::Point_3& p = points[input];
    out.vertices.push_back({p.x(), p.y(), p.z()});
  }
  std::vector<Triangle> faces;
  for (SM::Face_index f : hull.faces()) {
    Triangle t{};
    int k = 0;
    for (SM::Vertex_index v : CGAL::vertices_around_face(hull.halfedge(f), hull)) {
      if (k == 3) throw std::logic_error("sweptByTranslation: the hull has a non-triangular face");
      t[k++] = index.at(v.idx());
    }
    faces.push_back(t);
  }
  out.triangles = canonicalHullFaces(faces, out.vertices);
  return out;
}

}  // namespace reamsim
