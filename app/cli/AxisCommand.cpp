// axis: version and inclination of reaming axes in the scapular frame, and the axis (and a plan) for given
// angles. docs/PLANNING.md.
#include <cmath>
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "CliArgs.h"
#include "Commands.h"
#include "reamsim/mesh/MeshError.h"
#include "reamsim/ream/CutLogIO.h"
#include "DefaultCase.h"
#include "reamsim/ream/GlenoidFace.h"
#include "reamsim/ream/Plan.h"
#include "reamsim/ream/Resources.h"
#include "reamsim/ream/ScapularFrame.h"

namespace reamsim::cli {
namespace {

using nlohmann::json;
constexpr double kDefaultClearanceMm = 10;  // clear of the glenoid rim for tilts up to ~25 degrees

json vec(const Vec3& v) { return json::array({v.x, v.y, v.z}); }

Vec3 parseAxis(const std::string& text) {
  std::string s = text;
  for (char& c : s)
    if (c == ',') c = ' ';
  std::istringstream in(s);
  Vec3 v;
  std::string rest;
  if (!(in >> v.x >> v.y >> v.z) || (in >> rest) || !std::isfinite(v.x) || !std::isfinite(v.y) ||
      !std::isfinite(v.z) || !(norm(v) > 0))
    throw UsageError("--axis expects X,Y,Z: the reamer's feed direction (into the bone), not zero");
  return v;
}

// The angles of a feed axis (the reamer's, into the bone): measured on the outward direction, its opposite.
json measured(const ScapularFrame& frame, const std::string& source, const Vec3& feedAxis) {
  const AxisAngles a = feedAxisAngles(frame, feedAxis);
  return {{"source", source}, {"axis", vec(normalized(feedAxis))}, {"version_deg", a.versionDeg},
          {"inclination_deg", a.inclinationDeg}};
}

// The glenoid face of `boneArg` about the frame's glenoid centre, its angles, and each axis's correction of them.
json glenoidFace(const ScapularFrame& frame, const std::string& boneArg, const std::string& units, double radiusMm) {
  const std::string source = boneArg == "default" ? "the bundled scapula" : boneArg;
  const BoneState bone = BoneState::fromMesh(benchMesh(boneArg, units));
  GlenoidFaceOptions options;
  options.radiusMm = radiusMm;
  try {
    const GlenoidFace face = measureGlenoidFace(bone, frame.origin, options);
    const AxisAngles a = axisAngles(frame, face.outward);
    return {{"bone", source}, {"outward", vec(face.outward)}, {"version_deg", a.versionDeg},
            {"inclination_deg", a.inclinationDeg}, {"radius_mm", face.radiusMm}, {"triangles", face.triangles},
            {"area_mm2", face.areaMm2}, {"centre_gap_mm", face.centreGapMm}};
  } catch (const std::invalid_argument& e) {
    throw InputError(boneArg == "default" ? std::string("the bundled scapula") : boneArg,
                     std::string("glenoid face: ") + e.what());
  }
}

// What an axis changes of the glenoid's own angles (positive: towards anteversion, superior tilt).
void addCorrection(json& axis, const json& face) {
  axis["correction_deg"] = {{"version", axis["version_deg"].get<double>() - face["version_deg"].get<double>()},
                            {"inclination", axis["inclination_deg"].get<double>() - face["inclination_deg"].get<double>()}};
}

}  // namespace

int runAxis(const std::vector<std::string>& args) {
  CliArgs a(args, {"landmarks", "axis", "plan", "version", "inclination", "clearance", "plan-out", "reamer", "step", "count",
             "bone", "units", "glenoid-radius"},
            {});
  if (!a.positionals().empty()) throw UsageError("axis takes no positional argument");
  const std::string landmarksArg = a.value("landmarks", "default");
  const ScapulaLandmarks landmarks = landmarksArg == "default" ? loadDefaultLandmarks() : loadLandmarks(landmarksArg);
  const std::string landmarksSource = landmarksArg == "default" ? "the bundled scapula's" : landmarksArg;
  ScapularFrame frame;
  try {
    frame = scapularFrame(landmarks);
  } catch (const std::invalid_argument& e) {
    throw InputError(landmarksArg == "default" ? resourcePath(kDefaultLandmarksFile) : landmarksArg, e.what());
  }
  const bool aim = a.has("version") || a.has("inclination");
  if (aim && (a.has("axis") || a.has("plan"))) throw UsageError("give --version/--inclination or an axis to measure, not both");
  if (!aim && (a.has("plan-out") || a.has("clearance") || a.has("reamer") || a.has("step") || a.has("count")))
    throw UsageError("--plan-out, --clearance, --reamer, --step and --count go with --version and --inclination");

  if (!a.has("bone") && (a.has("units") || a.has("glenoid-radius")))
    throw UsageError("--units and --glenoid-radius go with --bone");
  // The bundled landmarks are the bundled bone's: on another bone its glenoid centre is nowhere in particular.
  if (a.has("bone") && a.value("bone") != "default" && !a.has("landmarks"))
    throw UsageError("--bone MESH needs that bone's --landmarks (the default ones are the bundled scapula's)");

  json out = {{"landmarks", landmarksSource},
              {"side", toString(frame.side)},
              {"frame", {{"origin", vec(frame.origin)}, {"lateral", vec(frame.lateral)},
                         {"anterior", vec(frame.anterior)}, {"superior", vec(frame.superior)}}}};
  if (a.has("bone"))
    out["glenoid_face"] = glenoidFace(frame, a.value("bone"), a.value("units", "auto"),
                                      a.number("glenoid-radius", GlenoidFaceOptions{}.radiusMm));
  if (!aim) {
    json axes = json::array();
    try {
      if (a.has("axis")) axes.push_back(measured(frame, "--axis", parseAxis(a.value("axis"))));
    } catch (const std::invalid_argument& e) {
      throw InputError("--axis", e.what());
    }
    try {
      if (a.has("plan") || !a.has("axis")) {
        const std::string planArg = a.value("plan", "default");
        const std::string planPath = planArg == "default" ? defaultPlanPath() : planArg;
        const ReamPlan plan = loadPlan(planPath);
        // Each run of equal axes once: a feed has one, a list of poses as many as it turns through.
        std::vector<std::pair<std::string, Vec3>> runs;
        if (plan.feed) runs.push_back({planPath + ": feed.start", plan.feed->start.axis});
        for (std::size_t i = 0; i < plan.poses.size(); ++i)
          if (runs.empty() || norm(runs.back().second - plan.poses[i].axis) > 1e-12)
            runs.push_back({planPath + ": poses[" + std::to_string(i) + "]", plan.poses[i].axis});
        for (const auto& [source, axis] : runs) axes.push_back(measured(frame, source, axis));
      }
    } catch (const std::invalid_argument& e) {
      throw InputError(a.value("plan", "default plan"), e.what());
    }
    if (out.contains("glenoid_face"))
      for (json& axis : axes) addCorrection(axis, out["glenoid_face"]);
    out["axes"] = axes;
    std::cout << out.dump(2) << "\n";
    return kOk;
  }

  const AxisAngles angles{a.number("version", 0), a.number("inclination", 0)};
  const double clearance = a.number("clearance", kDefaultClearanceMm);
  if (!(clearance >= 0 && clearance <= 200)) throw UsageError("--clearance must be within 0..200 mm");
  Pose start;
  try {
    start = aimedReamerPose(frame, angles, clearance);
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
  out["aimed"] = {{"version_deg", angles.versionDeg}, {"inclination_deg", angles.inclinationDeg},
                  {"clearance_mm", clearance}, {"tip", vec(start.tip)}, {"axis", vec(start.axis)}};
  if (out.contains("glenoid_face")) addCorrection(out["aimed"], out["glenoid_face"]);
  if (a.has("plan-out")) {
    ReamPlan plan;
    plan.reamer = a.value("reamer", "glenoid-36-R30");
    FeedSpec feed;
    feed.start = start;
    feed.stepMm = a.number("step", 0.2);
    const double count = a.number("count", std::ceil((clearance + 3) / feed.stepMm));
    if (!(feed.stepMm > 0) || !(count >= 1 && count <= 1e6) || count != std::floor(count))
      throw UsageError("--step must be > 0 and --count a whole number within 1..1000000");
    feed.count = int(count);
    plan.feed = feed;
    std::ostringstream d;
    d << "Feed along the axis at version " << angles.versionDeg << " deg, inclination " << angles.inclinationDeg
      << " deg in the scapular frame of " << landmarksSource << " landmarks (reamsim-cli axis, docs/PLANNING.md): start "
      << clearance << " mm out from the glenoid centre, " << feed.count << " steps of " << feed.stepMm << " mm.";
    plan.description = d.str();
    try {
      writeTextFile(a.value("plan-out"), planToJson(plan));
    } catch (const InputError& e) {
      std::fprintf(stderr, "reamsim-cli axis: error: %s\n", e.what());
      return kWriteFailed;
    }
    out["plan_out"] = a.value("plan-out");
  }
  std::cout << out.dump(2) << "\n";
  return kOk;
}

}  // namespace reamsim::cli
