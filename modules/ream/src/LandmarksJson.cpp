// Landmark files: {"side": "right", "glenoid_centre": [x, y, z], "trigonum_scapulae": ..., "inferior_angle": ...}
// (docs/PLANNING.md). A point may be absent or null: a half-picked set is saved and read back as it is.
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "reamsim/core/BoneNode.h"
#include "reamsim/core/Document.h"
#include "reamsim/mesh/MeshError.h"
#include "reamsim/ream/ScapularFrame.h"

namespace reamsim {
namespace {

using nlohmann::json;
constexpr double kMaxCoordinateMm = 1e6;  // as plans: a kilometre is beyond any bone

Vec3 readPoint(const json& j, const std::string& key, const std::string& source) {
  if (!j.is_array() || j.size() != 3) throw InputError(source, "\"" + key + "\" must be an array of 3 numbers or null");
  Vec3 v;
  for (int i = 0; i < 3; ++i) {
    if (!j[i].is_number()) throw InputError(source, "\"" + key + "\" must be an array of 3 numbers or null");
    v[i] = j[i].get<double>();
    if (!std::isfinite(v[i]) || std::abs(v[i]) > kMaxCoordinateMm)
      throw InputError(source, "\"" + key + "\" has a value that is not finite or beyond ±1e6 mm");
  }
  return v;
}

}  // namespace

bool operator==(const BonePlanning& a, const BonePlanning& b) {
  if (!(a.landmarks == b.landmarks) || a.plannedAxis.has_value() != b.plannedAxis.has_value()) return false;
  return !a.plannedAxis || (a.plannedAxis->tip == b.plannedAxis->tip && a.plannedAxis->axis == b.plannedAxis->axis &&
                            a.plannedAxis->rollDeg == b.plannedAxis->rollDeg);
}

BonePlanning planningOf(const BoneNode& bone) { return {bone.landmarks(), bone.plannedAxis()}; }

void applyPlanning(BoneNode& bone, const BonePlanning& planning) {
  std::optional<Document::BatchScope> batch;
  if (bone.document()) batch.emplace(*bone.document());
  bone.setLandmarks(planning.landmarks);
  bone.setPlannedAxis(planning.plannedAxis);
}

BonePlanning parsePlanningJson(const std::string& text, const std::string& source) {
  json j;
  try {
    j = json::parse(text);
  } catch (const json::exception& e) {  // parse_error, and out_of_range for a number beyond double (fuzzing)
    throw InputError(source, std::string("not valid JSON: ") + e.what());
  }
  if (!j.is_object()) throw InputError(source, "a landmark file must be a JSON object");
  // A misspelt key must not read as a landmark left unplaced.
  for (const auto& [key, value] : j.items()) {
    bool known = key == "side" || key == "method" || key == "planned_axis";
    for (ScapulaLandmark which : kScapulaLandmarks) known = known || key == jsonKey(which);
    if (!known)
      throw InputError(source, "unknown key \"" + key + "\" (a landmark file has \"side\", \"glenoid_centre\", "
                               "\"trigonum_scapulae\", \"inferior_angle\", \"planned_axis\" and \"method\")");
  }
  BonePlanning planning;
  ScapulaLandmarks& out = planning.landmarks;
  if (j.contains("side")) {
    if (!j["side"].is_string()) throw InputError(source, "\"side\" must be \"right\", \"left\" or \"unspecified\"");
    const std::optional<BodySide> side = parseBodySide(j["side"].get<std::string>());
    if (!side) throw InputError(source, "\"side\" must be \"right\", \"left\" or \"unspecified\", not \"" +
                                            j["side"].get<std::string>() + "\"");
    out.side = *side;
  }
  for (ScapulaLandmark which : kScapulaLandmarks) {
    const std::string key = jsonKey(which);
    if (!j.contains(key) || j[key].is_null()) continue;
    out[which] = readPoint(j[key], key, source);
  }
  if (j.contains("planned_axis") && !j["planned_axis"].is_null()) {
    const json& a = j["planned_axis"];
    if (!a.is_object() || !a.contains("tip") || !a.contains("axis"))
      throw InputError(source, "\"planned_axis\" must be an object with \"tip\" and \"axis\"");
    Pose axis;
    axis.tip = readPoint(a["tip"], "planned_axis.tip", source);
    const Vec3 direction = readPoint(a["axis"], "planned_axis.axis", source);
    if (!(norm(direction) > 1e-9)) throw InputError(source, "\"planned_axis.axis\" must not be zero");
    axis.axis = normalized(direction);
    planning.plannedAxis = axis;
  }
  return planning;
}

ScapulaLandmarks parseLandmarksJson(const std::string& text, const std::string& source) {
  return parsePlanningJson(text, source).landmarks;
}

BonePlanning loadPlanning(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, "cannot open the landmark file");
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw InputError(path, "cannot read the landmark file");
  return parsePlanningJson(text.str(), path);
}

ScapulaLandmarks loadLandmarks(const std::string& path) { return loadPlanning(path).landmarks; }

std::string landmarksToJson(const ScapulaLandmarks& landmarks, const std::string& method) {
  return planningToJson({landmarks, std::nullopt}, method);
}

std::string planningToJson(const BonePlanning& planning, const std::string& method) {
  const ScapulaLandmarks& landmarks = planning.landmarks;
  json j = json::object();
  j["side"] = toString(landmarks.side);
  for (ScapulaLandmark which : kScapulaLandmarks) {
    const std::optional<Vec3>& p = landmarks[which];
    j[jsonKey(which)] = p ? json::array({p->x, p->y, p->z}) : json(nullptr);
  }
  if (const std::optional<Pose>& a = planning.plannedAxis)
    j["planned_axis"] = {{"tip", {a->tip.x, a->tip.y, a->tip.z}}, {"axis", {a->axis.x, a->axis.y, a->axis.z}}};
  if (!method.empty()) j["method"] = method;
  return j.dump(2) + "\n";
}

}  // namespace reamsim
