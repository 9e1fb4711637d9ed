#include "reamsim/collision/PenetrationQuery.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <vector>

#include "AxialEvents.h"
#include "CapBounds.h"
#include "CapShadow.h"
#include "PoseFrame.h"
#include "QueryArguments.h"
#include "SurfaceTouch.h"
#include "reamsim/collision/OverlapQuery.h"
#include "reamsim/collision/TriangleGeometry.h"

namespace reamsim {

namespace {

using detail::AxialInterval;
using detail::CapBounds;
using detail::CapShadow;
using detail::PoseFrame;

struct AxialScratch {
  std::vector<std::uint32_t> nodeStamp, triStamp;
  std::vector<Vec3> lo, hi;  // reamer nodes' world boxes
  std::vector<Vec3> axis;    // reamer nodes' slab axes in the world
  std::vector<double> axisAtTip;  // axis . tip
  std::vector<std::array<Vec3, 3>> tri;
  std::vector<Vec3> tlo, thi;
  std::uint32_t stamp = 0;
  void begin(std::size_t nodes, std::size_t tris) {
    if (nodeStamp.size() < nodes) {
      nodeStamp.resize(nodes, 0);
      lo.resize(nodes);
      hi.resize(nodes);
      axis.resize(nodes);
      axisAtTip.resize(nodes);
    }
    if (triStamp.size() < tris) { triStamp.resize(tris, 0); tri.resize(tris); tlo.resize(tris); thi.resize(tris); }
    if (++stamp == 0) {
      std::fill(nodeStamp.begin(), nodeStamp.end(), 0);
      std::fill(triStamp.begin(), triStamp.end(), 0);
      stamp = 1;
    }
  }
};
thread_local AxialScratch tlsAxial;

// The back-out distances d at which the range [alo, ahi] along an axis, moving by d * rate, overlaps [lo, hi]
// (a node's range and the other node's slab), widened for the rounding of the divisions. False when they
// never overlap.
bool overlapWhileBackingOut(double alo, double ahi, double rate, double lo, double hi, double& dlo, double& dhi) {
  if (std::abs(rate) < 1e-9) {  // the axis runs across the back-out direction: the ranges do not move
    dlo = -std::numeric_limits<double>::infinity();
    dhi = std::numeric_limits<double>::infinity();
    return alo <= hi && ahi >= lo;
  }
  double a = (lo - ahi) / rate, z = (hi - alo) / rate;
  if (a > z) std::swap(a, z);
  const double slack = 1e-12 * (std::abs(a) + std::abs(z)) + 1e-300;
  dlo = a - slack;
  dhi = z + slack;
  return true;
}

// The run of touch intervals as a sweep in back-out distance. The run's end E is the least fixpoint of
// E = max{hi of the intervals with lo <= E + tol} (from 0, or from the first contact backing out): items
// (bone node, reamer node) pairs with their box interval, triangle pairs with their exact interval) wait in
// a min-heap on where they start until the run reaches them, then in a max-heap on where they can end, and
// the one reaching farthest is taken first. So the deepest contact raises the end early and everything
// that cannot pass it is dropped unopened: with the cap pressed into a glenoid every pair starts near 0,
// and a sweep in order of the start opened them all. Every pair is evaluated at most once.
//
// A parametric reamer's cutting face is a height field across the axis (CapShadow): its pairs with a bone
// triangle come as one interval from the bone triangle alone, and bone nodes and triangles are bounded
// against the face without a reamer tree (CapBounds: the ideal sphere's tangent plane from above, and less
// its curvature and the facets' sag from below); the reamer tree paired with the bone is then only the rest
// (body and back). A triangle waits with its bounds and is solved only if the run has not passed it when its
// turn comes. Under a pressed cap the run climbs from 0 through a wide area of bone: with the two-tree pairs'
// loose starts nearly every pair under the cap was reached and opened (~450 exact pairs and ~3,800 node pairs
// per hand-held tick at 405k); with these bounds, tight from both sides, ~13 triangles are solved.
class AxialSweep {
 public:
  AxialSweep(const TriangleBvh& bone, const ReamerModel& reamer, const PoseFrame& frame, const Vec3& u, double tol)
      : bone_(bone),
        cap_(reamer.capShadow()),
        rtree_(cap_ ? reamer.restBvh() : reamer.solidBvh()),
        solid_(reamer.solid()),
        frame_(frame),
        u_(u),
        tol_(tol),
        sc_(tlsAxial) {
    sc_.begin(rtree_.nodes().size(), rtree_.slotCapacity());
    if (cap_) capBounds_.emplace(reamer, frame);
  }

  std::size_t pairs = 0;

  // touching: the surfaces touch at 0 (the run starts there); otherwise it starts at the first contact.
  // Returns false if no contact at d >= 0 exists.
  bool run(bool touching, double& depth, Vec3& point) {
    started_ = touching;
    end_ = 0;
    waiting_.clear();
    reached_.clear();
    if (!rtree_.empty()) pushNodes(bone_.root(), rtree_.root());
    if (cap_) pushCap(bone_.root());
    while (true) {
      if (!started_) {
        // Until the first contact: in order of the start (node keys bound their pairs' starts from below).
        if (waiting_.empty()) break;
        std::pop_heap(waiting_.begin(), waiting_.end(), startsLater);
        const Item top = waiting_.back();
        waiting_.pop_back();
        if (!top.interval) {
          expand(top.b, top.r);
          continue;
        }
        started_ = true;
        end_ = std::max(top.key, 0.0);
        point_ = top.point;
        if (top.hi > end_) end_ = top.hi;
        continue;
      }
      while (!waiting_.empty() && waiting_.front().key <= end_ + tol_) {
        std::pop_heap(waiting_.begin(), waiting_.end(), startsLater);
        reach(waiting_.back());
        waiting_.pop_back();
      }
      if (reached_.empty()) break;  // nothing else starts before the run's end
      std::pop_heap(reached_.begin(), reached_.end(), endsSooner);
      const Item top = reached_.back();
      reached_.pop_back();
      if (top.hi <= end_) {  // the farthest-reaching cannot extend the run: none of them can
        reached_.clear();
        continue;
      }
      if (top.interval) {
        end_ = top.hi;
        point_ = top.point;
        continue;
      }
      expand(top.b, top.r);
    }
    depth = end_;
    point = point_;
    return started_;
  }

 private:
  struct Item {
    double key, hi;
    std::int32_t b, r;
    bool interval;
    Vec3 point;
  };
  static bool startsLater(const Item& a, const Item& b) { return a.key > b.key; }  // min-heap on the start
  static bool endsSooner(const Item& a, const Item& b) { return a.hi < b.hi; }     // max-heap on the end
  double floor() const { return started_ ? end_ : 0.0; }
  void push(const Item& it) {
    if (started_ && it.key <= end_ + tol_) {
      reach(it);
      return;
    }
    waiting_.push_back(it);
    std::push_heap(waiting_.begin(), waiting_.end(), startsLater);
  }
  void reach(const Item& it) {
    if (it.hi <= end_) return;  // cannot extend the run
    reached_.push_back(it);
    std::push_heap(reached_.begin(), reached_.end(), endsSooner);
  }

  void worldBox(std::int32_t r) {
    if (sc_.nodeStamp[r] == sc_.stamp) return;
    frame_.localBoxToWorld(rtree_.nodes()[r].lo, rtree_.nodes()[r].hi, sc_.lo[r], sc_.hi[r]);
    sc_.axis[r] = frame_.R * rtree_.slab(r).axis;
    sc_.axisAtTip[r] = dot(sc_.axis[r], frame_.t);
    sc_.nodeStamp[r] = sc_.stamp;
  }

  // Where backing out can make the pair's triangles meet, from the reamer node's slab: its triangles lie
  // within [lo, hi] along the slab's axis n (reamer frame), and backed out by d a world point x lies at
  // n' . (x - tip) + d n.z along it (n' = R n; the tip moves by -d u and n' . u = n.z). The bone node's box
  // ∩ slab ranges n' . x, so d is confined to where the two ranges overlap. A cap patch is thin along its
  // normal, which is nearly the axis, so this is far tighter than the boxes' interval, which grows with the
  // boxes' thickness along the axis. False if they cannot meet at any d.
  bool slabInterval(std::int32_t b, std::int32_t r, double& dlo, double& dhi) const {
    const BvhSlab& rs = rtree_.slab(r);
    double alo, ahi;
    regionRange(bone_.nodes()[b].lo, bone_.nodes()[b].hi, bone_.slab(b), sc_.axis[r], alo, ahi);
    const double c = sc_.axisAtTip[r];
    const double pad = 1e-12 * (std::abs(c) + std::abs(alo) + std::abs(ahi) + std::abs(rs.lo) + std::abs(rs.hi)) + 1e-300;
    return overlapWhileBackingOut(alo - c - pad, ahi - c + pad, rs.axis.z, rs.lo, rs.hi, dlo, dhi);
  }

  // The same from the bone node's slab: its triangles lie within [lo, hi] along m (world); backed out by d
  // a reamer point p lies at (R^T m) . p + m . tip - d m . u along it.
  bool boneSlabInterval(std::int32_t b, std::int32_t r, double& dlo, double& dhi) const {
    const BvhSlab& bs = bone_.slab(b);
    double plo, phi;
    regionRange(rtree_.nodes()[r].lo, rtree_.nodes()[r].hi, rtree_.slab(r), frame_.Rt * bs.axis, plo, phi);
    const double c = dot(bs.axis, frame_.t);
    const double pad = 1e-12 * (std::abs(c) + std::abs(plo) + std::abs(phi) + std::abs(bs.lo) + std::abs(bs.hi)) + 1e-300;
    return overlapWhileBackingOut(plo + c - pad, phi + c + pad, -dot(bs.axis, u_), bs.lo, bs.hi, dlo, dhi);
  }
  void worldTri(std::uint32_t s) {
    if (sc_.triStamp[s] == sc_.stamp) return;
    const BvhTriangle& t = rtree_.triangle(s);
    sc_.tri[s] = {frame_.toWorld(t.a), frame_.toWorld(t.b), frame_.toWorld(t.c)};
    TriangleBvh::paddedBox({sc_.tri[s][0], sc_.tri[s][1], sc_.tri[s][2]}, sc_.tlo[s], sc_.thi[s]);
    sc_.triStamp[s] = sc_.stamp;
  }

  void pushNodes(std::int32_t b, std::int32_t r) {
    worldBox(r);
    const BvhNode& B = bone_.nodes()[b];
    double dlo, dhi;
    if (!detail::axialBoxInterval(sc_.lo[r], sc_.hi[r], B.lo, B.hi, u_, dlo, dhi) || dhi < floor() - tol_) return;
    double slo, shi;
    if (!slabInterval(b, r, slo, shi)) return;
    dlo = std::max(dlo, slo);
    dhi = std::min(dhi, shi);
    if (!boneSlabInterval(b, r, slo, shi)) return;
    dlo = std::max(dlo, slo);
    dhi = std::min(dhi, shi);
    if (dlo > dhi || dhi < floor() - tol_) return;
    push({dlo, dhi, b, r, false, {}});
  }

  // Whether the two triangles can still touch at some back-out d >= floor, from their planes alone: the
  // moving reamer triangle's plane must pass through the bone triangle, and the bone triangle's plane
  // through the moving reamer triangle. Cheaper than the exact interval, which most pairs under a pressed
  // cap do not need once the run has reached past them.
  bool planesCanMeetBeyond(const Vec3 x[3], const BvhTriangle& bt, double floor) const {
    auto latest = [&](const Vec3& n, double o, double vlo, double vhi, double rate, double& dmax) {
      // The plane n . y = o - d rate (moving) against values [vlo, vhi] that stay: d <= dmax.
      const double pad = 1e-10 * (std::abs(o) + std::abs(vlo) + std::abs(vhi)) + 1e-300;
      if (std::abs(rate) <= 1e-12 * norm(n)) {
        dmax = (o >= vlo - pad && o <= vhi + pad) ? std::numeric_limits<double>::infinity() : -std::numeric_limits<double>::infinity();
        return;
      }
      dmax = (rate > 0 ? o - (vlo - pad) : o - (vhi + pad)) / rate;
      dmax += 1e-12 * std::abs(dmax);
    };
    const Vec3 n = cross(x[1] - x[0], x[2] - x[0]);
    const double b0 = dot(n, bt.a), b1 = dot(n, bt.b), b2 = dot(n, bt.c);
    double dmax;
    latest(n, dot(n, x[0]), std::min({b0, b1, b2}), std::max({b0, b1, b2}), dot(n, u_), dmax);
    if (dmax < floor) return false;
    // The bone's plane m . y = m . a against the reamer's vertices moving by -d u: m . x_i - d (m . u).
    const Vec3 m = cross(bt.b - bt.a, bt.c - bt.a);
    const double x0 = dot(m, x[0]), x1 = dot(m, x[1]), x2 = dot(m, x[2]), mu = dot(m, u_);
    // m . x_i - d mu = m . a  <=>  the plane m . y = m . a + d mu, moving at rate -mu, against the x values.
    latest(m, dot(m, bt.a), std::min({x0, x1, x2}), std::max({x0, x1, x2}), -mu, dmax);
    return dmax >= floor;
  }

  static constexpr std::int32_t kCap = -2;          // an item's reamer side is the whole face (CapShadow)
  static constexpr std::int32_t kCapTriangle = -3;  // ...and its bone side one triangle, bounded, not yet solved

  // The face against a bone node, bounded (CapBounds) without a reamer tree.
  void pushCap(std::int32_t b) {
    const BvhNode& B = bone_.nodes()[b];
    double lo, hi;
    if (!capBounds_->node(B.lo, B.hi, bone_.slab(b), lo, hi) || hi < floor() - tol_) return;
    push({lo, hi, b, kCap, false, {}});
  }

  // A bone triangle's exact interval against the face, once the run has not passed its bound.
  void solveCapTriangle(std::int32_t slot) {
    const BvhTriangle& t = bone_.triangle(static_cast<std::uint32_t>(slot));
    const Vec3 q[3] = {frame_.toLocal(t.a), frame_.toLocal(t.b), frame_.toLocal(t.c)};
    double lo, hi;
    Vec3 point;
    ++pairs;
    if (cap_->interval(q, lo, hi, point) && hi >= floor() - tol_) push({lo, hi, slot, kCap, true, frame_.toWorld(point)});
  }

  void expandCap(std::int32_t b) {
    const BvhNode& B = bone_.nodes()[b];
    if (!B.isLeaf()) {
      bone_.prefetchNode(B.left, true);
      bone_.prefetchNode(B.right, true);
      pushCap(B.left);
      pushCap(B.right);
      return;
    }
    const std::uint32_t* bs = bone_.leafSlots(B);
    const BvhTriangle* bts = bone_.leafTriangles(B);
    for (int i = 0; i < B.count; ++i) {
      const Vec3 q[3] = {frame_.toLocal(bts[i].a), frame_.toLocal(bts[i].b), frame_.toLocal(bts[i].c)};
      const std::int32_t slot = static_cast<std::int32_t>(bs[i]);
      if (CapShadow::steep(q)) {
        // Solved only if the run has not passed it when its turn comes: under a pressed cap most of a leaf's
        // triangles lie well below its deepest one, and their bounds are within the facets' sag.
        double lo, hi;
        capBounds_->triangle(q, lo, hi);
        if (hi >= floor() - tol_) push({lo, hi, slot, kCapTriangle, false, {}});
        continue;
      }
      // Along the axis: its shadow is thin, so it is paired with each face triangle over it.
      const BvhTriangle local{q[0], q[1], q[2]};
      cap_->facesUnder(q, faces_);
      for (std::uint32_t f : faces_) {
        const Triangle& t = solid_.triangles[f];
        const Vec3 x[3] = {solid_.vertices[t[0]], solid_.vertices[t[1]], solid_.vertices[t[2]]};
        ++pairs;
        const AxialInterval iv = detail::axialInterval(x, local, Vec3{0, 0, 1});
        if (!iv.valid || iv.hi < floor() - tol_) continue;
        push({iv.lo, iv.hi, slot, kCap, true, frame_.toWorld(iv.hiPoint)});
      }
    }
  }

  void expand(std::int32_t b, std::int32_t r) {
    if (r == kCap) {
      expandCap(b);
      return;
    }
    if (r == kCapTriangle) {
      solveCapTriangle(b);
      return;
    }
    const BvhNode& B = bone_.nodes()[b];
    const BvhNode& R = rtree_.nodes()[r];
    if (!B.isLeaf() || !R.isLeaf()) {
      const double sb = (B.hi.x - B.lo.x) + (B.hi.y - B.lo.y) + (B.hi.z - B.lo.z);
      const double sr = (R.hi.x - R.lo.x) + (R.hi.y - R.lo.y) + (R.hi.z - R.lo.z);
      if (R.isLeaf() || (!B.isLeaf() && sb >= sr)) {
        bone_.prefetchNode(B.left, true);  // both read below (node and slab), behind early returns: overlap
        bone_.prefetchNode(B.right, true);  // the misses
        pushNodes(B.left, r);
        pushNodes(B.right, r);
      } else {
        pushNodes(b, R.left);
        pushNodes(b, R.right);
      }
      return;
    }
    const std::uint32_t* bs = bone_.leafSlots(B);
    const BvhTriangle* bts = bone_.leafTriangles(B);
    const std::uint32_t* rs = rtree_.leafSlots(R);
    for (int j = 0; j < R.count; ++j) {
      worldTri(rs[j]);
      const auto& xt = sc_.tri[rs[j]];
      const Vec3 x[3] = {xt[0], xt[1], xt[2]};
      for (int i = 0; i < B.count; ++i) {
        const BvhTriangle& bt = bts[i];
        Vec3 blo, bhi;
        TriangleBvh::paddedBox(bt, blo, bhi);
        double dlo, dhi;
        if (!detail::axialBoxInterval(sc_.tlo[rs[j]], sc_.thi[rs[j]], blo, bhi, u_, dlo, dhi) || dhi < floor() - tol_)
          continue;
        if (!planesCanMeetBeyond(x, bt, floor() - tol_)) continue;
        if (!detail::shadowsOverlap(x, bt, u_)) continue;
        ++pairs;
        const AxialInterval iv = detail::axialInterval(x, bt, u_);
        if (!iv.valid || iv.hi < floor() - tol_) continue;
        push({iv.lo, iv.hi, static_cast<std::int32_t>(bs[i]), static_cast<std::int32_t>(rs[j]), true, iv.hiPoint});
      }
    }
  }

  const TriangleBvh& bone_;
  const CapShadow* cap_;
  const TriangleBvh& rtree_;
  const TriangleMesh& solid_;
  std::optional<CapBounds> capBounds_;
  std::vector<std::uint32_t> faces_;
  const PoseFrame& frame_;
  Vec3 u_;
  double tol_;
  AxialScratch& sc_;
  std::vector<Item> waiting_, reached_;
  bool started_ = false;
  double end_ = 0;
  Vec3 point_;
};

}  // namespace

PenetrationResult queryAxialPenetration(const TriangleBvh& bone, const ReamerModel& reamer, const RigidTransform& pose,
                                        bool boneClosed) {
  detail::requireRigidPose(pose, "queryAxialPenetration", "pose");
  PenetrationResult out;
  const PoseFrame frame(pose);
  const Vec3 u = normalized(frame.R * Vec3{0, 0, 1});
  out.backOut = -u;
  if (bone.empty()) return out;
  // Touching at the pose (the run starts at 0), else overlapping without contact (enclosed: the run starts
  // at the first contact backing out), else nothing to back out of.
  const bool touching = detail::surfacesTouch(bone, reamer, pose, nullptr);
  if (!touching && !queryOverlap(bone, reamer, pose, OverlapMode::AnyContact, boneClosed).overlap) return out;
  out.penetrating = true;
  out.enclosed = !touching;
  const double tol = kChainToleranceRelative * std::max(1.0, reamer.radius());
  AxialSweep sweep(bone, reamer, frame, u, tol);
  double depth = 0;
  Vec3 point;
  sweep.run(touching, depth, point);
  out.depthMm = std::max(0.0, depth);
  out.lastContact = point;
  out.trianglePairs = sweep.pairs;
  return out;
}

}  // namespace reamsim
