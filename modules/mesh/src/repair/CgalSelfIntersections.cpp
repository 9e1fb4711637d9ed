// CGAL translation unit: self-intersection count of an arbitrary triangle soup. Epick is right here:
// self_intersections uses predicates only, and Epick's predicates are exact.
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>

#include <iterator>

#include "reamsim/mesh/Validation.h"

namespace reamsim {
namespace {
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Mesh = CGAL::Surface_mesh<K::Point_3>;
namespace PMP = CGAL::Polygon_mesh_processing;

// Stops the traversal once enough pairs are known (the count is then a lower bound).
struct CountingOutput {
  std::size_t* count;
  std::size_t limit;
  CountingOutput& operator*() { return *this; }
  CountingOutput& operator++() { return *this; }
  CountingOutput operator++(int) { return *this; }
  template <class Pair>
  CountingOutput& operator=(const Pair&) {
    if (++*count >= limit) throw LimitReached{};
    return *this;
  }
  struct LimitReached {};
};
}  // namespace

std::size_t countSelfIntersections(const TriangleMesh& input, std::size_t maxPairs) {
  std::vector<K::Point_3> points;
  points.reserve(input.vertices.size());
  for (const Vec3& p : input.vertices) points.emplace_back(p.x, p.y, p.z);
  std::vector<std::vector<std::size_t>> faces;
  faces.reserve(input.triangles.size());
  for (const Triangle& t : input.triangles) {
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) continue;  // counted as degenerate elsewhere
    faces.push_back({t[0], t[1], t[2]});
  }
  // Non-manifold edges and vertices are split so that CGAL can build a valid halfedge structure.
  PMP::orient_polygon_soup(points, faces);
  Mesh mesh;
  PMP::polygon_soup_to_polygon_mesh(points, faces, mesh);
  std::size_t count = 0;
  try {
    PMP::self_intersections(mesh, CountingOutput{&count, std::max<std::size_t>(maxPairs, 1)});
  } catch (const CountingOutput::LimitReached&) {
  }
  return count;
}

}  // namespace reamsim
