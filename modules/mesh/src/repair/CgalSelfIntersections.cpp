// CGAL translation unit: self-intersection count of an arbitrary triangle soup. Epick is right here:
// self_intersections uses predicates only, and Epick's predicates are exact.
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <vector>

#include <tbb/parallel_for.h>

#include "reamsim/mesh/Validation.h"

namespace reamsim {
namespace {
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Mesh = CGAL::Surface_mesh<K::Point_3>;
namespace PMP = CGAL::Polygon_mesh_processing;

// Counts the pairs CGAL reports in slab `slab` whose canonical slab it is (below), and stops the traversal
// once enough pairs are known (the count is then a lower bound).
struct CountingOutput {
  const std::vector<double>* lo;       // each face's lowest coordinate along the slabs' axis
  const std::vector<double>* inner;    // the slabs' inner boundaries, ascending
  std::size_t slab;
  std::size_t* count;
  std::size_t limit;
  CountingOutput& operator*() { return *this; }
  CountingOutput& operator++() { return *this; }
  CountingOutput operator++(int) { return *this; }
  template <class Pair>
  CountingOutput& operator=(const Pair& p) {
    const double x = std::max((*lo)[std::size_t(p.first)], (*lo)[std::size_t(p.second)]);
    if (slabOf(*inner, x) != slab) return *this;
    if (++*count >= limit) throw LimitReached{};
    return *this;
  }
  static std::size_t slabOf(const std::vector<double>& inner, double x) {
    return std::size_t(std::upper_bound(inner.begin(), inner.end(), x) - inner.begin());
  }
  struct LimitReached {};
};

}  // namespace

std::size_t countSelfIntersections(const TriangleMesh& input, std::size_t maxPairs, const StageProgress& progress) {
  // About 200,000 faces a slab: a second or less each, so a cancel is seen between them.
  return detail::countSelfIntersectionsInSlabs(input, maxPairs, progress, 200000);
}

std::size_t detail::countSelfIntersectionsInSlabs(const TriangleMesh& input, std::size_t maxPairs,
                                                  const StageProgress& progress, std::size_t facesPerSlab) {
  progress.check(0);
  std::vector<K::Point_3> points;
  points.reserve(input.vertices.size());
  for (const Vec3& p : input.vertices) points.emplace_back(p.x, p.y, p.z);
  std::vector<std::vector<std::size_t>> faces;
  faces.reserve(input.triangles.size());
  for (const Triangle& t : input.triangles) {
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) continue;  // counted as degenerate elsewhere
    faces.push_back({t[0], t[1], t[2]});
  }
  // Non-manifold edges and vertices are split so that CGAL can build a valid halfedge structure. (Asking
  // first whether the soup is already a valid mesh cost more than orienting it: session 48, the skull.)
  PMP::orient_polygon_soup(points, faces);
  Mesh mesh;
  PMP::polygon_soup_to_polygon_mesh(points, faces, mesh);
  progress.check(0.1);

  // The faces in slabs of about equal counts along the mesh's longest axis, each slab checked on its own
  // with the faces that reach into it. An intersecting pair's ranges along the axis overlap, so both faces
  // lie in the slab of the larger of their two lower ends, and the pair is counted there only: the same
  // count as one pass over the whole mesh.
  const std::size_t n = mesh.number_of_faces();
  Bounds bounds = computeBounds(input);
  const Vec3 extent = bounds.max - bounds.min;
  const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
  std::vector<double> lo(n), hi(n);
  for (Mesh::Face_index f : mesh.faces()) {
    const auto h = mesh.halfedge(f);
    const double a = mesh.point(mesh.target(h))[axis], b = mesh.point(mesh.target(mesh.next(h)))[axis],
                 c = mesh.point(mesh.source(h))[axis];
    lo[std::size_t(f)] = std::min({a, b, c});
    hi[std::size_t(f)] = std::max({a, b, c});
  }
  std::size_t slabs = std::max<std::size_t>(1, std::min<std::size_t>(64, n / std::max<std::size_t>(1, facesPerSlab)));
  const bool finite = std::all_of(lo.begin(), lo.end(), [](double x) { return std::isfinite(x); }) &&
                      std::all_of(hi.begin(), hi.end(), [](double x) { return std::isfinite(x); });
  if (!finite) slabs = 1;
  std::vector<double> inner;
  if (slabs > 1) {
    std::vector<double> sorted = lo;
    std::sort(sorted.begin(), sorted.end());
    for (std::size_t i = 1; i < slabs; ++i) inner.push_back(sorted[i * n / slabs]);
  }
  std::vector<std::vector<Mesh::Face_index>> inSlab(slabs);
  std::size_t entries = 0;
  for (Mesh::Face_index f : mesh.faces())
    for (std::size_t s = CountingOutput::slabOf(inner, lo[std::size_t(f)]); s <= CountingOutput::slabOf(inner, hi[std::size_t(f)]); ++s) {
      inSlab[s].push_back(f);
      ++entries;
    }
  // Faces long along the axis (a cylinder's sides in an STL) would be checked in many slabs over: then one
  // slab, as one pass over the whole mesh.
  if (entries > 2 * n && slabs > 1) {
    inner.clear();
    inSlab.assign(1, std::vector<Mesh::Face_index>(mesh.faces().begin(), mesh.faces().end()));
    slabs = 1;
  }

  // The slabs are independent (each reads the mesh and counts its own pairs), so they run two at a time, one
  // per core; progress is reported, and a cancel seen, between those pairs on the calling thread. Each slab
  // stops at the limit on its own, so the sum, capped at the limit, is what one pass would give.
  const std::size_t limit = std::max<std::size_t>(maxPairs, 1);
  std::vector<std::size_t> counts(slabs, 0);
  const auto countSlab = [&](std::size_t s) {
    if (s > 0 && s < inner.size() && inner[s - 1] == inner[s]) return;  // holds no canonical point
    try {
      PMP::self_intersections(inSlab[s], mesh, CountingOutput{&lo, &inner, s, &counts[s], limit});
    } catch (const CountingOutput::LimitReached&) {
    }
  };
  constexpr std::size_t kSlabsAtOnce = 2;
  std::size_t total = 0;
  for (std::size_t first = 0; first < slabs && total < limit; first += kSlabsAtOnce) {
    progress.check(0.1 + 0.9 * double(first) / double(slabs));
    tbb::parallel_for(first, std::min(slabs, first + kSlabsAtOnce), countSlab);
    for (std::size_t s = first; s < std::min(slabs, first + kSlabsAtOnce); ++s) total += counts[s];
  }
  return std::min(total, limit);
}

}  // namespace reamsim
