// The volume a convex cutting solid sweeps along a translation (SweptVolume.h): built from the solid's own faces
// and its swept silhouette (sweptBySilhouette, plain doubles, checked), else as the convex hull of its two
// placements (hullOfPlacements). The hull needs only predicates, so the inexact-constructions kernel is exact
// there: its output points are input points.
#include "ExactRationalFastPaths.h"  // before any CGAL kernel: see there
#include <CGAL/Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Projection_traits_3.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>
#include <CGAL/convex_hull_3.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>
#include <optional>
#include <string>
#include <stdexcept>
#include <vector>

#include "FacesAcross.h"
#include "reamsim/csg/SweptVolume.h"

namespace reamsim {
namespace {
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using SM = CGAL::Surface_mesh<K::Point_3>;
// 2D Delaunay in a hull face's own plane: predicates on the 3D points projected along a fixed normal (exact
// for that normal; any normal gives a valid triangulation of the face).
using InPlane = CGAL::Projection_traits_3<K>;
using Vb2 = CGAL::Triangulation_vertex_base_with_info_2<std::uint32_t, InPlane>;
using DT2 = CGAL::Delaunay_triangulation_2<InPlane, CGAL::Triangulation_data_structure_2<Vb2>>;

constexpr std::uint32_t kNoIndex = ~std::uint32_t(0);

std::uint32_t findRoot(std::vector<std::uint32_t>& parent, std::uint32_t i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}

// The hull of `points`, the same whatever convex_hull_3's split of its planar faces, as indices into
// `points`. Its facets are unique where no four hull points are coplanar; a planar face of several facets
// (the floor of a flat reamer's sweep, its discs, the parallelograms between the two rims) it splits in an
// order that follows memory addresses (a std::map keyed by handles), which differ from run to run, and the
// Boolean breaks ties by the tool's order (docs/CSG.md, "Reproducibility"). So each planar face is
// triangulated again: its corners only (points inside it or on its edges dropped), by their Delaunay
// triangulation in its plane (unique: ties of cocircular corners are broken by CGAL's symbolic
// perturbation, whatever the order of insertion).
std::vector<Triangle> canonicalHull(const std::vector<K::Point_3>& points) {
  SM hull;
  CGAL::convex_hull_3(points.begin(), points.end(), hull);
  using F = SM::Face_index;
  using H = SM::Halfedge_index;
  // Coplanar neighbours joined into faces (exact orientation of the vertex across their edge).
  std::vector<std::uint32_t> parent(hull.number_of_faces());
  std::iota(parent.begin(), parent.end(), 0u);
  for (F f : hull.faces())
    for (H h : CGAL::halfedges_around_face(hull.halfedge(f), hull)) {
      const H o = hull.opposite(h);
      const F g = hull.face(o);
      if (g < f) continue;  // each edge once
      const H hf = hull.halfedge(f);
      if (CGAL::orientation(hull.point(hull.source(hf)), hull.point(hull.target(hf)),
                            hull.point(hull.target(hull.next(hf))), hull.point(hull.target(hull.next(o)))) == CGAL::COPLANAR)
        parent[findRoot(parent, f.idx())] = findRoot(parent, g.idx());
    }
  // A corner has at least three faces around it (one inside a face, two on an edge between faces).
  std::vector<char> corner(hull.number_of_vertices(), 0);
  for (SM::Vertex_index v : hull.vertices()) {
    std::uint32_t seen[3];
    int n = 0;
    for (F f : CGAL::faces_around_target(hull.halfedge(v), hull)) {
      const std::uint32_t r = findRoot(parent, f.idx());
      if (std::find(seen, seen + n, r) != seen + n) continue;
      seen[n++] = r;
      if (n == 3) break;
    }
    corner[v.idx()] = n == 3;
  }
  // The input index of each corner: the first input point at its position (input sorted by position).
  std::vector<std::uint32_t> byPosition(points.size());
  std::iota(byPosition.begin(), byPosition.end(), 0u);
  std::stable_sort(byPosition.begin(), byPosition.end(), [&](std::uint32_t i, std::uint32_t j) { return points[i] < points[j]; });
  std::vector<std::uint32_t> input(hull.number_of_vertices(), 0);
  for (SM::Vertex_index v : hull.vertices())
    if (corner[v.idx()])
      input[v.idx()] = *std::lower_bound(byPosition.begin(), byPosition.end(), hull.point(v),
                                         [&](std::uint32_t i, const K::Point_3& p) { return points[i] < p; });

  // Facets grouped by face (sorted by root: a fixed order), without a container per face.
  std::vector<std::pair<std::uint32_t, F>> byFace;
  byFace.reserve(hull.number_of_faces());
  for (F f : hull.faces()) byFace.emplace_back(findRoot(parent, f.idx()), f);
  std::sort(byFace.begin(), byFace.end());
  std::vector<Triangle> out;
  out.reserve(hull.number_of_faces());
  std::vector<F> fs;
  std::vector<SM::Vertex_index> vs;
  for (std::size_t i = 0; i < byFace.size();) {
    fs.clear();
    vs.clear();
    for (const std::uint32_t root = byFace[i].first; i < byFace.size() && byFace[i].first == root; ++i)
      fs.push_back(byFace[i].second);
    for (F f : fs)
      for (SM::Vertex_index v : CGAL::vertices_around_face(hull.halfedge(f), hull))
        if (corner[v.idx()]) vs.push_back(v);
    if (fs.size() == 1 && vs.size() == 3) {  // a facet of three corners: the hull's own
      out.push_back({input[vs[0].idx()], input[vs[1].idx()], input[vs[2].idx()]});
      continue;
    }
    std::sort(vs.begin(), vs.end(), [&](SM::Vertex_index a, SM::Vertex_index b) { return input[a.idx()] < input[b.idx()]; });
    vs.erase(std::unique(vs.begin(), vs.end()), vs.end());
    // The face's normal from one of its facets (outwards): triangles counter-clockwise about it face out.
    const H h = hull.halfedge(fs[0]);
    const InPlane plane(CGAL::cross_product(hull.point(hull.target(h)) - hull.point(hull.source(h)),
                                            hull.point(hull.target(hull.next(h))) - hull.point(hull.source(h))));
    if (fs.size() == 2 && vs.size() == 4) {  // a quad (the strips between the two rims): its Delaunay diagonal
      // The quad (p, q, r, t) with the facets' shared edge r-p: facet (p, q, r) and the vertex t across.
      H e = h;
      while (hull.face(hull.opposite(e)) != fs[1]) e = hull.next(e);
      const SM::Vertex_index p = hull.target(e), q = hull.target(hull.next(e)), r = hull.source(e),
                             t = hull.target(hull.next(hull.opposite(e)));
      const CGAL::Oriented_side side =
          plane.side_of_oriented_circle_2_object()(hull.point(p), hull.point(q), hull.point(r), hull.point(t));
      // Cocircular (a rectangle): the diagonal at the corner listed first in the input.
      const std::uint32_t first = std::min({input[p.idx()], input[q.idx()], input[r.idx()], input[t.idx()]});
      const bool flip = side == CGAL::ON_POSITIVE_SIDE ||
                        (side == CGAL::ON_ORIENTED_BOUNDARY && first != input[p.idx()] && first != input[r.idx()]);
      if (flip) {
        out.push_back({input[q.idx()], input[r.idx()], input[t.idx()]});
        out.push_back({input[t.idx()], input[p.idx()], input[q.idx()]});
      } else {
        out.push_back({input[p.idx()], input[q.idx()], input[r.idx()]});
        out.push_back({input[r.idx()], input[t.idx()], input[p.idx()]});
      }
      continue;
    }
    DT2 dt{plane};
    for (SM::Vertex_index v : vs) dt.insert(hull.point(v))->info() = input[v.idx()];
    for (auto f = dt.finite_faces_begin(); f != dt.finite_faces_end(); ++f)
      out.push_back({f->vertex(0)->info(), f->vertex(1)->info(), f->vertex(2)->info()});
  }
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

namespace {
void requireSameRotation(const RigidTransform& from, const RigidTransform& to, const char* what) {
  for (int i = 0; i < 9; ++i)
    if (from.rotation[i] != to.rotation[i])
      throw std::invalid_argument(std::string(what) + ": the two poses have different orientations");
}

// The solid's vertices placed at `from`, then at `to`.
std::vector<Vec3> placements(const TriangleMesh& solid, const RigidTransform& from, const RigidTransform& to) {
  std::vector<Vec3> points;
  points.reserve(2 * solid.vertices.size());
  for (const RigidTransform* t : {&from, &to})
    for (const Vec3& p : solid.vertices) points.push_back(t->apply(p));
  return points;
}

// Listed canonically: the vertices the triangles use, in the input's order; each triangle from its smallest
// vertex; triangles sorted.
TriangleMesh canonicalMesh(const std::vector<Vec3>& points, std::vector<Triangle> facets) {
  std::vector<std::uint32_t> outIndex(points.size(), kNoIndex);
  for (const Triangle& t : facets)
    for (std::uint32_t v : t) outIndex[v] = 0;
  TriangleMesh out;
  for (std::uint32_t i = 0; i < points.size(); ++i)
    if (outIndex[i] != kNoIndex) {
      outIndex[i] = static_cast<std::uint32_t>(out.vertices.size());
      out.vertices.push_back(points[i]);
    }
  for (Triangle& t : facets) {
    for (auto& v : t) v = outIndex[v];
    std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
  }
  std::sort(facets.begin(), facets.end());
  out.triangles = std::move(facets);
  return out;
}

// The face across each edge of each face (csg::facesAcross), or nothing unless every index is a vertex and
// every directed edge has exactly one twin (a closed, consistently oriented manifold).
std::optional<std::vector<std::array<std::uint32_t, 3>>> closedAcross(const std::vector<Triangle>& faces,
                                                                      std::size_t vertexCount) {
  for (const Triangle& t : faces)
    for (std::uint32_t v : t)
      if (v >= vertexCount) return std::nullopt;
  csg::FacesAcross adjacency = csg::facesAcross(faces, vertexCount);
  if (adjacency.repeatedDirectedEdge) return std::nullopt;
  for (const auto& across : adjacency.face)
    for (std::uint32_t g : across)
      if (g == csg::kNoFaceAcross) return std::nullopt;
  return std::move(adjacency.face);
}

// Smallest sine of a triangle's angles for the silhouette sweep: a needle's plane is not known in doubles.
// A 1 µm move along 1 mm edges makes ~1e-3.
constexpr double kMinimumSine = 1e-6;
// How far, relative to the coordinates' size (times the face's conditioning, below), a vertex may lie in
// front of the plane of a face across an edge from it: rounding (the placed solid is convex only to the
// rounding of its placed vertices).
constexpr double kConvexityTolerance = 1e-12;

// |cos| of the angle between a face's normal and the move below which the face counts as parallel to it.
constexpr double kParallelTolerance = 1e-12;

bool wellShaped(const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 e[3] = {b - a, c - b, a - c};
  const double area2 = norm(cross(e[0], e[1]));
  for (int i = 0; i < 3; ++i)  // the sine of the angle opposite edge i+2: |e_i x e_{i+1}| / (|e_i| |e_{i+1}|)
    if (!(area2 > kMinimumSine * norm(e[i]) * norm(e[(i + 1) % 3]))) return false;
  return true;
}
}  // namespace

std::optional<TriangleMesh> sweptBySilhouette(const TriangleMesh& solid, const RigidTransform& from,
                                              const RigidTransform& to) {
  requireSameRotation(from, to, "sweptBySilhouette");
  const auto n = static_cast<std::uint32_t>(solid.vertices.size());
  const auto solidAcross = closedAcross(solid.triangles, n);
  if (!solidAcross) return std::nullopt;  // not a closed, oriented manifold
  const std::vector<Vec3> points = placements(solid, from, to);
  // The move in the solid's frame (the rotation is row-major: its transpose applied to the change).
  const Vec3 m = to.translation - from.translation;
  const auto& r = from.rotation;
  const Vec3 move{r[0] * m.x + r[3] * m.y + r[6] * m.z, r[1] * m.x + r[4] * m.y + r[7] * m.z,
                  r[2] * m.x + r[5] * m.y + r[8] * m.z};
  std::vector<char> front(solid.triangles.size());
  for (std::size_t f = 0; f < solid.triangles.size(); ++f) {
    const Triangle& t = solid.triangles[f];
    const Vec3 a = solid.vertices[t[0]];
    // A face parallel to the move stays at the start; "parallel" up to rounding, so that coplanar faces
    // (the two halves of a planar quad) go the same way: one of them moved would fold the strip between.
    const Vec3 normal = cross(solid.vertices[t[1]] - a, solid.vertices[t[2]] - a);
    front[f] = dot(normal, move) > kParallelTolerance * norm(normal) * norm(move);
  }
  std::vector<Triangle> faces;
  faces.reserve(solid.triangles.size() + 256);
  for (std::size_t f = 0; f < solid.triangles.size(); ++f) {
    const Triangle& t = solid.triangles[f];
    if (!front[f]) {
      faces.push_back(t);
      continue;
    }
    faces.push_back({t[0] + n, t[1] + n, t[2] + n});
    for (int i = 0; i < 3; ++i) {
      const std::uint32_t a = t[i], b = t[(i + 1) % 3];
      if (front[(*solidAcross)[f][std::size_t(i)]]) continue;
      // Silhouette edge: the quad (start a, start b, end b, end a), whose sides are the twins of the back
      // face's b->a at the start and of this face's a->b at the end; split on its shorter diagonal.
      const std::uint32_t sa = a, sb = b, eb = b + n, ea = a + n;
      if (squaredNorm(points[eb] - points[sa]) <= squaredNorm(points[ea] - points[sb])) {
        faces.push_back({sa, sb, eb});
        faces.push_back({sa, eb, ea});
      } else {
        faces.push_back({sa, sb, ea});
        faces.push_back({sb, eb, ea});
      }
    }
  }
  // The checks on the placed points: every edge with its twin, Euler characteristic 2 (one closed piece of
  // genus 0), no needle, and no edge reflex beyond rounding.
  const auto across = closedAcross(faces, points.size());
  if (!across) return std::nullopt;
  std::vector<char> used(points.size(), 0);
  double scale = 1;
  for (const Triangle& t : faces) {
    if (!wellShaped(points[t[0]], points[t[1]], points[t[2]])) return std::nullopt;
    for (std::uint32_t v : t) {
      used[v] = 1;
      scale = std::max({scale, std::abs(points[v].x), std::abs(points[v].y), std::abs(points[v].z)});
    }
  }
  const auto vertices = std::count(used.begin(), used.end(), char(1));
  const auto edges = std::int64_t(3 * faces.size() / 2);
  if (vertices - edges + std::int64_t(faces.size()) != 2) return std::nullopt;
  for (std::size_t f = 0; f < faces.size(); ++f)
    for (int i = 0; i < 3; ++i) {
      const std::size_t g = (*across)[f][std::size_t(i)];
      if (g < f) continue;  // each edge's dihedral once
      const Triangle& t = faces[f];
      const Triangle& u = faces[g];
      std::uint32_t opposite = u[0];
      for (std::uint32_t v : u)
        if (v != t[i] && v != t[(i + 1) % 3]) opposite = v;
      const Vec3 normal = cross(points[t[1]] - points[t[0]], points[t[2]] - points[t[0]]);
      const Vec3 other = cross(points[u[1]] - points[u[0]], points[u[2]] - points[u[0]]);
      // The plane of a thin triangle is known less well: its normal's error grows as its squared size over
      // its area.
      const Vec3 reach = points[opposite] - points[t[0]];
      const double size2 = std::max({squaredNorm(points[t[1]] - points[t[0]]),
                                     squaredNorm(points[t[2]] - points[t[0]]), squaredNorm(reach)});
      if (dot(normal, reach) > kConvexityTolerance * scale * (norm(normal) + size2)) return std::nullopt;
      if (!(dot(normal, other) > -0.5 * norm(normal) * norm(other))) return std::nullopt;  // folded back
    }
  return canonicalMesh(points, std::move(faces));
}

TriangleMesh hullOfPlacements(const TriangleMesh& solid, const RigidTransform& from, const RigidTransform& to) {
  requireSameRotation(from, to, "hullOfPlacements");
  const std::vector<Vec3> placed = placements(solid, from, to);
  std::vector<K::Point_3> points;
  points.reserve(placed.size());
  for (const Vec3& q : placed) points.emplace_back(q.x, q.y, q.z);
  return canonicalMesh(placed, canonicalHull(points));
}

TriangleMesh sweptByTranslation(const TriangleMesh& solid, const RigidTransform& from, const RigidTransform& to) {
  requireSameRotation(from, to, "sweptByTranslation");
  if (std::optional<TriangleMesh> swept = sweptBySilhouette(solid, from, to)) return std::move(*swept);
  return hullOfPlacements(solid, from, to);
}

}  // namespace reamsim
