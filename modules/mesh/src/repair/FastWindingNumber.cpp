#include <algorithm>
#include <stdexcept>

#include "reamsim/mesh/WindingNumber.h"

namespace reamsim {
namespace {
constexpr std::uint32_t kLeafSize = 8;
}  // namespace

// Computed once a triangle: the build sums them at every level of the tree.
struct FastWindingNumber::Facet {
  Corners corners;
  Vec3 areaVector;     // ½ (b − a) × (c − a)
  double area = 0;     // its length
  Vec3 cornerSum;      // a + b + c: what the median split orders by
  Vec3 centroid;       // cornerSum / 3
};

FastWindingNumber::FastWindingNumber(const TriangleMesh& mesh) {
  if (mesh.triangles.empty()) return;
  if (mesh.triangles.size() >= std::size_t(0xffffffffu))
    throw std::length_error("FastWindingNumber: more triangles than 32-bit indices address");
  std::vector<Facet> facets;
  facets.reserve(mesh.triangles.size());
  for (const Triangle& t : mesh.triangles) {
    Facet f;
    f.corners = {mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]]};
    const Corners& c = f.corners;
    f.areaVector = cross(c.b - c.a, c.c - c.a) * 0.5;
    f.area = norm(f.areaVector);
    f.cornerSum = c.a + c.b + c.c;
    f.centroid = f.cornerSum / 3.0;
    facets.push_back(f);
  }
  std::vector<std::uint32_t> order(facets.size());
  for (std::uint32_t i = 0; i < order.size(); ++i) order[i] = i;
  nodes_.reserve(facets.size() / 2 + 2);  // leaves hold 4 to 8 triangles
  corners_.reserve(facets.size());
  build(order, 0, std::uint32_t(order.size()), facets);
}

std::uint32_t FastWindingNumber::build(std::vector<std::uint32_t>& order, std::uint32_t begin, std::uint32_t end,
                                       const std::vector<Facet>& facets) {
  const std::uint32_t index = std::uint32_t(nodes_.size());
  nodes_.emplace_back();
  // The cluster's moments, from its own triangles (O(n log n) in all; a build is a small part of a remesh).
  Node node;
  double area = 0;
  Vec3 weighted, plain;
  for (std::uint32_t i = begin; i < end; ++i) {
    const Facet& f = facets[order[i]];
    node.areaVector += f.areaVector;
    weighted += f.centroid * f.area;
    plain += f.centroid;
    area += f.area;
  }
  node.center = area > 0 ? weighted / area : plain / double(end - begin);
  for (std::uint32_t i = begin; i < end; ++i) {
    const Facet& f = facets[order[i]];
    const Vec3 d = f.centroid - node.center;
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) node.moment[3 * r + c] += f.areaVector[r] * d[c];
    for (const Vec3* p : {&f.corners.a, &f.corners.b, &f.corners.c})
      node.radius = std::max(node.radius, norm(*p - node.center));
  }

  if (end - begin <= kLeafSize) {
    node.first = std::uint32_t(corners_.size());
    node.count = end - begin;
    for (std::uint32_t i = begin; i < end; ++i) corners_.push_back(facets[order[i]].corners);
    nodes_[index] = node;
    return index;
  }
  // Median split along the longest axis of the centroids' bounds.
  Bounds b;
  for (std::uint32_t i = begin; i < end; ++i) b.add(facets[order[i]].centroid);
  const Vec3 extent = b.max - b.min;
  const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
  const std::uint32_t mid = begin + (end - begin) / 2;
  std::nth_element(order.begin() + begin, order.begin() + mid, order.begin() + end,
                   [&](std::uint32_t i, std::uint32_t j) { return facets[i].cornerSum[axis] < facets[j].cornerSum[axis]; });
  node.left = build(order, begin, mid, facets);
  node.right = build(order, mid, end, facets);
  nodes_[index] = node;
  return index;
}

double FastWindingNumber::evaluate(const Vec3& p, double beta, std::size_t* terms) const {
  if (!(beta >= 1) || !std::isfinite(beta)) throw std::invalid_argument("FastWindingNumber: beta must be at least 1");
  if (nodes_.empty()) return 0;
  const double beta2 = beta * beta;
  double sum = 0;
  std::size_t count = 0;
  std::uint32_t stack[128];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& node = nodes_[stack[--top]];
    const Vec3 y = node.center - p;
    const double d2 = squaredNorm(y);
    if (d2 > beta2 * node.radius * node.radius) {
      // Flux of the kernel (x − p)/|x − p|³ through the cluster, expanded about its centre to second order:
      // K(c)·N + Σ ∂_j K_i(c) M_ij, with ∂_j K_i = δ_ij/d³ − 3 y_i y_j/d⁵.
      const double inv3 = 1.0 / (d2 * std::sqrt(d2));
      const double* m = node.moment;
      const double trace = m[0] + m[4] + m[8];
      const double yMy = y.x * (m[0] * y.x + m[1] * y.y + m[2] * y.z) + y.y * (m[3] * y.x + m[4] * y.y + m[5] * y.z) +
                         y.z * (m[6] * y.x + m[7] * y.y + m[8] * y.z);
      sum += dot(y, node.areaVector) * inv3 + trace * inv3 - 3.0 * yMy * inv3 / d2;
      ++count;
    } else if (node.count > 0) {
      for (std::uint32_t i = node.first; i < node.first + node.count; ++i)
        sum += solidAngle(p, corners_[i].a, corners_[i].b, corners_[i].c);
      count += node.count;
    } else {
      stack[top++] = node.left;
      stack[top++] = node.right;
    }
  }
  if (terms) *terms += count;
  return sum / (4.0 * M_PI);
}

}  // namespace reamsim
