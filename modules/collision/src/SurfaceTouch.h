#pragma once
// Internal: do the posed reamer surface and the bone surface touch (closed triangles, touching counts)?
// The cutting face is searched first through its thin region (DistanceQuery.cpp), then the body and back
// through a plain two-frame BVH-vs-BVH traversal. First hit wins. Each half is also callable alone.
#include <cstdint>
#include <utility>
#include <vector>

#include "PairBoxes.h"
#include "PoseFrame.h"
#include "reamsim/collision/ReamerModel.h"
#include "reamsim/collision/TriangleBvh.h"
#include "reamsim/core/Pose.h"

namespace reamsim::detail {

struct TouchPair {
  std::uint32_t boneSlot = 0;
  std::uint32_t reamerTriangle = 0;  // solid triangle index
  Vec3 point;                        // a common point, bone coordinates
};

// `nodesOpened`, when given, is increased by the bone nodes the search opened.
bool faceTouchesBone(const TriangleBvh& bone, const ReamerModel& reamer, const RigidTransform& pose, TouchPair* where,
                     std::size_t* nodesOpened = nullptr);
// The body and back alone.
bool restTouchesBone(const TriangleBvh& bone, const ReamerModel& reamer, const RigidTransform& pose, TouchPair* where);
bool surfacesTouch(const TriangleBvh& bone, const ReamerModel& reamer, const RigidTransform& pose, TouchPair* where);
// The body and back against bone subtrees one at a time, at one pose (first contact asks it of each bone leaf
// its sweep finds the ideal solid reaching at the start, FirstContact.cpp). One object serves all of a
// query's subtrees, so the reamer's boxes and triangles mapped to world are computed once per query, not
// once per leaf (the rest-touching motions of the collision bench at 405k: median 72 -> 60 us).
class RestTouchSearch {
 public:
  RestTouchSearch(const TriangleBvh& bone, const ReamerModel& reamer, const RigidTransform& pose)
      : bone_(bone), reamer_(reamer), frame_(pose), boxes_(bone, reamer.restBvh(), frame_) {}
  RestTouchSearch(const RestTouchSearch&) = delete;  // boxes_ refers to frame_
  RestTouchSearch& operator=(const RestTouchSearch&) = delete;
  bool touchesSubtree(std::int32_t node, TouchPair* where);

 private:
  const TriangleBvh& bone_;
  const ReamerModel& reamer_;
  PoseFrame frame_;
  PairBoxes boxes_;
  std::vector<std::pair<std::int32_t, std::int32_t>> stack_;
};

}  // namespace reamsim::detail
