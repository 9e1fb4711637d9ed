#include "reamsim/collision/PenetrationQuery.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "AxialEvents.h"
#include "PoseFrame.h"
#include "SurfaceTouch.h"
#include "reamsim/collision/OverlapQuery.h"
#include "reamsim/collision/TriangleGeometry.h"

namespace reamsim {

namespace {

using detail::AxialInterval;
using detail::PoseFrame;

struct AxialScratch {
  std::vector<std::uint32_t> nodeStamp, triStamp;
  std::vector<Vec3> lo, hi;
  std::vector<std::array<Vec3, 3>> tri;
  std::vector<Vec3> tlo, thi;
  std::uint32_t stamp = 0;
  void begin(std::size_t nodes, std::size_t tris) {
    if (nodeStamp.size() < nodes) { nodeStamp.resize(nodes, 0); lo.resize(nodes); hi.resize(nodes); }
    if (triStamp.size() < tris) { triStamp.resize(tris, 0); tri.resize(tris); tlo.resize(tris); thi.resize(tris); }
    if (++stamp == 0) {
      std::fill(nodeStamp.begin(), nodeStamp.end(), 0);
      std::fill(triStamp.begin(), triStamp.end(), 0);
      stamp = 1;
    }
  }
};
thread_local AxialScratch tlsAxial;

// The run of touch intervals as a sweep in back-out distance: (bone node, reamer node) pairs come out of a
// min-heap in order of where their box interval starts, triangle pairs in order of where their exact
// interval starts; the run grows while the next item starts before its end (+ tolerance). Nothing that starts
// after the run ends is ever evaluated, and every pair is evaluated once.
class AxialSweep {
 public:
  AxialSweep(const TriangleBvh& bone, const ReamerModel& reamer, const PoseFrame& frame, const Vec3& u, double tol)
      : bone_(bone), rtree_(reamer.solidBvh()), frame_(frame), u_(u), tol_(tol), sc_(tlsAxial) {
    sc_.begin(rtree_.nodes().size(), rtree_.slotCapacity());
  }

  std::size_t pairs = 0;

  // touching: the surfaces touch at 0 (the run starts there); otherwise it starts at the first contact.
  // Returns false if no contact at d >= 0 exists.
  bool run(bool touching, double& depth, Vec3& point) {
    started_ = touching;
    end_ = 0;
    heap_.clear();
    pushNodes(bone_.root(), rtree_.root());
    while (!heap_.empty()) {
      const Item top = heap_.front();
      if (started_ && top.key > end_ + tol_) break;
      std::pop_heap(heap_.begin(), heap_.end());
      heap_.pop_back();
      if (top.hi < floor() - tol_) continue;  // ends before the run's current end
      if (top.interval) {
        if (!started_) {
          started_ = true;
          end_ = std::max(top.key, 0.0);
        }
        if (top.key <= end_ + tol_ && top.hi > end_) {
          end_ = top.hi;
          point_ = top.point;
        }
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
    bool operator<(const Item& o) const { return key > o.key; }  // min-heap
  };
  double floor() const { return started_ ? end_ : 0.0; }
  void push(const Item& it) {
    heap_.push_back(it);
    std::push_heap(heap_.begin(), heap_.end());
  }

  void worldBox(std::int32_t r) {
    if (sc_.nodeStamp[r] == sc_.stamp) return;
    frame_.localBoxToWorld(rtree_.nodes()[r].lo, rtree_.nodes()[r].hi, sc_.lo[r], sc_.hi[r]);
    sc_.nodeStamp[r] = sc_.stamp;
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
    push({dlo, dhi, b, r, false, {}});
  }

  void expand(std::int32_t b, std::int32_t r) {
    const BvhNode& B = bone_.nodes()[b];
    const BvhNode& R = rtree_.nodes()[r];
    if (!B.isLeaf() || !R.isLeaf()) {
      const double sb = (B.hi.x - B.lo.x) + (B.hi.y - B.lo.y) + (B.hi.z - B.lo.z);
      const double sr = (R.hi.x - R.lo.x) + (R.hi.y - R.lo.y) + (R.hi.z - R.lo.z);
      if (R.isLeaf() || (!B.isLeaf() && sb >= sr)) {
        bone_.prefetchNode(B.left, false);  // both read below, behind an early return: overlap the misses
        bone_.prefetchNode(B.right, false);
        pushNodes(B.left, r);
        pushNodes(B.right, r);
      } else {
        pushNodes(b, R.left);
        pushNodes(b, R.right);
      }
      return;
    }
    const std::uint32_t* bs = bone_.leafSlots(B);
    const std::uint32_t* rs = rtree_.leafSlots(R);
    for (int j = 0; j < R.count; ++j) {
      worldTri(rs[j]);
      const auto& xt = sc_.tri[rs[j]];
      const Vec3 x[3] = {xt[0], xt[1], xt[2]};
      for (int i = 0; i < B.count; ++i) {
        const BvhTriangle& bt = bone_.triangle(bs[i]);
        Vec3 blo, bhi;
        TriangleBvh::paddedBox(bt, blo, bhi);
        double dlo, dhi;
        if (!detail::axialBoxInterval(sc_.tlo[rs[j]], sc_.thi[rs[j]], blo, bhi, u_, dlo, dhi) || dhi < floor() - tol_)
          continue;
        if (!detail::shadowsOverlap(x, bt, u_)) continue;
        ++pairs;
        const AxialInterval iv = detail::axialInterval(x, bt, u_);
        if (!iv.valid || iv.hi < floor() - tol_) continue;
        push({iv.lo, iv.hi, static_cast<std::int32_t>(bs[i]), static_cast<std::int32_t>(rs[j]), true, iv.hiPoint});
      }
    }
  }

  const TriangleBvh& bone_;
  const TriangleBvh& rtree_;
  const PoseFrame& frame_;
  Vec3 u_;
  double tol_;
  AxialScratch& sc_;
  std::vector<Item> heap_;
  bool started_ = false;
  double end_ = 0;
  Vec3 point_;
};

}  // namespace

PenetrationResult queryAxialPenetration(const TriangleBvh& bone, const ReamerModel& reamer, const RigidTransform& pose,
                                        bool boneClosed) {
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
