// CGAL translation unit: AABB tree distance queries.
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <cmath>
#include <tbb/parallel_for.h>

#include "DistanceOracle.h"
#include "reamsim/mesh/VolumetricRemesh.h"

namespace reamsim {
namespace {
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Primitive = CGAL::AABB_triangle_primitive<K, std::vector<K::Triangle_3>::const_iterator>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<K, Primitive>>;
}  // namespace

struct DistanceOracle::Impl {
  std::vector<K::Triangle_3> triangles;
  Tree tree;
};

DistanceOracle::DistanceOracle(const TriangleMesh& mesh) : impl_(std::make_unique<Impl>()) {
  impl_->triangles.reserve(mesh.triangles.size());
  for (const Triangle& t : mesh.triangles) {
    const Vec3 &a = mesh.vertices[t[0]], &b = mesh.vertices[t[1]], &c = mesh.vertices[t[2]];
    K::Triangle_3 tri({a.x, a.y, a.z}, {b.x, b.y, b.z}, {c.x, c.y, c.z});
    if (!tri.is_degenerate()) impl_->triangles.push_back(tri);
  }
  impl_->tree.insert(impl_->triangles.cbegin(), impl_->triangles.cend());
  impl_->tree.accelerate_distance_queries();
}

DistanceOracle::~DistanceOracle() = default;

double DistanceOracle::distance(const Vec3& p) const {
  if (impl_->triangles.empty()) return INFINITY;
  return std::sqrt(impl_->tree.squared_distance(K::Point_3(p.x, p.y, p.z)));
}

void surfaceDistance(const TriangleMesh& from, const TriangleMesh& to, double& maxMm, double& meanMm,
                     const StageProgress& progress) {
  progress.check(0);
  DistanceOracle oracle(to);
  std::vector<double> d(from.vertices.size());
  // In slices, so that a cancel is seen within a fraction of a second at millions of vertices.
  constexpr std::size_t kSlice = std::size_t(1) << 14;
  for (std::size_t first = 0; first < d.size(); first += kSlice) {
    progress.check(double(first) / double(d.size()));
    tbb::parallel_for(first, std::min(d.size(), first + kSlice), [&](std::size_t i) { d[i] = oracle.distance(from.vertices[i]); });
  }
  maxMm = 0;
  double sum = 0;
  for (double x : d) { maxMm = std::max(maxMm, x); sum += x; }
  meanMm = d.empty() ? 0 : sum / d.size();
}

}  // namespace reamsim
