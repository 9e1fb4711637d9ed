#include "reamsim/ream/Approach.h"

#include <cmath>
#include <stdexcept>

#include "reamsim/collision/BoneCollider.h"

namespace reamsim {
std::optional<double> advanceToContactMm(const BoneState& bone, const TriangleMesh& cuttingVolumeLocal,
                                         const Pose& start, double maxMm, const ReamerSpec* spec) {
  if (!(maxMm > 0) || !std::isfinite(maxMm)) throw std::invalid_argument("advanceToContactMm: maxMm must be > 0");
  if (bone.empty()) return std::nullopt;
  const BoneCollider collider(bone);
  const ReamerModel reamer = ReamerModel::fromCuttingVolume(cuttingVolumeLocal, spec);
  const FirstContactResult r =
      collider.firstContact(reamer, toTransform(start), toTransform(advancedAlongAxis(start, maxMm)));
  if (!r.hit) return std::nullopt;
  return r.t * maxMm;
}

std::vector<Pose> reamToDepthPoses(const Pose& start, double approachMm, double depthMm, double stepMm) {
  std::vector<Pose> poses;
  if (!(approachMm >= 0) || !(depthMm > 0) || !(stepMm > 0)) return poses;
  if (approachMm > 0) poses.push_back(advancedAlongAxis(start, approachMm));
  const int n = static_cast<int>(std::ceil(depthMm / stepMm - 1e-9));
  for (int i = 1; i <= n; ++i) poses.push_back(advancedAlongAxis(start, approachMm + std::min(depthMm, i * stepMm)));
  return poses;
}

}  // namespace reamsim
