#include "reamsim/collision/SyntheticCut.h"

#include <unordered_map>

#include "PoseFrame.h"
#include "reamsim/collision/BvhRayCast.h"

namespace reamsim {

MeshDelta dentDelta(const BoneState& bone, const std::vector<std::uint32_t>& touchedSlots, const ReamerModel& reamer,
                    const RigidTransform& pose) {
  const detail::PoseFrame frame(pose);
  MeshDelta d;
  d.removedTriangles = touchedSlots;
  std::unordered_map<std::uint32_t, std::uint32_t> moved;  // vertex slot -> delta reference
  for (std::uint32_t slot : touchedSlots) {
    Triangle t = bone.triangle(slot);
    for (std::uint32_t& v : t) {
      auto it = moved.find(v);
      if (it == moved.end()) {
        std::uint32_t ref = v;
        const Vec3 local = frame.toLocal(bone.vertex(v));
        if (reamer.containsLocal(local)) {
          // Onto the solid's surface straight ahead: where the material in front of the reamer now begins.
          const auto hit = firstHit(reamer.solidBvh(), local, Vec3{0, 0, 1});
          if (hit) {
            d.addedVertices.push_back(frame.toWorld(hit->point));
            ref = MeshDelta::newVertex(static_cast<std::uint32_t>(d.addedVertices.size() - 1));
          }
        }
        it = moved.emplace(v, ref).first;
      }
      v = it->second;
    }
    d.addedTriangles.push_back(t);
  }
  return d;
}

}  // namespace reamsim
