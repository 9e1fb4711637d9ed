#pragma once
// The scapular landmarks of one bone, as the surgeon picked them (or a file gave them): the glenoid
// centre, the trigonum scapulae (where the spine of the scapula meets the medial border) and the
// inferior angle, with the body side. They define the scapular frame in which the reaming axis's version
// and inclination are measured (reamsim/ream/ScapularFrame.h; docs/PLANNING.md).
//
// A view places a landmark when asked: a panel sets pickRequest(), the view's next click on the bone sets
// that landmark and clears the request (the MRML interaction-node idea: the request is in the document,
// so the panel needs no handle on the view).
#include <array>
#include <optional>
#include <string_view>

#include "reamsim/core/Node.h"
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

class LandmarksNode : public Node {
 public:
  static constexpr NodeKind kKind = NodeKind::Landmarks;
  explicit LandmarksNode(std::string name = {}) : Node(std::move(name)) {}
  NodeKind kind() const override { return kKind; }

  // The bone the points lie on (its coordinates); invalid when none.
  NodeId boneId() const { return boneId_; }
  void setBoneId(NodeId id);

  const ScapulaLandmarks& landmarks() const { return landmarks_; }
  void setLandmarks(const ScapulaLandmarks& landmarks);  // also clears a pick request
  void setLandmark(ScapulaLandmark which, const std::optional<Vec3>& point);
  void setSide(BodySide side);

  // Which landmark the view's next click on the bone places; nullopt when none is asked for.
  const std::optional<ScapulaLandmark>& pickRequest() const { return pickRequest_; }
  void setPickRequest(std::optional<ScapulaLandmark> which);

 private:
  NodeId boneId_;
  ScapulaLandmarks landmarks_;
  std::optional<ScapulaLandmark> pickRequest_;
};

}  // namespace reamsim
