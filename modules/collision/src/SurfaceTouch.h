#pragma once
// Internal: do the posed reamer surface and the bone surface touch (closed triangles, touching counts)?
// The cutting face is searched first through its thin region (DistanceQuery.cpp), then the body and back
// through a plain two-frame BVH-vs-BVH traversal. First hit wins. Each half is also callable alone.
#include <cstdint>

#include "reamsim/collision/ReamerModel.h"
#include "reamsim/collision/TriangleBvh.h"
#include "reamsim/core/Pose.h"

namespace reamsim::detail {

struct TouchPair {
  std::uint32_t boneSlot = 0;
  std::uint32_t reamerTriangle = 0;  // solid triangle index
  Vec3 point;                        // a common point, bone coordinates
};

bool faceTouchesBone(const TriangleBvh& bone, const ReamerModel& reamer, const RigidTransform& pose, TouchPair* where);
// The body and back alone.
bool restTouchesBone(const TriangleBvh& bone, const ReamerModel& reamer, const RigidTransform& pose, TouchPair* where);
bool surfacesTouch(const TriangleBvh& bone, const ReamerModel& reamer, const RigidTransform& pose, TouchPair* where);
// The body and back against the bone subtree under `node` only (first contact asks it of each bone leaf its
// sweep finds the ideal solid reaching at the start, FirstContact.cpp).
bool restTouchesSubtree(const TriangleBvh& bone, std::int32_t node, const ReamerModel& reamer, const RigidTransform& pose,
                        TouchPair* where);

}  // namespace reamsim::detail
