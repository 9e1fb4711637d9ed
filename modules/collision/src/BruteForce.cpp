#include "reamsim/collision/BruteForce.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "AxialEvents.h"
#include "ContactEvents.h"
#include "PoseFrame.h"
#include "RationalMotion.h"
#include "reamsim/collision/MeshRayCast.h"
#include "reamsim/collision/TriangleGeometry.h"

namespace reamsim {

namespace {

using detail::PoseFrame;
constexpr double kInf = std::numeric_limits<double>::infinity();
const Vec3 kParityDir{0.2672612419124244, 0.5345224838248488, 0.8017837257372732};  // as insideClosedSurface

BvhTriangle corners(const TriangleMesh& m, std::size_t i) {
  const Triangle& t = m.triangles[i];
  return {m.vertices[t[0]], m.vertices[t[1]], m.vertices[t[2]]};
}

struct BoxedTri {
  BvhTriangle t;
  Vec3 lo, hi;
};
std::vector<BoxedTri> boxed(const TriangleMesh& m, const PoseFrame* toWorld) {
  std::vector<BoxedTri> out(m.triangles.size());
  for (std::size_t i = 0; i < m.triangles.size(); ++i) {
    BvhTriangle t = corners(m, i);
    if (toWorld) t = {toWorld->toWorld(t.a), toWorld->toWorld(t.b), toWorld->toWorld(t.c)};
    out[i].t = t;
    TriangleBvh::paddedBox(t, out[i].lo, out[i].hi);
  }
  return out;
}

}  // namespace

OverlapResult bruteForceOverlap(const TriangleMesh& bone, const ReamerModel& reamer, const RigidTransform& pose,
                                bool boneClosed) {
  OverlapResult out;
  const PoseFrame frame(pose);
  const std::vector<BoxedTri> rt = boxed(reamer.solid(), nullptr);
  const Bounds rb = computeBounds(reamer.solid());
  for (std::size_t i = 0; i < bone.triangles.size(); ++i) {
    const BvhTriangle w = corners(bone, i);
    const BvhTriangle l{frame.toLocal(w.a), frame.toLocal(w.b), frame.toLocal(w.c)};
    Vec3 lo, hi;
    TriangleBvh::paddedBox(l, lo, hi);
    bool crossing = false;
    for (const BoxedTri& r : rt)
      if (boxesOverlap(lo, hi, r.lo, r.hi) && trianglesIntersect(l.a, l.b, l.c, r.t.a, r.t.b, r.t.c)) {
        crossing = true;
        break;
      }
    if (crossing) {
      out.touchedSlots.push_back(static_cast<std::uint32_t>(i));
      ++out.surfaceCrossings;
    } else if (boxesOverlap(lo, hi, rb.min, rb.max) && reamer.containsLocal(l.a)) {
      out.touchedSlots.push_back(static_cast<std::uint32_t>(i));
      ++out.insideFaces;
    }
  }
  if (out.touchedSlots.empty() && boneClosed && !bone.triangles.empty())
    out.reamerInsideBone = allHits(bone, pose.apply(reamer.deepPoint()), kParityDir).size() % 2 == 1;
  out.overlap = !out.touchedSlots.empty() || out.reamerInsideBone;
  return out;
}

DistanceResult bruteForceFaceDistance(const TriangleMesh& bone, const ReamerModel& reamer, const RigidTransform& pose) {
  DistanceResult out;
  const PoseFrame frame(pose);
  std::vector<BoxedTri> face;
  for (std::uint32_t f : reamer.faceTriangles()) {
    BvhTriangle t = corners(reamer.solid(), f);
    t = {frame.toWorld(t.a), frame.toWorld(t.b), frame.toWorld(t.c)};
    BoxedTri b{t, {}, {}};
    TriangleBvh::paddedBox(t, b.lo, b.hi);
    face.push_back(b);
  }
  const std::vector<BoxedTri> bt = boxed(bone, nullptr);
  double best2 = kInf;
  auto evaluate = [&](std::size_t i, std::size_t j) {
    ++out.trianglePairs;
    const ClosestPair cp = closestTriangleTriangle(face[j].t.a, face[j].t.b, face[j].t.c, bt[i].t.a, bt[i].t.b, bt[i].t.c);
    if (cp.squaredDistance < best2) {
      best2 = cp.squaredDistance;
      out.found = true;
      out.onReamer = cp.onA;
      out.onBone = cp.onB;
      out.boneSlot = static_cast<std::uint32_t>(i);
      out.reamerTriangle = reamer.faceTriangles()[j];
    }
  };
  // Seed with the pair of nearest boxes, then scan every pair whose box distance could still beat it.
  double seedLb = kInf;
  std::size_t si = 0, sj = 0;
  for (std::size_t i = 0; i < bt.size(); ++i)
    for (std::size_t j = 0; j < face.size(); ++j) {
      const double lb = boxSquaredDistance(bt[i].lo, bt[i].hi, face[j].lo, face[j].hi);
      if (lb < seedLb) { seedLb = lb; si = i; sj = j; }
    }
  if (!bt.empty() && !face.empty()) evaluate(si, sj);
  for (std::size_t i = 0; i < bt.size(); ++i)
    for (std::size_t j = 0; j < face.size(); ++j)
      if (boxSquaredDistance(bt[i].lo, bt[i].hi, face[j].lo, face[j].hi) < best2) evaluate(i, j);
  if (out.found) out.distanceMm = std::sqrt(best2);
  return out;
}

FirstContactResult bruteForceFirstContact(const TriangleMesh& bone, const ReamerModel& reamer,
                                          const RigidTransform& from, const RigidTransform& to) {
  FirstContactResult out;
  const detail::MotionPlan plan = detail::MotionPlan::between(from, to);
  const std::vector<BoxedTri> bt = boxed(bone, nullptr);
  const TriangleMesh& solid = reamer.solid();
  for (int seg = 0; seg < plan.segments && !out.hit; ++seg) {
    const detail::SegmentMotion m = plan.segment(seg);
    const detail::Mat3 rotEnd = m.tau == 0 ? detail::Mat3{} : m.turnAt(1.0);
    double best = 1;
    for (std::size_t j = 0; j < solid.triangles.size(); ++j) {
      const BvhTriangle lt = corners(solid, j);
      const Vec3 p[3] = {lt.a, lt.b, lt.c};
      const Vec3 q[3] = {m.R0 * lt.a, m.R0 * lt.b, m.R0 * lt.c};
      Vec3 slo, shi;
      detail::sweptTriangleBox(m, rotEnd, q, 1.0, slo, shi);
      for (std::size_t i = 0; i < bt.size(); ++i) {
        if (!boxesOverlap(slo, shi, bt[i].lo, bt[i].hi)) continue;
        ++out.trianglePairs;
        const detail::PairContact c = detail::pairFirstContact(m, p, q, bt[i].t, best);
        if (!c.hit || (out.hit && c.s >= best)) continue;
        best = c.s;
        out.hit = true;
        out.t = std::min(1.0, (seg + c.s) / plan.segments);
        out.point = c.point;
        out.normal = c.normal;
        out.feature = c.feature;
        out.boneSlot = static_cast<std::uint32_t>(i);
        out.reamerTriangle = static_cast<std::uint32_t>(j);
      }
    }
  }
  return out;
}

PenetrationResult bruteForceAxialPenetration(const TriangleMesh& bone, const ReamerModel& reamer,
                                             const RigidTransform& pose, bool boneClosed) {
  PenetrationResult out;
  const PoseFrame frame(pose);
  const Vec3 u = normalized(frame.R * Vec3{0, 0, 1});
  out.backOut = -u;
  if (!bruteForceOverlap(bone, reamer, pose, boneClosed).overlap) return out;
  out.penetrating = true;
  const std::vector<BoxedTri> rt = boxed(reamer.solid(), &frame);
  const std::vector<BoxedTri> bt = boxed(bone, nullptr);
  std::size_t out_pairs = 0;
  // Every pair whose boxes meet somewhere behind the pose, with its touch interval computed on first use.
  struct Candidate {
    std::size_t r, b;
    double dlo, dhi;
    bool computed;
    detail::AxialInterval iv;
  };
  std::vector<Candidate> candidates;
  for (std::size_t i = 0; i < rt.size(); ++i)
    for (std::size_t j = 0; j < bt.size(); ++j) {
      double dlo, dhi;
      if (detail::axialBoxInterval(rt[i].lo, rt[i].hi, bt[j].lo, bt[j].hi, u, dlo, dhi) && dhi >= -1.0)
        candidates.push_back({i, j, dlo, dhi, false, {}});
    }
  auto collect = [&](double wlo, double whi, std::vector<detail::AxialInterval>& out) {
    for (Candidate& c : candidates) {
      if (c.dhi < wlo || c.dlo > whi) continue;
      if (!c.computed) {
        const Vec3 x[3] = {rt[c.r].t.a, rt[c.r].t.b, rt[c.r].t.c};
        c.iv = detail::axialInterval(x, bt[c.b].t, u);
        c.computed = true;
        ++out_pairs;
      }
      if (c.iv.valid && c.iv.hi >= wlo && c.iv.lo <= whi) out.push_back(c.iv);
    }
  };
  const double tol = kChainToleranceRelative * std::max(1.0, reamer.radius());
  const double reach = computeBounds(bone).diagonal() + 2 * reamer.radius();
  bool touching = false;
  for (std::size_t i = 0; i < rt.size() && !touching; ++i)
    for (const BoxedTri& b : bt)
      if (boxesOverlap(rt[i].lo, rt[i].hi, b.lo, b.hi) &&
          trianglesIntersect(rt[i].t.a, rt[i].t.b, rt[i].t.c, b.t.a, b.t.b, b.t.c)) {
        touching = true;
        break;
      }
  const detail::AxialRun run = detail::axialRun(collect, tol, reach, std::max(0.25, 0.02 * reamer.radius()), touching);
  out.enclosed = run.enclosed;
  out.depthMm = run.depth;
  out.lastContact = run.point;
  out.trianglePairs = out_pairs;
  return out;
}

}  // namespace reamsim
