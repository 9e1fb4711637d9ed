#pragma once
// Where the reamer goes over a bone that has just come in (file, CT import), shared by the ways in.
#include "reamsim/core/Pose.h"
#include "reamsim/mesh/Bounds.h"

namespace reamsim::ui {

// The reamer fitted when a bone arrives and none is set yet.
inline constexpr const char* kDefaultReamerPreset = "glenoid-36-R30";

// Above the bone's lateral (+Z) side, feeding along -Z.
inline Pose startPoseFor(const Bounds& b) {
  const Vec3 c = b.center();
  return Pose{{c.x, c.y, b.max.z + 10.0}, {0, 0, -1}, 0};
}

}  // namespace reamsim::ui
