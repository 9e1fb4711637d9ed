#pragma once
// How far the reamer can advance along its axis before its cutting volume first touches the bone: the start
// of "ream to depth" (depth is measured from the first contact). Exact first contact on a BVH of the bone
// (collision query 3); builds the hierarchy, so it belongs on a worker thread for big bones.
#include <optional>

#include "reamsim/core/BoneState.h"
#include "reamsim/core/Pose.h"
#include "reamsim/core/ReamerSpec.h"
#include "reamsim/mesh/TriangleMesh.h"

namespace reamsim {

// 0 when the reamer already touches or enters the bone; nullopt when nothing is met within maxMm.
// `spec`: what the cutting volume was built from, when known (ReamerModel::fromCuttingVolume).
std::optional<double> advanceToContactMm(const BoneState& bone, const TriangleMesh& cuttingVolumeLocal,
                                         const Pose& start, double maxMm, const ReamerSpec* spec = nullptr);

// Feed poses for "ream to depth": a single move to the first contact (nothing is in between), then feed
// steps of at most stepMm down to depthMm below it. Empty when approachMm is negative or depthMm <= 0.
std::vector<Pose> reamToDepthPoses(const Pose& start, double approachMm, double depthMm, double stepMm);

}  // namespace reamsim
