#include <algorithm>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>

#include "reamsim/mesh/MeshError.h"
#include "reamsim/ream/Plan.h"

namespace reamsim {
namespace {

constexpr double kMaxCoordinateMm = 1e6;
using nlohmann::json;

Vec3 readVec3(const json& j, const std::string& where, const std::string& source) {
  if (!j.is_array() || j.size() != 3) throw InputError(source, where + " must be an array of 3 numbers");
  Vec3 v;
  for (int i = 0; i < 3; ++i) {
    if (!j[i].is_number()) throw InputError(source, where + " must be an array of 3 numbers");
    v[i] = j[i].get<double>();
    if (!std::isfinite(v[i])) throw InputError(source, where + " has a non-finite value");
    // Millimetres: a kilometre is beyond any bone and keeps every derived value (poses along a feed, axes) finite.
    if (std::abs(v[i]) > kMaxCoordinateMm)
      throw InputError(source, where + " has a value beyond ±" + std::to_string(int(kMaxCoordinateMm)));
  }
  return v;
}


// What a pose of "poses" may carry besides where it is (docs/PLAN_FORMAT.md).
struct PoseExtras {
  bool placed = false;
  std::string note;
  std::optional<double> timeMs;
};

Pose readPose(const json& j, const std::string& where, const std::string& source, PoseExtras* extras = nullptr) {
  if (!j.is_object()) throw InputError(source, where + " must be an object with \"tip\" and \"axis\"");
  for (const char* key : {"tip", "axis"})
    if (!j.contains(key)) throw InputError(source, where + " lacks \"" + key + "\"");
  Pose p;
  p.tip = readVec3(j["tip"], where + ".tip", source);
  const Vec3 axis = readVec3(j["axis"], where + ".axis", source);
  if (!(norm(axis) >= 1e-9)) throw InputError(source, where + ".axis must not be zero");
  p.axis = normalized(axis);
  if (j.contains("roll_deg")) {
    if (!j["roll_deg"].is_number()) throw InputError(source, where + ".roll_deg must be a number");
    p.rollDeg = j["roll_deg"].get<double>();
    if (!std::isfinite(p.rollDeg)) throw InputError(source, where + ".roll_deg must be finite");
  }
  for (const char* key : {"placed", "note", "t_ms"})
    if (j.contains(key) && !extras)
      throw InputError(source, where + "." + key + " is for the poses of \"poses\"");
  if (j.contains("placed")) {
    if (!j["placed"].is_boolean()) throw InputError(source, where + ".placed must be true or false");
    extras->placed = j["placed"].get<bool>();
  }
  if (j.contains("note")) {
    if (!j["note"].is_string()) throw InputError(source, where + ".note must be a string");
    extras->note = j["note"].get<std::string>();
  }
  if (j.contains("t_ms")) {
    const json& t = j["t_ms"];
    if (!t.is_number() || !std::isfinite(t.get<double>()) || t.get<double>() < 0 || t.get<double>() > kMaxPlanTimeMs)
      throw InputError(source, where + ".t_ms must be a number of milliseconds from 0 to 1e9");
    extras->timeMs = t.get<double>();
  }
  return p;
}

json poseJson(const Pose& p, bool placed = false, const std::string& note = {}, std::optional<double> timeMs = {}) {
  json j = {{"tip", {p.tip.x, p.tip.y, p.tip.z}}, {"axis", {p.axis.x, p.axis.y, p.axis.z}}, {"roll_deg", p.rollDeg}};
  if (placed) j["placed"] = true;
  if (timeMs) j["t_ms"] = *timeMs;
  if (!note.empty()) j["note"] = note;
  return j;
}
}  // namespace

std::vector<Pose> ReamPlan::expandedPoses() const {
  std::vector<Pose> out;
  if (feed)
    for (int i = 1; i <= feed->count; ++i) out.push_back(advancedAlongAxis(feed->start, i * feed->stepMm));
  out.insert(out.end(), poses.begin(), poses.end());
  return out;
}

// Per-pose values of `poses` (empty: none) laid beside expandedPoses(): the feed's steps get T{}.
template <class T>
std::vector<T> ReamPlan::besideExpandedPoses(const std::vector<T>& perPose) const {
  std::vector<T> out((feed ? std::size_t(feed->count) : 0) + poses.size());
  std::copy(perPose.begin(), perPose.begin() + std::min(perPose.size(), poses.size()), out.end() - poses.size());
  return out;
}

std::vector<bool> ReamPlan::expandedPlacements() const {
  std::vector<bool> out(feed ? std::size_t(feed->count) : 0, false);
  const std::size_t first = out.size();
  out.resize(first + poses.size(), false);
  for (std::size_t i : placedPoses)
    if (i < poses.size()) out[first + i] = true;
  return out;
}

std::vector<std::string> ReamPlan::expandedNotes() const { return besideExpandedPoses(poseNotes); }

std::vector<std::optional<double>> ReamPlan::expandedTimesMs() const { return besideExpandedPoses(poseTimesMs); }

bool ReamPlan::hasTimes() const {
  return std::any_of(poseTimesMs.begin(), poseTimesMs.end(), [](const std::optional<double>& t) { return t.has_value(); });
}

double ReamPlan::maxStepMm() const {
  const std::vector<Pose> all = expandedPoses();
  double step = 0;
  Vec3 previous = feed ? feed->start.tip : (all.empty() ? Vec3{} : all.front().tip);
  for (const Pose& p : all) {
    step = std::max(step, norm(p.tip - previous));
    previous = p.tip;
  }
  return step;
}

ReamPlan parsePlan(const std::string& text, const std::string& source) {
  json j;
  try {
    j = json::parse(text);
  } catch (const json::exception& e) {  // parse_error, and out_of_range for a number beyond double (fuzzing)
    throw InputError(source, std::string("not valid JSON: ") + e.what());
  }
  if (!j.is_object()) throw InputError(source, "a plan must be a JSON object");
  ReamPlan plan;
  if (j.contains("reamer")) {
    if (!j["reamer"].is_string()) throw InputError(source, "\"reamer\" must be a preset name or a mesh path");
    plan.reamer = j["reamer"].get<std::string>();
  }
  if (j.contains("description") && j["description"].is_string()) plan.description = j["description"];
  if (j.contains("feed")) {
    const json& f = j["feed"];
    if (!f.is_object()) throw InputError(source, "\"feed\" must be an object");
    for (const char* key : {"start", "step_mm", "count"})
      if (!f.contains(key)) throw InputError(source, std::string("feed lacks \"") + key + "\"");
    FeedSpec feed;
    feed.start = readPose(f["start"], "feed.start", source);
    if (!f["step_mm"].is_number() || !(f["step_mm"].get<double>() > 0) || !std::isfinite(f["step_mm"].get<double>()))
      throw InputError(source, "feed.step_mm must be a positive number");
    feed.stepMm = f["step_mm"];
    if (!f["count"].is_number_integer() || f["count"].get<long>() < 1 || f["count"].get<long>() > 1000000)
      throw InputError(source, "feed.count must be an integer from 1 to 1000000");
    feed.count = f["count"].get<int>();
    if (feed.stepMm * feed.count > kMaxCoordinateMm)
      throw InputError(source, "feed.step_mm × feed.count must not exceed " + std::to_string(int(kMaxCoordinateMm)) + " mm");
    plan.feed = feed;
  }
  if (j.contains("poses")) {
    if (!j["poses"].is_array()) throw InputError(source, "\"poses\" must be an array");
    const std::size_t n = j["poses"].size();
    std::vector<std::string> notes(n);
    std::vector<std::optional<double>> times(n);
    std::optional<double> lastTime;
    for (std::size_t i = 0; i < n; ++i) {
      const std::string where = "poses[" + std::to_string(i) + "]";
      PoseExtras extras;
      plan.poses.push_back(readPose(j["poses"][i], where, source, &extras));
      if (extras.placed) plan.placedPoses.push_back(i);
      notes[i] = std::move(extras.note);
      times[i] = extras.timeMs;
      if (extras.timeMs && lastTime && *extras.timeMs < *lastTime)
        throw InputError(source, where + ".t_ms goes back in time (" + json(*extras.timeMs).dump() + " after " +
                                     json(*lastTime).dump() + ")");
      if (extras.timeMs) lastTime = extras.timeMs;
    }
    if (std::any_of(notes.begin(), notes.end(), [](const std::string& t) { return !t.empty(); }))
      plan.poseNotes = std::move(notes);
    if (lastTime) plan.poseTimesMs = std::move(times);
  }
  if (!plan.feed && plan.poses.empty()) throw InputError(source, "the plan has neither \"feed\" nor \"poses\"");
  return plan;
}

ReamPlan loadPlan(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, "cannot open the plan file");
  std::ostringstream text;
  text << in.rdbuf();
  return parsePlan(text.str(), path);
}

std::string planToJson(const ReamPlan& plan) {
  json j;
  if (!plan.reamer.empty()) j["reamer"] = plan.reamer;
  if (!plan.description.empty()) j["description"] = plan.description;
  if (plan.feed)
    j["feed"] = {{"start", poseJson(plan.feed->start)}, {"step_mm", plan.feed->stepMm}, {"count", plan.feed->count}};
  if (!plan.poses.empty()) {
    j["poses"] = json::array();
    for (std::size_t i = 0; i < plan.poses.size(); ++i)
      j["poses"].push_back(poseJson(plan.poses[i], std::binary_search(plan.placedPoses.begin(), plan.placedPoses.end(), i),
                                    i < plan.poseNotes.size() ? plan.poseNotes[i] : std::string(),
                                    i < plan.poseTimesMs.size() ? plan.poseTimesMs[i] : std::nullopt));
  }
  // A note that is not UTF-8 (typed in no editor, but read from a damaged file) is replaced, not a failed export.
  return j.dump(2, ' ', false, json::error_handler_t::replace);
}

}  // namespace reamsim
