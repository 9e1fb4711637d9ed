#pragma once
// A reamer in the scene: its spec, its current pose and the cutting volume built from the spec.
// The cutting volume is produced elsewhere (tools module) and cached here in reamer-local
// coordinates (tip at origin, feed along +Z); changing the spec drops it because it no longer fits.
#include <memory>
#include <optional>
#include <utility>

#include "reamsim/core/Node.h"
#include "reamsim/core/Pose.h"
#include "reamsim/core/ReamerSpec.h"
#include "reamsim/mesh/TriangleMesh.h"

namespace reamsim {

class ReamerNode : public Node {
 public:
  static constexpr NodeKind kKind = NodeKind::Reamer;
  explicit ReamerNode(std::string name = {}, ReamerSpec spec = {}) : Node(std::move(name)), spec_(std::move(spec)) {}
  NodeKind kind() const override { return kKind; }

  const ReamerSpec& spec() const { return spec_; }
  void setSpec(ReamerSpec spec);  // also clears the cached cutting volume

  const Pose& pose() const { return pose_; }
  void setPose(const Pose& pose);
  RigidTransform transform() const { return toTransform(pose_); }

  // A pose asked for from outside the reaming loop (a planning panel, later an input device): whoever runs
  // the loop takes it on the modification it reports and places the reamer there as its own move, so the
  // asker needs no handle on the loop. nullopt when none waits. take...() does not report a modification.
  // `clearOfBone`: where the reamer would cut the bone there, the loop places it out along its axis, as near
  // as it is clear (Aim: a placement that cut the glenoid rim surprised; ClearPlacement.h).
  struct PlacementRequest {
    Pose pose;
    bool clearOfBone = false;
  };
  const std::optional<PlacementRequest>& placementRequest() const { return placementRequest_; }
  void requestPlacement(const Pose& pose, bool clearOfBone = false);
  std::optional<PlacementRequest> takePlacementRequest() { return std::exchange(placementRequest_, std::nullopt); }

  // Null until set; shared so the renderer and the cutting engine can hold it without copies.
  const std::shared_ptr<const TriangleMesh>& cuttingVolume() const { return cuttingVolume_; }
  void setCuttingVolume(std::shared_ptr<const TriangleMesh> mesh);

 private:
  ReamerSpec spec_;
  Pose pose_;
  std::optional<PlacementRequest> placementRequest_;
  std::shared_ptr<const TriangleMesh> cuttingVolume_;
};

}  // namespace reamsim
