// ream: run a plan against a bone through the document and the reaming controller.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>

#include "CliArgs.h"
#include "Commands.h"
#include "ReamedSurfaceJson.h"
#include "TerminalProgress.h"
#include "reamsim/core/Document.h"
#include "reamsim/core/PlanNode.h"
#include "reamsim/mesh/MeshError.h"
#include "reamsim/mesh/MeshIO.h"
#include "reamsim/mesh/Repair.h"
#include "reamsim/ream/CutLogIO.h"
#include "reamsim/ream/DefaultCase.h"
#include "reamsim/ream/LocalCutBackend.h"
#include "reamsim/ream/Plan.h"
#include "reamsim/ream/ReamController.h"
#include "reamsim/ream/ReamReport.h"
#include "reamsim/ream/Resources.h"
#include "reamsim/ream/ScapularFrame.h"
#include "reamsim/tools/ReamerFile.h"
#include "reamsim/tools/ReamerPresets.h"

namespace reamsim::cli {
namespace {

constexpr const char* kDefaultReamer = "glenoid-36-R30";

struct LoadedBone {
  TriangleMesh mesh;
  std::shared_ptr<TriangleMesh> original;
  std::string importReport;
};

LoadedBone loadBone(const std::string& arg, Units units) {
  LoadedBone b;
  if (arg == "default") {
    DefaultBone d = loadDefaultBone();
    b.mesh = std::move(d.mesh);
    b.original = std::make_shared<TriangleMesh>(readMesh(d.originalPath).mesh);
    b.importReport = "bundled default scapula: " + d.meshPath;
    return b;
  }
  ReadOptions options;
  options.units = units;
  LoadedMesh m = readMesh(arg, options);
  for (const std::string& n : m.notes) std::fprintf(stderr, "note: %s: %s\n", arg.c_str(), n.c_str());
  b.original = std::make_shared<TriangleMesh>(m.mesh);
  RepairOptions repairOptions = importRepairOptions();
  repairOptions.progress = terminalProgress("ream: repair on import");
  RepairResult r = repairMesh(m.mesh, repairOptions);
  b.importReport = toText(r.report);
  if (!r.report.actions.empty() && r.report.before.isCleanSolid() == false)
    std::fprintf(stderr, "note: %s: repaired on import:\n%s", arg.c_str(), b.importReport.c_str());
  if (!r.report.success())
    throw InputError(arg, "cannot be repaired into a closed solid without self-intersections; see the report above");
  b.mesh = std::move(r.mesh);
  return b;
}

// A reamer argument is a mesh file if such a file exists, otherwise a preset name.
ReamerSpec resolveReamer(const std::string& arg, TriangleMesh& cuttingVolume) {
  ReamerSpec spec = reamerFromArgument(arg, reamerPresetsPath());
  cuttingVolume = cuttingSolidFor(spec);
  return spec;
}

std::string fmt(const char* f, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

void printRow(const CutLogEntry& e) {
  std::printf("%4zu  %8.2f %8.2f %8.2f  %-7s %9s %11.3f %12.3f %9.2f %7zu\n", e.stepIndex, e.pose.tip.x, e.pose.tip.y,
              e.pose.tip.z, e.contact ? "yes" : (e.boxesOverlap ? "boxes" : "no"),
              std::isfinite(e.minDistanceMm) ? fmt("%.3f", e.minDistanceMm).c_str() : "-", e.removedMm3,
              e.cumulativeMm3, e.cutMs, e.faces);
}

}  // namespace

int runReam(const std::vector<std::string>& args) {
  CliArgs a(args, {"bone", "reamer", "plan", "out", "units", "engine", "collision", "landmarks"},
            {"json", "check", "no-cleanup"});
  if (!a.positionals().empty()) throw UsageError("unexpected argument '" + a.positionals()[0] + "'");
  const std::string outDir = a.required("out");
  const std::string planArg = a.value("plan", "default");
  const ReamPlan plan = loadPlan(planArg == "default" ? defaultPlanPath() : planArg);
  const std::string reamerArg = a.value("reamer", plan.reamer.empty() ? kDefaultReamer : plan.reamer);
  LoadedBone bone = loadBone(a.value("bone", "default"), parseUnits(a.value("units", "auto")));
  // The scapular landmarks for the report's version and inclination: the bundled bone's by default.
  const std::string landmarksArg = a.value("landmarks", a.value("bone", "default") == "default" ? "default" : "none");
  const BonePlanning planning = landmarksArg == "none"      ? BonePlanning{}
                                : landmarksArg == "default" ? BonePlanning{loadDefaultLandmarks(), std::nullopt}
                                                            : loadPlanning(landmarksArg);
  const ScapulaLandmarks& landmarks = planning.landmarks;

  TriangleMesh cuttingVolume;
  const ReamerSpec spec = resolveReamer(reamerArg, cuttingVolume);

  Document doc;
  auto& boneNode = doc.create<BoneNode>("Bone", BoneState::fromMesh(bone.mesh));
  boneNode.setOriginalMesh(bone.original);
  boneNode.setImportReport(bone.importReport);
  auto& reamer = doc.create<ReamerNode>("Reamer", spec);
  reamer.setCuttingVolume(std::make_shared<const TriangleMesh>(std::move(cuttingVolume)));
  auto& planNode = doc.create<PlanNode>("Plan");
  planNode.setReamerSpecName(spec.name);
  planNode.setPoses(plan.expandedPoses());
  auto& log = doc.create<LogNode>("Log");
  auto& alerts = doc.create<AlertNode>("Alerts");
  // Cutting engine (issue 4): the local exact engine, or the whole-mesh CGAL reference.
  const std::string engineName = a.value("engine", "local");
  if (engineName != "local" && engineName != "reference")
    throw UsageError("--engine must be 'local' or 'reference', not '" + engineName + "'");
  // Collision engine (issue 3): exact BVH queries, or the thesis's rays.
  const std::string collisionName = a.value("collision", "bvh");
  if (collisionName != "bvh" && collisionName != "thesis")
    throw UsageError("--collision must be 'bvh' or 'thesis', not '" + collisionName + "'");
  ReamController controller(doc, boneNode, reamer, log, &alerts,
                            engineName == "local" ? localCutBackendFactory(!a.has("no-cleanup"))
                                                  : referenceCutBackendFactory(),
                            collisionName == "bvh" ? makeBvhContactBackend() : makeThesisContactBackend());

  const bool json = a.has("json");
  const double startVolume = boneNode.current().volume();
  if (!json) {
    std::printf("bone: %zu faces, %.1f mm3; reamer: %s; %zu steps\n", boneNode.current().liveTriangleCount(),
                startVolume, spec.name.c_str(), planNode.poses().size());
    std::printf("step     tip_x    tip_y    tip_z  contact  min_dist  removed_mm3  cumulative     cut_ms   faces\n");
  }
  double worstBookkeeping = 0;
  bool invariantsHeld = true;
  std::size_t roundedSelfIntersectingSteps = 0;
  std::vector<double> cutTimes;
  const std::vector<bool> placements = plan.expandedPlacements();
  const std::vector<std::string> notes = plan.expandedNotes();
  for (std::size_t i = 0; i < planNode.poses().size(); ++i) {
    const Pose& pose = planNode.poses()[i];
    const ReamStepOutcome step = controller.moveTo(pose, placements[i], notes[i]);
    worstBookkeeping = std::max(worstBookkeeping, step.volumeBookkeepingError / std::max(1.0, step.cut.removedMm3));
    if (step.cut.changed) cutTimes.push_back(step.entry.cutMs);
    if (a.has("check") && step.cut.changed) {
      const BoneInvariants inv = controller.checkBone();
      // The engine's exact state is the bone; the rounded copy is what is displayed and exported.
      // Self-intersections the bone came with (a dirty CT mesh) are not a broken invariant; new ones are.
      if (!inv.closed || !inv.outwardOriented || inv.newSelfIntersectionsExact) {
        invariantsHeld = false;
        std::fprintf(stderr, "step %zu: bone invariant broken (closed %d, outward %d, new self-intersections %d)\n",
                     step.entry.stepIndex, inv.closed, inv.outwardOriented, inv.newSelfIntersectionsExact);
      }
      if (inv.newSelfIntersectionsRounded) ++roundedSelfIntersectingSteps;
    }
    if (!json) printRow(step.entry);
  }

  std::sort(cutTimes.begin(), cutTimes.end());
  const double medianMs = cutTimes.empty() ? 0.0 : cutTimes[cutTimes.size() / 2];
  const TriangleMesh finalMesh = boneNode.current().toMesh();
  nlohmann::json summary = {{"bone", a.value("bone", "default")},
                            {"reamer", spec.name},
                            {"steps", log.size()},
                            {"volume_start_mm3", startVolume},
                            {"volume_end_mm3", boneNode.current().volume()},
                            {"removed_total_mm3", log.empty() ? 0.0 : log.entries().back().cumulativeMm3},
                            {"faces_start", bone.mesh.triangles.size()},
                            {"faces_end", finalMesh.triangles.size()},
                            {"median_cut_ms", medianMs},
                            {"max_volume_bookkeeping_error_rel", worstBookkeeping},
                            {"invariants_checked", a.has("check")},
                            {"invariants_held", invariantsHeld},
                            {"rounded_copy_self_intersecting_steps", roundedSelfIntersectingSteps},
                            {"engine", engineName == "local" ? "local-exact (modules/csg LocalSubtractor)"
                                                             : "cgal-corefinement-epeck (reference)"},
                            {"collision", collisionName == "bvh" ? "bvh-exact (modules/collision BoneCollider)"
                                                                 : "thesis rays (reference)"}};

  // What a surgeon asks of the result: how much of the face is seated and how close the bone is to the
  // ideal face (parametric reamers: the ideal face is what the spec describes).
  std::string reamedLine;
  std::optional<ReamedSurfaceReport> seatAtLast;  // for the report too
  if (spec.meshFile.empty() && !planNode.poses().empty()) {
    const ReamedSurfaceReport rs = measureReamedSurface(finalMesh, spec, planNode.poses().back(), kReamedSurfaceBandMm);
    summary["reamed_surface"] = reamedSurfaceJson(rs, kReamedSurfaceBandMm);
    seatAtLast = rs;
    reamedLine = reamedSurfaceLine(rs);
  }

  ReamReportInput report;
  report.boneName = a.value("bone", "default") == "default" ? "bundled default scapula" : a.value("bone");
  report.boneSource = a.value("bone", "default") == "default" ? resourcePath(kDefaultBoneFile) : a.value("bone");
  report.volumeAtStartMm3 = startVolume;
  report.volumeNowMm3 = boneNode.current().volume();
  report.facesAtStart = bone.mesh.triangles.size();
  report.facesNow = finalMesh.triangles.size();
  report.reamer = spec;
  if (!planNode.poses().empty()) report.reamerPose = planNode.poses().back();
  report.landmarks = landmarks;
  report.plannedAxis = planning.plannedAxis;
  addGlenoidFaces(report, boneNode.history().entries().front().state, boneNode.current());
  report.seat = seatAtLast;  // at the last pose, which is the report's reamer pose
  // The landmarks' frame, once: the glenoid face's angles, the last pose's, and each log row's.
  std::optional<ScapularFrame> frame;
  std::string frameProblem;
  if (landmarks.complete()) try {
      frame = scapularFrame(landmarks);
    } catch (const std::invalid_argument& e) {
      frameProblem = e.what();
    }
  if (landmarks.complete()) {
    // The glenoid face's own angles before and after: what the plan set out to correct, and what it made.
    nlohmann::json faces;
    for (const auto& [key, reported] : {std::pair{"as_opened", &report.glenoidAsOpened}, std::pair{"now", &report.glenoidNow}}) {
      if (!reported->face || !frame) {
        faces[key] = {{"problem", !reported->face ? reported->problem : frameProblem}};
        continue;
      }
      try {
        const AxisAngles g = axisAngles(*frame, reported->face->outward);
        faces[key] = {{"version_deg", g.versionDeg}, {"inclination_deg", g.inclinationDeg}};
      } catch (const std::invalid_argument& e) {
        faces[key] = {{"problem", e.what()}};
      }
    }
    summary["glenoid_face"] = faces;
  }
  for (const CutLogEntry& e : log.entries())
    if (e.removedMm3 > 0) report.cuts.push_back(e);
  report.writtenUnixMs = std::chrono::duration_cast<std::chrono::milliseconds>(
                             std::chrono::system_clock::now().time_since_epoch()).count();
  report.writtenBy = "reamsim-cli ream --plan " + planArg;
  if (report.reamerPose && landmarks.complete()) try {
      if (!frame) throw std::invalid_argument(frameProblem);
      const AxisAngles last = feedAxisAngles(*frame, report.reamerPose->axis);
      summary["last_pose_version_deg"] = last.versionDeg;
      summary["last_pose_inclination_deg"] = last.inclinationDeg;
    } catch (const std::invalid_argument& e) {
      std::fprintf(stderr, "note: no version and inclination: %s\n", e.what());
    }

  std::error_code ec;
  std::filesystem::create_directories(outDir, ec);
  try {
    writeTextFile(outDir + "/log.csv", frame ? cutLogCsv(log.entries(), *frame) : cutLogCsv(log.entries()));
    writeTextFile(outDir + "/log.json", cutLogJson(log.entries(), summary.dump(), frame ? &*frame : nullptr));
    writeMesh(finalMesh, outDir + "/bone_final.ply");
    writeTextFile(outDir + "/report.html", reamReportHtml(report));
  } catch (const InputError& e) {
    std::fprintf(stderr, "reamsim-cli ream: error: %s\n", e.what());
    return kWriteFailed;
  }
  if (json) {
    std::cout << cutLogJson(log.entries(), summary.dump(), frame ? &*frame : nullptr) << "\n";
  } else {
    std::printf("removed %.3f mm3 in %zu steps; median cut %.2f ms; faces %zu -> %zu; worst |removed - (V_before - "
                "V_after)| / removed = %.2e\n",
                summary["removed_total_mm3"].get<double>(), log.size(), medianMs, bone.mesh.triangles.size(),
                finalMesh.triangles.size(), worstBookkeeping);
    if (!reamedLine.empty()) std::printf("%s\n", reamedLine.c_str());
    std::printf("written: %s/log.csv, %s/log.json, %s/bone_final.ply, %s/report.html\n", outDir.c_str(), outDir.c_str(),
                outDir.c_str(), outDir.c_str());
  }
  return invariantsHeld ? kOk : kFailed;
}

}  // namespace reamsim::cli
