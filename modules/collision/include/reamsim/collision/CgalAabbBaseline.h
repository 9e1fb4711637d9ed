#pragma once
// CGAL's AABB_tree (Epick kernel) over a triangle mesh, wrapped for the collision benchmark: the baseline the
// BVH is compared with for the queries CGAL has (ray first hit, ray hit count, triangle intersection, closest
// point). Degenerate (collinear) triangles are left out, as CGAL's predicates require proper triangles.
#include <cstddef>
#include <memory>
#include <vector>

#include "reamsim/mesh/TriangleMesh.h"

namespace reamsim {

class CgalAabbBaseline {
 public:
  explicit CgalAabbBaseline(const TriangleMesh& mesh);
  ~CgalAabbBaseline();
  CgalAabbBaseline(CgalAabbBaseline&&) noexcept;
  CgalAabbBaseline& operator=(CgalAabbBaseline&&) noexcept;

  double buildMilliseconds() const;
  std::size_t triangleCount() const;  // triangles in the tree

  // Nearest intersection of the ray origin + t dir (t >= 0): t in units of |dir|, and the mesh triangle.
  bool firstHit(const Vec3& origin, const Vec3& dir, double& t, std::size_t& triangle) const;
  std::size_t countHits(const Vec3& origin, const Vec3& dir) const;  // intersected triangles (not merged)
  // Mesh triangles intersecting the closed triangle abc (appended to out).
  void intersectedTriangles(const Vec3& a, const Vec3& b, const Vec3& c, std::vector<std::size_t>& out) const;
  bool intersects(const Vec3& a, const Vec3& b, const Vec3& c) const;
  double squaredDistance(const Vec3& p, Vec3& closest) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace reamsim
