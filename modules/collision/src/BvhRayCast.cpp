#include "reamsim/collision/BvhRayCast.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "QueryArguments.h"

namespace reamsim {

namespace {

// Slab test prepared once per ray. Zero direction components are handled explicitly (no 0 * inf NaNs):
// the ray then stays in the slab or never enters it.
struct RaySlabs {
  Vec3 o, inv;
  bool zero[3];
  explicit RaySlabs(const Vec3& origin, const Vec3& dir) : o(origin) {
    for (int i = 0; i < 3; ++i) {
      zero[i] = dir[i] == 0.0;
      inv[i] = zero[i] ? 0.0 : 1.0 / dir[i];
    }
  }
  // Parameter interval of the ray inside [lo, hi] clipped to [t0, t1]; false when empty.
  bool clip(const Vec3& lo, const Vec3& hi, double t0, double t1, double& enter) const {
    for (int i = 0; i < 3; ++i) {
      if (zero[i]) {
        if (o[i] < lo[i] || o[i] > hi[i]) return false;
        continue;
      }
      double a = (lo[i] - o[i]) * inv[i], b = (hi[i] - o[i]) * inv[i];
      if (a > b) std::swap(a, b);
      t0 = a > t0 ? a : t0;
      t1 = b < t1 ? b : t1;
      if (t0 > t1) return false;
    }
    enter = t0;
    return true;
  }
};

// Hits at t in [-kRayStartEpsilon, 0) are clamped to 0 by the triangle test, so boxes are entered from there.
constexpr double kStart = -2 * kRayStartEpsilon;

MeshHit toMeshHit(const RayHit& h, std::uint32_t slot, const Vec3& origin, const Vec3& dir) {
  return MeshHit{h.t, h.u, h.v, h.frontFacing, slot, origin + dir * h.t};
}

}  // namespace

std::optional<MeshHit> firstHit(const TriangleBvh& bvh, const Vec3& origin, const Vec3& dir, Culling culling,
                                 double tMax) {
  detail::requireRay(origin, dir, "firstHit");
  std::optional<MeshHit> best;
  if (bvh.empty()) return best;
  const RaySlabs ray(origin, dir);
  const auto& nodes = bvh.nodes();
  double enter;
  if (!ray.clip(nodes[bvh.root()].lo, nodes[bvh.root()].hi, kStart, tMax, enter)) return best;
  struct Item {
    std::int32_t node;
    double enter;
  };
  Item stack[256];
  std::vector<Item> overflow;
  int top = 0;
  stack[top++] = {bvh.root(), enter};
  double bestT = tMax;
  while (top > 0 || !overflow.empty()) {
    Item it;
    if (!overflow.empty()) { it = overflow.back(); overflow.pop_back(); } else { it = stack[--top]; }
    if (it.enter > bestT) continue;
    const BvhNode& n = nodes[it.node];
    if (n.isLeaf()) {
      const std::uint32_t* slots = bvh.leafSlots(n);
      const BvhTriangle* tris = bvh.leafTriangles(n);
      for (int i = 0; i < n.count; ++i) {
        const BvhTriangle& t = tris[i];
        const auto h = intersectRayTriangle(origin, dir, t.a, t.b, t.c, culling);
        if (!h || h->t > bestT) continue;
        if (!best || h->t < best->t || (h->t == best->t && slots[i] < best->triangle)) {
          best = toMeshHit(*h, slots[i], origin, dir);
          bestT = h->t;
        }
      }
      continue;
    }
    double el = 0, er = 0;
    const bool hl = ray.clip(nodes[n.left].lo, nodes[n.left].hi, kStart, bestT, el);
    const bool hr = ray.clip(nodes[n.right].lo, nodes[n.right].hi, kStart, bestT, er);
    auto push = [&](Item i) {
      if (top < 256) stack[top++] = i; else overflow.push_back(i);
    };
    if (hl && hr) {
      // Near child on top of the stack.
      if (el <= er) { push({n.right, er}); push({n.left, el}); } else { push({n.left, el}); push({n.right, er}); }
    } else if (hl) {
      push({n.left, el});
    } else if (hr) {
      push({n.right, er});
    }
  }
  return best;
}

std::vector<MeshHit> allHits(const TriangleBvh& bvh, const Vec3& origin, const Vec3& dir, Culling culling) {
  detail::requireRay(origin, dir, "allHits");
  std::vector<MeshHit> raw;
  if (bvh.empty()) return raw;
  const RaySlabs ray(origin, dir);
  const auto& nodes = bvh.nodes();
  constexpr double kInf = std::numeric_limits<double>::infinity();
  std::vector<std::int32_t> stack{bvh.root()};
  double enter;
  while (!stack.empty()) {
    const BvhNode& n = nodes[stack.back()];
    stack.pop_back();
    if (!ray.clip(n.lo, n.hi, kStart, kInf, enter)) continue;
    if (n.isLeaf()) {
      const std::uint32_t* slots = bvh.leafSlots(n);
      const BvhTriangle* tris = bvh.leafTriangles(n);
      for (int i = 0; i < n.count; ++i) {
        const BvhTriangle& t = tris[i];
        if (const auto h = intersectRayTriangle(origin, dir, t.a, t.b, t.c, culling))
          raw.push_back(toMeshHit(*h, slots[i], origin, dir));
      }
    } else {
      stack.push_back(n.left);
      stack.push_back(n.right);
    }
  }
  return mergeCrossings(std::move(raw));
}

bool insideClosedSurface(const TriangleBvh& bvh, const Vec3& p) {
  // A direction unlikely to lie in the plane of a modelled face (not axis-aligned, irrational ratios).
  const Vec3 dir{0.2672612419124244, 0.5345224838248488, 0.8017837257372732};
  return allHits(bvh, p, dir).size() % 2 == 1;
}

}  // namespace reamsim
