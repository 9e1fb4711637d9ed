#pragma once
// The scapular landmarks of a bone, as the surgeon placed them (or a file gave them): the glenoid
// centre, the trigonum scapulae (where the spine of the scapula meets the medial border) and the
// inferior angle, with the body side. They define the scapular frame in which the reaming axis's version
// and inclination are measured (reamsim/ream/ScapularFrame.h; docs/PLANNING.md). A BoneNode keeps its
// bone's landmarks (they go wherever its content goes: BoneContent).
#include <array>
#include <optional>
#include <string_view>

#include "reamsim/mesh/Vec3.h"

namespace reamsim {

enum class BodySide { Unspecified, Right, Left };
const char* toString(BodySide side);  // "unspecified", "right", "left"
std::optional<BodySide> parseBodySide(std::string_view text);  // case-insensitive; nullopt otherwise

enum class ScapulaLandmark { GlenoidCentre = 0, TrigonumScapulae = 1, InferiorAngle = 2 };
inline constexpr std::array<ScapulaLandmark, 3> kScapulaLandmarks = {
    ScapulaLandmark::GlenoidCentre, ScapulaLandmark::TrigonumScapulae, ScapulaLandmark::InferiorAngle};
const char* displayName(ScapulaLandmark which);  // "glenoid centre", "trigonum scapulae", "inferior angle"
const char* jsonKey(ScapulaLandmark which);      // "glenoid_centre", "trigonum_scapulae", "inferior_angle"

struct ScapulaLandmarks {
  std::array<std::optional<Vec3>, 3> points;  // indexed by ScapulaLandmark
  BodySide side = BodySide::Unspecified;

  const std::optional<Vec3>& operator[](ScapulaLandmark which) const { return points[std::size_t(which)]; }
  std::optional<Vec3>& operator[](ScapulaLandmark which) { return points[std::size_t(which)]; }
  bool complete() const { return points[0] && points[1] && points[2] && side != BodySide::Unspecified; }
  friend bool operator==(const ScapulaLandmarks& a, const ScapulaLandmarks& b);
};

}  // namespace reamsim
