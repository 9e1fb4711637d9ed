// The hierarchy's read side: the region bound of a box and slab, and the bounds, quality and validation
// reports. Building is in TriangleBvhBuild.cpp, the local update in TriangleBvhUpdate.cpp.
#include "reamsim/collision/TriangleBvh.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "TriangleBvhInternal.h"

namespace reamsim {

using namespace bvh_detail;

Bounds TriangleBvh::bounds() const {
  Bounds b;
  if (root_ >= 0) {
    b.add(nodes_[root_].lo);
    b.add(nodes_[root_].hi);
  }
  return b;
}

std::size_t TriangleBvh::hugePageBytes() const {
  return hugePageBytesIn({{nodes_.data(), nodes_.size() * sizeof(BvhNode)},
                          {slabs_.data(), slabs_.size() * sizeof(BvhSlab)},
                          {tris_.data(), tris_.size() * sizeof(BvhTriangle)},
                          {leafTris_.data(), leafTris_.size() * sizeof(BvhTriangle)}});
}

BvhQuality TriangleBvh::quality() const {
  BvhQuality q;
  q.triangles = triangleCount_;
  if (root_ < 0) return q;
  const double rootArea = std::max(area(nodes_[root_].lo, nodes_[root_].hi), 1e-300);
  std::vector<std::pair<std::int32_t, std::size_t>> stack{{root_, 1}};
  double cost = 0;
  while (!stack.empty()) {
    const auto [i, depth] = stack.back();
    stack.pop_back();
    const BvhNode& n = nodes_[i];
    ++q.nodes;
    q.maxDepth = std::max(q.maxDepth, depth);
    const double a = area(n.lo, n.hi) / rootArea;
    if (n.isLeaf()) {
      ++q.leaves;
      cost += a * n.count;
    } else {
      cost += a;
      stack.push_back({n.left, depth + 1});
      stack.push_back({n.right, depth + 1});
    }
  }
  q.sahCost = cost;
  q.meanLeafSize = q.leaves ? double(q.triangles) / double(q.leaves) : 0;
  return q;
}

std::string TriangleBvh::validate() const {
  if (root_ < 0) return triangleCount_ == 0 ? "" : "empty tree but triangleCount != 0";
  if (nodes_[root_].parent != -1) return "root has a parent";
  std::size_t seen = 0;
  std::vector<std::int32_t> stack{root_};
  auto encloses = [](const BvhNode& outer, const Vec3& lo, const Vec3& hi) {
    return outer.lo.x <= lo.x && outer.lo.y <= lo.y && outer.lo.z <= lo.z && outer.hi.x >= hi.x &&
           outer.hi.y >= hi.y && outer.hi.z >= hi.z;
  };
  while (!stack.empty()) {
    const std::int32_t i = stack.back();
    stack.pop_back();
    const BvhNode& n = nodes_[i];
    if (n.right == -2) return "reachable node " + std::to_string(i) + " is freed";
    if (book_[i].dirty) return "node " + std::to_string(i) + " left dirty";
    if (n.isLeaf()) {
      const int capacity = largeBlock_[std::size_t(n.left) / kBuildLeafSize] ? kLeafCapacity : kBuildLeafSize;
      if (n.count < 1 || n.count > capacity) return "leaf " + std::to_string(i) + " has count " + std::to_string(n.count);
      if (book_[i].size != n.count) return "leaf " + std::to_string(i) + " size counter mismatch";
      const std::uint32_t* s = leafSlots(n);
      const BvhTriangle* copies = leafTriangles(n);
      for (int k = 0; k < n.count; ++k) {
        if (s[k] >= leafOf_.size() || leafOf_[s[k]] != i) return "slot " + std::to_string(s[k]) + " not mapped to its leaf";
        const BvhTriangle& t = tris_[s[k]];
        if (!(copies[k].a == t.a && copies[k].b == t.b && copies[k].c == t.c))
          return "leaf " + std::to_string(i) + " holds a stale copy of slot " + std::to_string(s[k]);
        Vec3 lo, hi;
        paddedBox(t, lo, hi);
        if (!encloses(n, lo, hi)) return "leaf " + std::to_string(i) + " does not enclose slot " + std::to_string(s[k]);
        // Every slab on the path to the root holds the triangle's corners.
        for (std::int32_t a = i; a >= 0; a = nodes_[a].parent) {
          const BvhSlab& sl = slabs_[a];
          for (const Vec3* v : {&t.a, &t.b, &t.c}) {
            const double dv = dot(sl.axis, *v);
            if (!(dv >= sl.lo && dv <= sl.hi))
              return "slab of node " + std::to_string(a) + " does not hold slot " + std::to_string(s[k]);
          }
        }
      }
      seen += std::size_t(n.count);
    } else {
      for (std::int32_t c : {n.left, n.right}) {
        if (c < 0 || std::size_t(c) >= nodes_.size()) return "bad child index";
        if (nodes_[c].parent != i) return "child " + std::to_string(c) + " has a wrong parent";
        if (!encloses(n, nodes_[c].lo, nodes_[c].hi)) return "node " + std::to_string(i) + " does not enclose its child";
      }
      if (book_[i].size != book_[n.left].size + book_[n.right].size) return "size counter mismatch at " + std::to_string(i);
      stack.push_back(n.left);
      stack.push_back(n.right);
    }
  }
  if (seen != triangleCount_) return "tree holds " + std::to_string(seen) + " triangles, expected " + std::to_string(triangleCount_);
  std::size_t mapped = 0;
  for (std::int32_t l : leafOf_) mapped += l >= 0;
  if (mapped != seen) return "slot map holds stale entries";
  return "";
}

}  // namespace reamsim
