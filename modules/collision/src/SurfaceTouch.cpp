#include "SurfaceTouch.h"

#include <utility>
#include <vector>

#include "reamsim/collision/TriangleGeometry.h"

namespace reamsim::detail {

bool surfacesTouch(const TriangleBvh& bone, const ReamerModel& reamer, const RigidTransform& pose, TouchPair* where) {
  if (bone.empty()) return false;
  return faceTouchesBone(bone, reamer, pose, where) || restTouchesBone(bone, reamer, pose, where);
}

bool restTouchesBone(const TriangleBvh& bone, const ReamerModel& reamer, const RigidTransform& pose, TouchPair* where) {
  if (bone.empty()) return false;
  return RestTouchSearch(bone, reamer, pose).touchesSubtree(bone.root(), where);
}

bool RestTouchSearch::touchesSubtree(std::int32_t node, TouchPair* where) {
  const TriangleBvh& bone = bone_;
  const ReamerModel& reamer = reamer_;
  const TriangleBvh& rest = reamer.restBvh();
  if (rest.empty()) return false;
  PairBoxes& boxes = boxes_;
  boxes.resume();
  std::vector<std::pair<std::int32_t, std::int32_t>>& stack = stack_;
  stack.assign(1, {node, rest.root()});
  const auto& bn = bone.nodes();
  const auto& rn = rest.nodes();
  while (!stack.empty()) {
    const auto [b, r] = stack.back();
    stack.pop_back();
    if (!boxes.mayOverlap(b, r)) continue;
    const BvhNode& B = bn[b];
    const BvhNode& R = rn[r];
    if (B.isLeaf() && R.isLeaf()) {
      const BvhTriangle* bts = bone.leafTriangles(B);
      const std::uint32_t* rs = rest.leafSlots(R);
      for (int j = 0; j < R.count; ++j) {
        const Vec3 *rlo, *rhi;
        const BvhTriangle& rt = boxes.reamerTriangle(rs[j], rlo, rhi);
        for (int i = 0; i < B.count; ++i) {
          const BvhTriangle& bt = bts[i];
          Vec3 blo, bhi;
          TriangleBvh::paddedBox(bt, blo, bhi);
          if (!boxesOverlap(blo, bhi, *rlo, *rhi) || !trianglesIntersect(rt.a, rt.b, rt.c, bt.a, bt.b, bt.c)) continue;
          if (where) {
            where->boneSlot = bone.leafSlots(B)[i];
            where->reamerTriangle = reamer.restTriangles()[rs[j]];
            where->point = closestTriangleTriangle(rt.a, rt.b, rt.c, bt.a, bt.b, bt.c).onB;
          }
          return true;
        }
      }
      continue;
    }
    const bool splitBone = R.isLeaf() || (!B.isLeaf() && (B.hi.x - B.lo.x) + (B.hi.y - B.lo.y) + (B.hi.z - B.lo.z) >=
                                                            (R.hi.x - R.lo.x) + (R.hi.y - R.lo.y) + (R.hi.z - R.lo.z));
    if (splitBone) {
      stack.push_back({B.left, r});
      stack.push_back({B.right, r});
    } else {
      stack.push_back({b, R.left});
      stack.push_back({b, R.right});
    }
  }
  return false;
}

}  // namespace reamsim::detail
