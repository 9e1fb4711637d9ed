#include "reamsim/collision/FirstContact.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include "ContactEvents.h"
#include "RationalMotion.h"
#include "SurfaceTouch.h"
#include "reamsim/collision/TriangleGeometry.h"

namespace reamsim {

namespace {

using detail::Mat3;
using detail::MotionPlan;
using detail::PairContact;
using detail::SegmentMotion;

constexpr double kInf = std::numeric_limits<double>::infinity();

// Per-thread scratch: reamer node boxes rotated by R0 and reamer triangles rotated by R0, filled on first use.
struct ToiScratch {
  std::vector<std::uint32_t> nodeStamp, triStamp, planeStamp;
  std::vector<Vec3> a0lo, a0hi, rlo, rhi;
  std::vector<detail::AxisSweep> slab;
  std::vector<std::array<Vec3, 3>> q;
  std::vector<detail::AxisSweep> plane;
  std::uint32_t stamp = 0;
  void begin(std::size_t nodes, std::size_t tris) {
    if (nodeStamp.size() < nodes) {
      nodeStamp.resize(nodes, 0);
      a0lo.resize(nodes);
      a0hi.resize(nodes);
      rlo.resize(nodes);
      rhi.resize(nodes);
      slab.resize(nodes);
    }
    if (triStamp.size() < tris) {
      triStamp.resize(tris, 0);
      planeStamp.resize(tris, 0);
      q.resize(tris);
      plane.resize(tris);
    }
    if (++stamp == 0) {
      std::fill(nodeStamp.begin(), nodeStamp.end(), 0);
      std::fill(triStamp.begin(), triStamp.end(), 0);
      std::fill(planeStamp.begin(), planeStamp.end(), 0);
      stamp = 1;
    }
  }
};
thread_local ToiScratch tlsScratch;

// Best-first search over (bone node, reamer node) pairs ordered by the earliest time they can meet: the
// later of the time their boxes can meet (the reamer box at s = 0 moved along the tip's travel and grown by
// the rotation's reach: sweptBoxTime, exact for translations) and the time the reamer node's slab along its
// own normal can reach the bone box (axisSweepTime: what keeps a tilted face patch thin). Pairs that cannot
// meet before the best contact so far are dropped; triangle pairs that survive get the same two bounds plus
// a plane bound, then the exact cubic events.
class ToiSearch {
 public:
  ToiSearch(const TriangleBvh& bone, const ReamerModel& reamer, const SegmentMotion& m, FirstContactResult& out)
      : bone_(bone), rtree_(reamer.solidBvh()), radius_(reamer.solidNodeRadius()), slabs_(reamer.solidNodeSlabs()),
        m_(m), out_(out),
        sc_(tlsScratch) {
    sc_.begin(rtree_.nodes().size(), rtree_.slotCapacity());
  }

  bool run(double& sHit) {
    heap_.clear();
    pushNodes(bone_.root(), rtree_.root());
    const auto& bn = bone_.nodes();
    const auto& rn = rtree_.nodes();
    while (!heap_.empty()) {
      std::pop_heap(heap_.begin(), heap_.end());
      const Item it = heap_.back();
      heap_.pop_back();
      if (found_ ? it.slb >= best_ : it.slb > best_) break;  // every remaining item starts later
      if (it.triangles) {
        exact(it.b, it.r);
        continue;
      }
      const BvhNode& B = bn[it.b];
      const BvhNode& R = rn[it.r];
      if (B.isLeaf() && R.isLeaf()) {
        leafPair(B, R);
        continue;
      }
      const double sb = (B.hi.x - B.lo.x) + (B.hi.y - B.lo.y) + (B.hi.z - B.lo.z);
      const double sr = (R.hi.x - R.lo.x) + (R.hi.y - R.lo.y) + (R.hi.z - R.lo.z);
      if (R.isLeaf() || (!B.isLeaf() && sb >= sr)) {
        pushNodes(B.left, it.r);
        pushNodes(B.right, it.r);
      } else {
        pushNodes(it.b, R.left);
        pushNodes(it.b, R.right);
      }
    }
    sHit = best_;
    return found_;
  }

 private:
  // Reamer node box rotated by R0 and placed at the start tip, with the rates of its faces (cached).
  void startBox(std::int32_t r) {
    if (sc_.nodeStamp[r] == sc_.stamp) return;
    const BvhNode& R = rtree_.nodes()[r];
    Vec3 qlo, qhi;
    detail::mapBox(m_.R0, Vec3{}, R.lo, R.hi, qlo, qhi);
    sc_.a0lo[r] = qlo + m_.tip0;
    sc_.a0hi[r] = qhi + m_.tip0;
    detail::boxRates(m_, qlo, qhi, radius_[r], sc_.rlo[r], sc_.rhi[r]);
    const ReamerModel::NodeSlab& sl = slabs_[r];
    sc_.slab[r] = detail::axisSweep(m_, sl.axis, sl.lo, sl.hi, R.lo, R.hi, radius_[r]);
    sc_.nodeStamp[r] = sc_.stamp;
  }

  double bound(std::int32_t b, std::int32_t r) {
    startBox(r);
    const BvhNode& B = bone_.nodes()[b];
    const double t = detail::sweptBoxTime(sc_.a0lo[r], sc_.a0hi[r], sc_.rlo[r], sc_.rhi[r], B.lo, B.hi, best_);
    if (!promising(t)) return t;
    const detail::AxisSweep& slab = sc_.slab[r];
    double plo, phi;
    detail::projectBox(slab.axis, B.lo, B.hi, plo, phi);
    const double ts = std::max(t, detail::axisSweepTime(slab, plo, phi, best_));
    if (!promising(ts) || !B.isLeaf()) return ts;
    // A bone leaf: its triangles' own extent along the axis, much thinner than its box's when the patch
    // is tilted against the bone's axes (the near-contact case, where most pairs are leaves).
    const std::uint32_t* slots = bone_.leafSlots(B);
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (int i = 0; i < B.count; ++i) {
      const BvhTriangle& bt = bone_.triangle(slots[i]);
      for (const Vec3* v : {&bt.a, &bt.b, &bt.c}) {
        const double d = dot(slab.axis, *v);
        lo = std::min(lo, d);
        hi = std::max(hi, d);
      }
    }
    const double pad = 1e-12 * (std::abs(lo) + std::abs(hi)) + 1e-300;
    return std::max(ts, detail::axisSweepTime(slab, lo - pad, hi + pad, best_));
  }

  const std::array<Vec3, 3>& rotatedTriangle(std::uint32_t slot) {
    if (sc_.triStamp[slot] != sc_.stamp) {
      const BvhTriangle& t = rtree_.triangle(slot);
      sc_.q[slot] = {m_.R0 * t.a, m_.R0 * t.b, m_.R0 * t.c};
      sc_.triStamp[slot] = sc_.stamp;
    }
    return sc_.q[slot];
  }

  struct Item {
    double slb;
    std::int32_t b, r;  // node pair, or (bone slot, reamer slot) when `triangles`
    bool triangles;
    bool operator<(const Item& o) const { return slb > o.slb; }  // min-heap
  };
  bool promising(double t) const { return found_ ? t < best_ : t <= best_; }
  void push(const Item& it) {
    heap_.push_back(it);
    std::push_heap(heap_.begin(), heap_.end());
  }
  void pushNodes(std::int32_t b, std::int32_t r) {
    const double t = bound(b, r);
    if (promising(t)) push({t, b, r, false});
  }

  // Triangle pairs of two leaves, queued by their own bounds so the exact events run earliest-first.
  void leafPair(const BvhNode& B, const BvhNode& R) {
    const std::uint32_t* bs = bone_.leafSlots(B);
    const std::uint32_t* rs = rtree_.leafSlots(R);
    Vec3 blo[TriangleBvh::kLeafCapacity], bhi[TriangleBvh::kLeafCapacity];
    for (int i = 0; i < B.count; ++i) TriangleBvh::paddedBox(bone_.triangle(bs[i]), blo[i], bhi[i]);
    for (int j = 0; j < R.count; ++j) {
      const auto& qa = rotatedTriangle(rs[j]);
      const Vec3 X[3] = {m_.tip0 + qa[0], m_.tip0 + qa[1], m_.tip0 + qa[2]};
      Vec3 tlo, thi, qlo, qhi, rlo, rhi;
      TriangleBvh::paddedBox({X[0], X[1], X[2]}, tlo, thi);
      TriangleBvh::paddedBox({qa[0], qa[1], qa[2]}, qlo, qhi);
      detail::boxRates(m_, qlo, qhi, std::max({norm(qa[0]), norm(qa[1]), norm(qa[2])}), rlo, rhi);
      const detail::AxisSweep& plane = planeSweep(rs[j]);
      for (int i = 0; i < B.count; ++i) {
        const BvhTriangle& bt = bone_.triangle(bs[i]);
        double t = detail::sweptBoxTime(tlo, thi, rlo, rhi, blo[i], bhi[i], best_);
        if (!promising(t)) continue;
        // The reamer triangle's own plane, moving: the bone triangle's extent along its normal.
        const double h0 = dot(plane.axis, bt.a), h1 = dot(plane.axis, bt.b), h2 = dot(plane.axis, bt.c);
        const double hlo = std::min({h0, h1, h2}), hhi = std::max({h0, h1, h2});
        const double pad = 1e-12 * (std::abs(hlo) + std::abs(hhi)) + 1e-300;
        t = std::max(t, detail::axisSweepTime(plane, hlo - pad, hhi + pad, best_));
        if (!promising(t)) continue;
        // Plane bound: each reamer vertex needs at least h / (its fastest approach) to reach the bone
        // triangle's plane, and the triangle cannot touch before its first vertex or edge does.
        const Vec3 n = cross(bt.b - bt.a, bt.c - bt.a);
        const double h[3] = {dot(n, X[0] - bt.a), dot(n, X[1] - bt.a), dot(n, X[2] - bt.a)};
        if ((h[0] > 0 && h[1] > 0 && h[2] > 0) || (h[0] < 0 && h[1] < 0 && h[2] < 0)) {
          const double side = h[0] > 0 ? 1.0 : -1.0;
          double tp = std::numeric_limits<double>::infinity();
          for (int k = 0; k < 3; ++k) {
            const double rate = detail::approachRate(m_, n, qa[k], side);
            if (rate > 0) tp = std::min(tp, side * h[k] / rate * (1 - 1e-12));
          }
          t = std::max(t, tp);
          if (!promising(t)) continue;
        }
        push({t, static_cast<std::int32_t>(bs[i]), static_cast<std::int32_t>(rs[j]), true});
      }
    }
  }

  // The sweep of a reamer triangle along its own normal (cached: a triangle meets many bone leaves).
  const detail::AxisSweep& planeSweep(std::uint32_t slot) {
    if (sc_.planeStamp[slot] == sc_.stamp) return sc_.plane[slot];
    const BvhTriangle& lt = rtree_.triangle(slot);
    Vec3 n = cross(lt.b - lt.a, lt.c - lt.a);
    const double len = norm(n);
    n = len > 0 ? n / len : Vec3{0, 0, 1};
    const double d0 = dot(n, lt.a), d1 = dot(n, lt.b), d2 = dot(n, lt.c);
    const Vec3 plo{std::min({lt.a.x, lt.b.x, lt.c.x}), std::min({lt.a.y, lt.b.y, lt.c.y}),
                   std::min({lt.a.z, lt.b.z, lt.c.z})};
    const Vec3 phi{std::max({lt.a.x, lt.b.x, lt.c.x}), std::max({lt.a.y, lt.b.y, lt.c.y}),
                   std::max({lt.a.z, lt.b.z, lt.c.z})};
    const double reach = std::max({norm(lt.a), norm(lt.b), norm(lt.c)});  // rotation keeps lengths
    sc_.plane[slot] = detail::axisSweep(m_, n, std::min({d0, d1, d2}), std::max({d0, d1, d2}), plo, phi, reach);
    sc_.planeStamp[slot] = sc_.stamp;
    return sc_.plane[slot];
  }

  void exact(std::int32_t boneSlot, std::int32_t reamerSlot) {
    const BvhTriangle& lt = rtree_.triangle(static_cast<std::uint32_t>(reamerSlot));
    const auto& qa = rotatedTriangle(static_cast<std::uint32_t>(reamerSlot));
    const Vec3 p[3] = {lt.a, lt.b, lt.c};
    const Vec3 q[3] = {qa[0], qa[1], qa[2]};
    ++out_.trianglePairs;
    const PairContact c = detail::pairFirstContact(m_, p, q, bone_.triangle(static_cast<std::uint32_t>(boneSlot)), best_, false);
    if (!c.hit || (found_ && c.s >= best_)) return;
    found_ = true;
    best_ = c.s;
    out_.point = c.point;
    out_.normal = c.normal;
    out_.feature = c.feature;
    out_.boneSlot = static_cast<std::uint32_t>(boneSlot);
    out_.reamerTriangle = static_cast<std::uint32_t>(reamerSlot);
  }

  const TriangleBvh& bone_;
  const TriangleBvh& rtree_;
  const std::vector<double>& radius_;
  const std::vector<ReamerModel::NodeSlab>& slabs_;
  const SegmentMotion m_;
  FirstContactResult& out_;
  ToiScratch& sc_;
  bool found_ = false;
  double best_ = 1;
  std::vector<Item> heap_;
};

}  // namespace

FirstContactResult queryFirstContact(const TriangleBvh& bone, const ReamerModel& reamer, const RigidTransform& from,
                                     const RigidTransform& to) {
  FirstContactResult out;
  if (bone.empty()) return out;
  // Touching at the start: time 0 (the search below then knows the surfaces start apart).
  detail::TouchPair touch;
  if (detail::surfacesTouch(bone, reamer, from, &touch)) {
    const BvhTriangle& bt = bone.triangle(touch.boneSlot);
    out.hit = true;
    out.t = 0;
    out.point = touch.point;
    out.normal = normalized(cross(bt.b - bt.a, bt.c - bt.a));
    out.boneSlot = touch.boneSlot;
    out.reamerTriangle = touch.reamerTriangle;
    out.feature = ContactFeature::Initial;
    return out;
  }
  const MotionPlan plan = MotionPlan::between(from, to);
  for (int i = 0; i < plan.segments; ++i) {
    double s;
    FirstContactResult seg;
    if (ToiSearch(bone, reamer, plan.segment(i), seg).run(s)) {
      seg.hit = true;
      seg.t = std::min(1.0, (i + s) / plan.segments);
      seg.trianglePairs += out.trianglePairs;
      return seg;
    }
    out.trianglePairs += seg.trianglePairs;
  }
  return out;
}

FirstContactResult queryFirstContact(const TriangleBvh& bone, const ReamerModel& reamer, const Pose& from,
                                     const Pose& to) {
  return queryFirstContact(bone, reamer, toTransform(from), toTransform(to));
}

RigidTransform interpolateMotion(const RigidTransform& from, const RigidTransform& to, double t) {
  return MotionPlan::between(from, to).at(t);
}

}  // namespace reamsim
