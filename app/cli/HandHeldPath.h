#pragma once
// A recorded-style set of poses for `bench collision`: what a hand-held reamer (or a 6-DoF device) sends at
// 1 kHz while a surgeon brings it to the bone, presses, holds and backs off. Unlike the bench's random poses,
// consecutive queries are a tick apart in one place, as in a haptic loop (the caches stay warm).
#include <cstdint>
#include <vector>

#include "reamsim/collision/BoneCollider.h"
#include "reamsim/core/Pose.h"

namespace reamsim::cli {

struct HandHeldTick {
  RigidTransform from, to;  // the pose one tick before and this tick's
};

struct HandHeldPathOptions {
  int approaches = 8;           // each from its own direction, up to maxTiltDeg off the site's normal
  double maxTiltDeg = 15;
  double maxAimOffsetMm = 2;    // each approach aims within ± this of the site along two axes across its normal
  double startGapMm = 3;        // the approach starts this far (along its axis) before the first contact
  double pressMm = 0.5;         // and goes this far beyond it (no cut is made: the reamer sinks in)
  double feedMmPerTick = 0.02;  // 20 mm/s at 1 kHz
  int holdTicks = 100;          // held at the deepest point, with the hand's tremor
  double tremorMm = 0.05;       // physiological tremor: ~0.05 mm and ~0.1 degree at 5-10 Hz
  double tremorDeg = 0.1;
  std::uint64_t seed = 1;
};

// The ticks of all approaches in order. An approach whose straight feed meets no bone is left out.
std::vector<HandHeldTick> handHeldPath(const BoneCollider& bone, const ReamerModel& reamer, const Vec3& sitePoint,
                                       const Vec3& siteOutward, const HandHeldPathOptions& options = {});

}  // namespace reamsim::cli
