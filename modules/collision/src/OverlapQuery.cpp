#include "reamsim/collision/OverlapQuery.h"

#include <algorithm>
#include <vector>

#include "PoseFrame.h"
#include "QueryArguments.h"
#include "SurfaceTouch.h"
#include "reamsim/collision/BvhRayCast.h"
#include "reamsim/collision/TriangleGeometry.h"

namespace reamsim {

namespace {

using detail::PoseFrame;

double extentSum(const Vec3& lo, const Vec3& hi) { return (hi.x - lo.x) + (hi.y - lo.y) + (hi.z - lo.z); }

// Bone nodes are visited top-down with the reamer nodes that may still touch them ("active" list, in the
// reamer's local frame where its boxes are tight). A bone node with no active reamer node cannot meet the
// solid's surface, so its box lies entirely inside or outside the solid: one parity test decides for all
// its triangles.
class OverlapSearch {
 public:
  OverlapSearch(const TriangleBvh& bone, const ReamerModel& reamer, const RigidTransform& pose, OverlapMode mode,
                OverlapResult& out)
      : bone_(bone), reamer_(reamer), rtree_(reamer.solidBvh()), frame_(pose), mode_(mode), out_(out) {}

  void run() {
    const auto& rn = rtree_.nodes();
    Vec3 lo, hi;
    frame_.worldBoxToLocal(bone_.nodes()[bone_.root()].lo, bone_.nodes()[bone_.root()].hi, lo, hi);
    if (!boxesOverlap(lo, hi, rn[rtree_.root()].lo, rn[rtree_.root()].hi)) return;
    active_.clear();
    active_.push_back(rtree_.root());
    visit(bone_.root(), 0, 1);
  }

 private:
  bool done() const { return mode_ == OverlapMode::AnyContact && !out_.touchedSlots.empty(); }

  // The parent's active reamer nodes are active_[from, to); this node's are appended after them and dropped
  // on return (one buffer for the whole search, no allocation per node).
  void visit(std::int32_t b, std::size_t from, std::size_t to) {
    if (done()) return;
    const BvhNode& bn = bone_.nodes()[b];
    Vec3 lo, hi;
    frame_.worldBoxToLocal(bn.lo, bn.hi, lo, hi);
    const auto& rn = rtree_.nodes();
    const double size = extentSum(lo, hi);
    const std::size_t mine = active_.size();
    work_.assign(active_.begin() + static_cast<std::ptrdiff_t>(from), active_.begin() + static_cast<std::ptrdiff_t>(to));
    while (!work_.empty()) {
      const std::int32_t r = work_.back();
      work_.pop_back();
      if (!boxesOverlap(lo, hi, rn[r].lo, rn[r].hi)) continue;
      if (!rn[r].isLeaf() && extentSum(rn[r].lo, rn[r].hi) > size) {
        work_.push_back(rn[r].left);
        work_.push_back(rn[r].right);
      } else {
        active_.push_back(r);
      }
    }
    const std::size_t end = active_.size();
    if (end == mine) {
      // Entirely inside or outside: test one vertex of one triangle of this subtree.
      std::uint32_t any = 0;
      for (std::int32_t n = b;; n = bone_.nodes()[n].left)
        if (bone_.nodes()[n].isLeaf()) {
          any = bone_.leafSlots(bone_.nodes()[n])[0];
          break;
        }
      if (boxesOverlap(lo, hi, rn[rtree_.root()].lo, rn[rtree_.root()].hi) &&
          reamer_.containsLocal(frame_.toLocal(bone_.triangle(any).a))) {
        bone_.forEachSlot(b, [&](std::uint32_t s) {
          if (done()) return;
          out_.touchedSlots.push_back(s);
          ++out_.insideFaces;
        });
      }
    } else if (!bn.isLeaf()) {
      visit(bn.left, mine, end);
      visit(bn.right, mine, end);
    } else {
      const std::uint32_t* slots = bone_.leafSlots(bn);
      const BvhTriangle* tris = bone_.leafTriangles(bn);
      for (int i = 0; i < bn.count && !done(); ++i) testTriangle(slots[i], tris[i], mine, end);
    }
    active_.resize(mine);
  }

  void testTriangle(std::uint32_t slot, const BvhTriangle& w, std::size_t from, std::size_t to) {
    const Vec3 a = frame_.toLocal(w.a), b = frame_.toLocal(w.b), c = frame_.toLocal(w.c);
    BvhTriangle local{a, b, c};
    Vec3 lo, hi;
    TriangleBvh::paddedBox(local, lo, hi);
    const auto& rn = rtree_.nodes();
    std::vector<std::int32_t>& stack = stack_;
    stack.assign(active_.begin() + static_cast<std::ptrdiff_t>(from), active_.begin() + static_cast<std::ptrdiff_t>(to));
    while (!stack.empty()) {
      const BvhNode& r = rn[stack.back()];
      stack.pop_back();
      if (!boxesOverlap(lo, hi, r.lo, r.hi)) continue;
      if (!r.isLeaf()) {
        stack.push_back(r.left);
        stack.push_back(r.right);
        continue;
      }
      const std::uint32_t* rs = rtree_.leafSlots(r);
      for (int k = 0; k < r.count; ++k) {
        const BvhTriangle& t = rtree_.triangle(rs[k]);
        Vec3 tlo, thi;
        TriangleBvh::paddedBox(t, tlo, thi);
        if (!boxesOverlap(lo, hi, tlo, thi)) continue;
        if (trianglesIntersect(a, b, c, t.a, t.b, t.c)) {
          out_.touchedSlots.push_back(slot);
          ++out_.surfaceCrossings;
          return;
        }
      }
    }
    // No surface contact: the triangle is entirely inside or outside the solid.
    const auto& root = rn[rtree_.root()];
    if (boxesOverlap(lo, hi, root.lo, root.hi) && reamer_.containsLocal(a)) {
      out_.touchedSlots.push_back(slot);
      ++out_.insideFaces;
    }
  }

  const TriangleBvh& bone_;
  const ReamerModel& reamer_;
  const TriangleBvh& rtree_;
  PoseFrame frame_;
  OverlapMode mode_;
  OverlapResult& out_;
  std::vector<std::int32_t> stack_, work_, active_;
};

}  // namespace

OverlapResult queryOverlap(const TriangleBvh& bone, const ReamerModel& reamer, const RigidTransform& pose,
                           OverlapMode mode, bool boneClosed) {
  detail::requireRigidPose(pose, "queryOverlap", "pose");
  OverlapResult out;
  detail::TouchPair touch;
  if (mode == OverlapMode::AnyContact && detail::surfacesTouch(bone, reamer, pose, &touch)) {
    // Fast path for yes/no: the surfaces touch (the cutting face first, through its thin region).
    out.touchedSlots = {touch.boneSlot};
    out.surfaceCrossings = 1;
    out.overlap = true;
    return out;
  }
  if (!bone.empty()) OverlapSearch(bone, reamer, pose, mode, out).run();
  std::sort(out.touchedSlots.begin(), out.touchedSlots.end());
  if (out.touchedSlots.empty() && boneClosed && !bone.empty()) {
    // No bone face meets the solid, so the bone surface is at least deepClearance() from the deep point:
    // crossing parity from there is reliable.
    out.reamerInsideBone = insideClosedSurface(bone, pose.apply(reamer.deepPoint()));
  }
  out.overlap = !out.touchedSlots.empty() || out.reamerInsideBone;
  return out;
}

}  // namespace reamsim
