#pragma once
// Reamer pose: where the tip (apex of the cutting face) is and which way the reamer feeds.
// A reamer is a solid of revolution spinning about its axis, so the roll angle does not change the
// cutting volume; it is kept for display and replay only.
#include <array>

#include "reamsim/mesh/Vec3.h"

namespace reamsim {

struct Pose {
  Vec3 tip{0, 0, 0};      // apex of the cutting face, mm, bone coordinates
  Vec3 axis{0, 0, 1};     // unit feed direction: from the reamer into the bone
  double rollDeg = 0.0;   // rotation about the axis (display only)
};

// Row-major 3x4 rigid transform taking reamer-local coordinates (tip at origin, feed along +Z)
// to bone coordinates.
struct RigidTransform {
  std::array<double, 9> rotation{1, 0, 0, 0, 1, 0, 0, 0, 1};
  Vec3 translation{};

  Vec3 apply(const Vec3& p) const {
    const auto& r = rotation;
    return {r[0] * p.x + r[1] * p.y + r[2] * p.z + translation.x,
            r[3] * p.x + r[4] * p.y + r[5] * p.z + translation.y,
            r[6] * p.x + r[7] * p.y + r[8] * p.z + translation.z};
  }
  Vec3 applyToDirection(const Vec3& d) const {
    const auto& r = rotation;
    return {r[0] * d.x + r[1] * d.y + r[2] * d.z, r[3] * d.x + r[4] * d.y + r[5] * d.z,
            r[6] * d.x + r[7] * d.y + r[8] * d.z};
  }
};

// Local +Z maps to pose.axis, local origin to pose.tip; the local X axis is chosen deterministically
// perpendicular to the axis and then rotated by rollDeg.
RigidTransform toTransform(const Pose& pose);
// Pose moved by `distanceMm` along its own axis.
Pose advancedAlongAxis(const Pose& pose, double distanceMm);

}  // namespace reamsim
