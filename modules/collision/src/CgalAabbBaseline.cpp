// The one CGAL translation unit of the collision module (benchmark baseline only).
#include "reamsim/collision/CgalAabbBaseline.h"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <chrono>
#include <cmath>
#include <iterator>

namespace reamsim {

namespace {
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = K::Point_3;
using Tri = K::Triangle_3;
using Iterator = std::vector<Tri>::const_iterator;
using Primitive = CGAL::AABB_triangle_primitive<K, Iterator>;
using Traits = CGAL::AABB_traits<K, Primitive>;
using Tree = CGAL::AABB_tree<Traits>;

Point toPoint(const Vec3& v) { return {v.x, v.y, v.z}; }
}  // namespace

struct CgalAabbBaseline::Impl {
  std::vector<Tri> tris;
  std::vector<std::size_t> meshIndex;  // tree triangle -> mesh triangle
  Tree tree;
  double buildMs = 0;
  std::size_t indexOf(Iterator it) const { return meshIndex[static_cast<std::size_t>(it - tris.cbegin())]; }
};

CgalAabbBaseline::CgalAabbBaseline(const TriangleMesh& mesh) : impl_(std::make_unique<Impl>()) {
  for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
    const Triangle& t = mesh.triangles[i];
    Tri tri(toPoint(mesh.vertices[t[0]]), toPoint(mesh.vertices[t[1]]), toPoint(mesh.vertices[t[2]]));
    if (tri.is_degenerate()) continue;
    impl_->tris.push_back(tri);
    impl_->meshIndex.push_back(i);
  }
  const auto start = std::chrono::steady_clock::now();
  impl_->tree.insert(impl_->tris.cbegin(), impl_->tris.cend());
  impl_->tree.build();
  impl_->tree.accelerate_distance_queries();
  impl_->buildMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

CgalAabbBaseline::~CgalAabbBaseline() = default;
CgalAabbBaseline::CgalAabbBaseline(CgalAabbBaseline&&) noexcept = default;
CgalAabbBaseline& CgalAabbBaseline::operator=(CgalAabbBaseline&&) noexcept = default;

double CgalAabbBaseline::buildMilliseconds() const { return impl_->buildMs; }
std::size_t CgalAabbBaseline::triangleCount() const { return impl_->tris.size(); }

bool CgalAabbBaseline::firstHit(const Vec3& origin, const Vec3& dir, double& t, std::size_t& triangle) const {
  const K::Ray_3 ray(toPoint(origin), K::Vector_3(dir.x, dir.y, dir.z));
  const auto hit = impl_->tree.first_intersection(ray);
  if (!hit) return false;
  Vec3 p;
  if (const Point* pt = boost::get<Point>(&hit->first)) {
    p = {pt->x(), pt->y(), pt->z()};
  } else if (const K::Segment_3* s = boost::get<K::Segment_3>(&hit->first)) {
    // Coplanar overlap: the entry point is the segment end nearer the origin.
    const Point a = s->source(), b = s->target();
    const double da = CGAL::squared_distance(a, ray.source()), db = CGAL::squared_distance(b, ray.source());
    const Point& q = da <= db ? a : b;
    p = {q.x(), q.y(), q.z()};
  } else {
    return false;
  }
  t = dot(p - origin, dir) / dot(dir, dir);
  triangle = impl_->indexOf(hit->second);
  return true;
}

std::size_t CgalAabbBaseline::countHits(const Vec3& origin, const Vec3& dir) const {
  const K::Ray_3 ray(toPoint(origin), K::Vector_3(dir.x, dir.y, dir.z));
  return impl_->tree.number_of_intersected_primitives(ray);
}

void CgalAabbBaseline::intersectedTriangles(const Vec3& a, const Vec3& b, const Vec3& c,
                                            std::vector<std::size_t>& out) const {
  const Tri query(toPoint(a), toPoint(b), toPoint(c));
  if (query.is_degenerate()) return;
  std::vector<Iterator> hits;
  impl_->tree.all_intersected_primitives(query, std::back_inserter(hits));
  for (Iterator it : hits) out.push_back(impl_->indexOf(it));
}

bool CgalAabbBaseline::intersects(const Vec3& a, const Vec3& b, const Vec3& c) const {
  const Tri query(toPoint(a), toPoint(b), toPoint(c));
  return !query.is_degenerate() && impl_->tree.do_intersect(query);
}

double CgalAabbBaseline::squaredDistance(const Vec3& p, Vec3& closest) const {
  const Point q = impl_->tree.closest_point(toPoint(p));
  closest = {q.x(), q.y(), q.z()};
  return squaredNorm(closest - p);
}

}  // namespace reamsim
