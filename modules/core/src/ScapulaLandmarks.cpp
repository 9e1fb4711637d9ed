#include "reamsim/core/ScapulaLandmarks.h"

#include <cctype>
#include <string>

namespace reamsim {

const char* toString(BodySide side) {
  switch (side) {
    case BodySide::Right: return "right";
    case BodySide::Left: return "left";
    case BodySide::Unspecified: break;
  }
  return "unspecified";
}

std::optional<BodySide> parseBodySide(std::string_view text) {
  std::string lower;
  for (char c : text) lower += char(std::tolower(static_cast<unsigned char>(c)));
  for (BodySide side : {BodySide::Unspecified, BodySide::Right, BodySide::Left})
    if (lower == toString(side)) return side;
  return std::nullopt;
}

const char* displayName(ScapulaLandmark which) {
  switch (which) {
    case ScapulaLandmark::GlenoidCentre: return "glenoid centre";
    case ScapulaLandmark::TrigonumScapulae: return "trigonum scapulae";
    case ScapulaLandmark::InferiorAngle: return "inferior angle";
  }
  return "landmark";
}

const char* jsonKey(ScapulaLandmark which) {
  switch (which) {
    case ScapulaLandmark::GlenoidCentre: return "glenoid_centre";
    case ScapulaLandmark::TrigonumScapulae: return "trigonum_scapulae";
    case ScapulaLandmark::InferiorAngle: return "inferior_angle";
  }
  return "landmark";
}

bool operator==(const ScapulaLandmarks& a, const ScapulaLandmarks& b) {
  if (a.side != b.side) return false;
  for (std::size_t i = 0; i < a.points.size(); ++i) {
    if (a.points[i].has_value() != b.points[i].has_value()) return false;
    if (a.points[i] && !(*a.points[i] == *b.points[i])) return false;
  }
  return true;
}

}  // namespace reamsim
