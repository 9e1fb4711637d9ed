// bench cut: the local CSG engine on a realistic reaming path, timed per cut, with optional peers
// (in-process: the CGAL whole-mesh reference; with node: manifold-3d and csg.js from bench/peers, on the
// exported sequence), invariant checks, sequence export and the thesis's Table 5-1 experiment. Prints one
// JSON object (see docs/BENCHMARKS.md).
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <iostream>
#include <limits>
#include <map>
#include <memory>
#include <stdexcept>
#include <nlohmann/json.hpp>
#include <unistd.h>

#include "reamsim/core/HistoryJournal.h"
#include "BenchPlanning.h"
#include "CliArgs.h"
#include "Commands.h"
#include "DefaultCase.h"
#include "MachineSpeed.h"
#include "NodePeers.h"
#include "ReamedSurfaceJson.h"
#include "reamsim/core/Document.h"
#include "reamsim/core/HistoryJournal.h"
#include "reamsim/csg/LocalSubtractor.h"
#include "reamsim/csg/ReferenceSubtractor.h"
#include "reamsim/csg/SweptVolume.h"
#include "reamsim/mesh/MeshError.h"
#include "reamsim/mesh/MeshIO.h"
#include "reamsim/mesh/TriangleMesh.h"
#include "reamsim/ream/Approach.h"
#include "reamsim/ream/CutLogIO.h"
#include "reamsim/ream/LocalCutBackend.h"
#include "reamsim/ream/ReamController.h"
#include "reamsim/ream/ClearPlacement.h"
#include "reamsim/ream/ReamEngine.h"
#include "reamsim/tools/ReamerGeometry.h"
#include "reamsim/tools/ReamerPresets.h"

namespace reamsim::cli {
namespace {

struct Spot {
  Vec3 centre;  // on the surface
  Vec3 inward;  // feed direction
};

// The glenoid frame of the bundled scapula (for it and for the refinements of it that share its
// coordinates, scripts/make_scapula_variants.py), or the vertex farthest along +Z (the skull's vertex, far
// from the open border where the scan ends), fed along -Z.
Spot findSpot(const std::string& site, const TriangleMesh& mesh) {
  if (site == "glenoid") {
    const DefaultBone d = loadDefaultBone();
    return {d.glenoid.centre, -d.glenoid.outwardAxis};
  }
  Vec3 top = mesh.vertices.front();
  for (const Vec3& p : mesh.vertices)
    if (p.z > top.z) top = p;
  return {top, {0, 0, -1}};
}

// A realistic path: from 1 mm outside, fed `depthMm` deep over the steps while the axis wobbles by
// `tiltDeg` (a surgeon rocking the reamer) and the tip circles 0.5 mm about the axis.
std::vector<Pose> reamingPath(const Spot& s, int steps, double depthMm, double tiltDeg) {
  const Vec3 ref = std::abs(s.inward.x) < 0.9 ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
  const Vec3 u = normalized(cross(s.inward, ref)), v = cross(s.inward, u);
  const double tilt = std::tan(tiltDeg * M_PI / 180);
  std::vector<Pose> poses;
  for (int i = 0; i < steps; ++i) {
    const double f = steps > 1 ? double(i) / (steps - 1) : 1.0;
    const double a = 2 * M_PI * i / 50.0, b = 2 * M_PI * i / 37.0;
    const Vec3 axis = normalized(s.inward + (u * std::cos(a) + v * std::sin(a)) * tilt);
    const Vec3 tip = s.centre + s.inward * (-1.0 + (1.0 + depthMm) * f) + (u * std::cos(b) + v * std::sin(b)) * 0.5;
    poses.push_back({tip, axis, 0});
  }
  return poses;
}

// The soak path: five feeds into the spot, each from 1 mm outside to a deeper depth (depthMm, then + 0.5 mm
// per feed), each with its own mean tilt (4 degrees, turning 144 degrees per feed) and the jitter of
// reamingPath on top (2 degrees of wobble, 0.5 mm of drift): the reamer leaves and re-enters the cavity.
std::vector<Pose> soakPath(const Spot& s, int steps, double depthMm) {
  const Vec3 ref = std::abs(s.inward.x) < 0.9 ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
  const Vec3 u = normalized(cross(s.inward, ref)), v = cross(s.inward, u);
  constexpr int kFeeds = 5;
  const double meanTilt = std::tan(4 * M_PI / 180), wobble = std::tan(2 * M_PI / 180);
  std::vector<Pose> poses;
  for (int i = 0; i < steps; ++i) {
    const int feed = std::min(kFeeds - 1, i * kFeeds / steps);
    const int first = feed * steps / kFeeds, count = std::max(1, (feed + 1) * steps / kFeeds - first);
    const double f = count > 1 ? double(i - first) / (count - 1) : 1.0;
    const double m = 2 * M_PI * 0.4 * feed, a = 2 * M_PI * i / 50.0, b = 2 * M_PI * i / 37.0;
    const Vec3 axis = normalized(s.inward + (u * std::cos(m) + v * std::sin(m)) * meanTilt +
                                 (u * std::cos(a) + v * std::sin(a)) * wobble);
    const double depth = depthMm + 0.5 * feed;
    const Vec3 tip = s.centre + s.inward * (-1.0 + (1.0 + depth) * f) + (u * std::cos(b) + v * std::sin(b)) * 0.5;
    poses.push_back({tip, axis, 0});
  }
  return poses;
}

TriangleMesh placed(const TriangleMesh& local, const Pose& pose);

// --avoid-defects (bones other than the default): dirty CT meshes refuse cuts that reach a defect, so try
// up to 40 spots, highest first and each at least 20 mm from the ones tried, fed along the inward vertex
// normal, and keep the first where the path's deepest pose cuts without reaching a defect or an open border.
Spot findCleanSpot(const TriangleMesh& bone, const TriangleMesh& localTool,
                   const std::function<std::vector<Pose>(const Spot&)>& pathAt) {
  std::vector<Vec3> normal(bone.vertices.size());
  for (const Triangle& t : bone.triangles) {
    const Vec3 n = cross(bone.vertices[t[1]] - bone.vertices[t[0]], bone.vertices[t[2]] - bone.vertices[t[0]]);
    for (std::uint32_t v : t) normal[v] += n;
  }
  std::vector<std::uint32_t> order(bone.vertices.size());
  for (std::uint32_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) { return bone.vertices[a].z > bone.vertices[b].z; });
  LocalSubtractor probe(bone);
  std::vector<Vec3> tried;
  for (std::uint32_t v : order) {
    if (tried.size() >= 40) break;
    const Vec3& p = bone.vertices[v];
    if (norm(normal[v]) == 0 || std::any_of(tried.begin(), tried.end(), [&](const Vec3& q) { return norm(q - p) < 20; }))
      continue;
    tried.push_back(p);
    const Spot spot{p, -normalized(normal[v])};
    try {
      if (probe.subtract(placed(localTool, pathAt(spot).back())).changed) return spot;  // the probe is discarded
    } catch (const CutError&) {
    }
  }
  throw std::runtime_error("--avoid-defects: no spot among " + std::to_string(tried.size()) +
                           " tried lets the reamer cut without reaching a defect");
}

TriangleMesh placed(const TriangleMesh& local, const Pose& pose) {
  TriangleMesh m = local;
  const RigidTransform t = toTransform(pose);
  for (Vec3& p : m.vertices) p = t.apply(p);
  return m;
}

double percentile(std::vector<double> v, double q) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, std::size_t(q * (v.size() - 1) + 0.5))];
}

// What a sideways move costs before its cut: the swept hull (SweptVolume.h) of the reamer at the path's
// first poses and the same poses moved 0.5 mm across their axis, as a key press moves it in the GUI.
// 0.5 mm across the axis: the sideways key move of the swept-hull and moves-past-bone figures.
Vec3 sidewaysKeyMove(const Vec3& axis) {
  Vec3 across = cross(axis, Vec3{0, 0, 1});
  if (norm(across) < 0.1) across = cross(axis, Vec3{1, 0, 0});
  return across * (0.5 / norm(across));
}

nlohmann::json sweptHulls(const TriangleMesh& tool, const std::vector<Pose>& poses) {
  // What the reaming loop builds (sweptByTranslation: the silhouette sweep, else the hull) and, alternating
  // with it pose by pose, the hull alone (hullOfPlacements, its fallback), so their ratio is of one moment.
  std::vector<double> ms, hullMs, faces;
  std::size_t silhouette = 0;
  auto timed = [](auto&& build) {
    const auto t0 = std::chrono::steady_clock::now();
    TriangleMesh m = build();
    return std::make_pair(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count(),
                          std::move(m));
  };
  for (std::size_t i = 0; i < std::min<std::size_t>(poses.size(), 50); ++i) {
    const RigidTransform from = toTransform(poses[i]);
    RigidTransform to = from;
    to.translation = from.translation + sidewaysKeyMove(poses[i].axis);
    auto [sweptMs, swept] = timed([&] { return sweptByTranslation(tool, from, to); });
    auto [hullOnlyMs, hull] = timed([&] { return hullOfPlacements(tool, from, to); });
    ms.push_back(sweptMs);
    hullMs.push_back(hullOnlyMs);
    faces.push_back(double(swept.triangles.size()));
    if (sweptBySilhouette(tool, from, to)) ++silhouette;
  }
  const double median = percentile(ms, 0.5), hullMedian = percentile(hullMs, 0.5);
  return {{"what", "volume the reamer sweeps from a path pose to 0.5 mm across its axis (a sideways key move), per move: "
                   "sweptByTranslation as the reaming loop builds it"},
          {"hulls", ms.size()},
          {"median_ms", median},
          {"p95_ms", percentile(ms, 0.95)},
          {"median_faces", percentile(faces, 0.5)},
          {"by_silhouette", silhouette},
          {"convex_hull_median_ms", hullMedian},
          {"convex_hull_over_swept", median > 0 ? hullMedian / median : 0.0}};
}

// Sideways key moves (0.5 mm, back and forth) with the reamer's solid just clear of the bone (backed off
// the path's first pose along its axis until it misses, then 0.3 mm more), through ReamEngine with the
// application's engines: what such a step costs with the first-contact query deciding that the move swept
// past the bone (no hull built) against the same step building the hull and cutting nothing. Alternating
// the two engines move by move in one process, so the ratio is of the same moment of the machine.
nlohmann::json movesPastBone(const TriangleMesh& bone, const ReamerSpec& spec, const TriangleMesh& localTool,
                             const Pose& first) {
  const BoneState state = BoneState::fromMesh(bone);
  auto volume = std::make_shared<const TriangleMesh>(localTool);
  ReamEngine skip(volume, makeBvhContactBackend(false), localCutBackendFactory(), spec);
  ReamEngine build(volume, makeBvhContactBackend(false), localCutBackendFactory(), spec);
  build.setSkipMissedSweeps(false);
  const Vec3 axis = normalized(first.axis);
  Pose clear = first;
  for (int i = 0; i < 200; ++i) {  // back off in 0.25 mm steps until the solid misses the bone
    const ReamComputation c = skip.compute(state, 1, clear, 0.25);
    if (c.contact.solidOverlapsBone && !*c.contact.solidOverlapsBone) break;
    clear.tip = clear.tip - axis * 0.25;
  }
  clear.tip = clear.tip - axis * 0.3;
  const Vec3 across = sidewaysKeyMove(axis);
  std::vector<double> skipMs, buildMs;
  std::size_t reached = 0, skipped = 0, cut = 0;
  Pose at = clear;
  for (int i = 0; i < 41; ++i) {
    Pose to = at;
    to.tip = at.tip + (i % 2 == 0 ? across : across * -1.0);
    for (ReamEngine* e : {&skip, &build}) {
      const auto t0 = std::chrono::steady_clock::now();
      const ReamComputation c = e->compute(state, 1, to, 0.5, &at);
      const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
      if (i == 0) continue;  // the first move builds the engines' trees
      (e == &skip ? skipMs : buildMs).push_back(ms);
      if (e == &skip) {
        reached += c.contact.alongMove && c.contact.alongMove->reached;
        skipped += c.sweptPastBone;
      }
      cut += c.cut.changed;
    }
    at = to;
  }
  const double skipMedian = percentile(skipMs, 0.5), buildMedian = percentile(buildMs, 0.5);
  return {{"what", "0.5 mm sideways moves of the reamer just clear of the bone through ReamEngine: the first-contact "
                   "query shows the move missed the bone and no hull is built, against building the hull and cutting "
                   "nothing (alternating, one process)"},
          {"moves", skipMs.size()},
          {"moves_reaching_bone", reached},
          {"moves_swept_past_bone", skipped},
          {"moves_that_cut", cut},
          {"skip_median_ms", skipMedian},
          {"skip_p95_ms", percentile(skipMs, 0.95)},
          {"hull_median_ms", buildMedian},
          {"hull_p95_ms", percentile(buildMs, 0.95)},
          {"ratio", skipMedian > 0 ? buildMedian / skipMedian : 0.0}};
}

// "Ream to depth"'s contact search as the GUI makes it (ReamEngine::advanceToContactMm on the engine that
// has been reaming: its tree follows the bone) against the free advanceToContactMm, which builds a tree for
// the call (what the GUI did before session 30); from 1 to 5 mm before the first pose, alternating.
// A contact-only engine that has answered a step at `first` on `state` (revision 1), as a session's has: its
// tree exists and follows the bone.
std::unique_ptr<ReamEngine> engineThatHasStepped(const BoneState& state, const ReamerSpec& spec,
                                                 const TriangleMesh& localTool, const Pose& first) {
  auto engine = std::make_unique<ReamEngine>(std::make_shared<const TriangleMesh>(localTool),
                                             makeBvhContactBackend(false), CutBackendFactory{}, spec);
  engine->compute(state, 1, first, 0);
  return engine;
}

nlohmann::json reamToDepthSearch(const TriangleMesh& bone, const ReamerSpec& spec, const TriangleMesh& localTool,
                                 const Pose& first) {
  const BoneState state = BoneState::fromMesh(bone);
  const std::unique_ptr<ReamEngine> owned = engineThatHasStepped(state, spec, localTool, first);
  ReamEngine& engine = *owned;
  std::vector<double> engineMs, freshMs;
  double maxDiffMm = 0;
  std::size_t found = 0;
  for (int i = 0; i < 9; ++i) {
    const Pose from = advancedAlongAxis(first, -1.0 - 0.5 * i);
    const auto t0 = std::chrono::steady_clock::now();
    const auto viaEngine = engine.advanceToContactMm(state, 1, from, 100);
    const auto t1 = std::chrono::steady_clock::now();
    const auto fresh = advanceToContactMm(state, localTool, from, 100, &spec);
    const auto t2 = std::chrono::steady_clock::now();
    engineMs.push_back(std::chrono::duration<double, std::milli>(t1 - t0).count());
    freshMs.push_back(std::chrono::duration<double, std::milli>(t2 - t1).count());
    if (viaEngine.has_value() != fresh.has_value()) maxDiffMm = std::numeric_limits<double>::infinity();
    if (viaEngine && fresh) {
      maxDiffMm = std::max(maxDiffMm, std::abs(*viaEngine - *fresh));
      ++found;
    }
  }
  const double engineMedian = percentile(engineMs, 0.5), freshMedian = percentile(freshMs, 0.5);
  return {{"what", "the first contact along the reamer axis (ream to depth) on the reaming engine's own tree, against "
                   "a tree built for each search (alternating, one process)"},
          {"searches", engineMs.size()},
          {"found", found},
          {"max_diff_mm", maxDiffMm},
          {"engine_median_ms", engineMedian},
          {"fresh_tree_median_ms", freshMedian},
          {"ratio", engineMedian > 0 ? freshMedian / engineMedian : 0.0}};
}

// Aim's placement clear of the bone (findClearPlacement on the reaming engine's own tree, what the GUI's
// ReamSession::placeClearOfBone runs): from 0.25 to 5 mm past the first contact along the path's first pose's
// axis, 20 poses, each of which overlaps the bone; each answer must be a retreat, clear (no overlap at all), and
// overlapping 0.01 mm inward of it less its margin (`not_nearest_clear` counts the answers that are not: a
// failed check, the command's exit code 1).
nlohmann::json clearPlacement(const TriangleMesh& bone, const ReamerSpec& spec, const TriangleMesh& localTool,
                              const Pose& first) {
  const BoneState state = BoneState::fromMesh(bone);
  const std::unique_ptr<ReamEngine> owned = engineThatHasStepped(state, spec, localTool, first);
  ReamEngine& engine = *owned;
  const std::optional<double> approach = engine.advanceToContactMm(state, 1, first, 100);
  if (!approach) return {{"error", "the path's first pose meets no bone along its axis"}};
  std::vector<double> ms, retreat, queries;
  std::size_t retreated = 0, wrong = 0, overlapSearches = 0, askedClear = 0;
  for (int i = 0; i < 20; ++i) {
    const Pose asked = advancedAlongAxis(first, *approach + 0.25 * (i + 1));
    const auto t0 = std::chrono::steady_clock::now();
    const ClearPlacement c = findClearPlacement(engine, state, 1, asked);
    ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
    queries.push_back(c.queries);
    overlapSearches += c.overlapSearch;
    if (c.outcome != ClearPlacement::Outcome::Retreated) {
      // Kept as asked is right where the pose is clear (past a bone thinner than its depth), wrong elsewhere.
      const bool clear = c.outcome == ClearPlacement::Outcome::AsAsked && engine.overlapsAt(state, 1, asked) == false;
      ++(clear ? askedClear : wrong);
      continue;
    }
    ++retreated;
    retreat.push_back(c.retreatMm);
    const bool clearThere = engine.overlapsAt(state, 1, c.pose) == false;
    const bool touchingInward = engine.overlapsAt(state, 1, advancedAlongAxis(c.pose, 0.05 + 0.01)) == true;
    if (!clearThere || !touchingInward) ++wrong;
  }
  return {{"what", "Aim's placement clear of the bone (findClearPlacement on the reaming engine's tree) from 20 poses "
                   "0.25-5 mm past the first contact"},
          {"placements", ms.size()},
          {"retreated", retreated},
          {"not_nearest_clear", wrong},
          {"median_ms", percentile(ms, 0.5)},
          {"p95_ms", percentile(ms, 0.95)},
          {"median_queries", percentile(queries, 0.5)},
          {"overlap_searches", overlapSearches},  // answers the surface touch got wrong (ClearPlacement::overlapSearch)
          {"asked_clear", askedClear},            // poses past a thin bone, clear as asked
          {"median_retreat_mm", retreat.empty() ? 0.0 : percentile(retreat, 0.5)}};
}

double smallestAngleDeg(const TriangleMesh& m, const Triangle& t) {
  return smallestAngle(m.vertices[t[0]], m.vertices[t[1]], m.vertices[t[2]]) * 180 / M_PI;
}

double minAngleDeg(const TriangleMesh& m) {
  double best = 180;
  for (const Triangle& t : m.triangles) best = std::min(best, smallestAngleDeg(m, t));
  return best;
}

// How many faces have a smallest angle below 1, 5 and 15 degrees (slivers left over).
nlohmann::json facesBelowAngle(const TriangleMesh& m) {
  std::size_t n1 = 0, n5 = 0, n15 = 0;
  for (const Triangle& t : m.triangles) {
    const double a = smallestAngleDeg(m, t);
    n1 += a < 1;
    n5 += a < 5;
    n15 += a < 15;
  }
  return {{"below_1_deg", n1}, {"below_5_deg", n5}, {"below_15_deg", n15}};
}

// The faces the cuts made and kept (those of the final mesh that are not faces of the start mesh, compared by
// their corners' coordinates, which the engine never moves on faces it does not touch): how many, their
// smallest angle and slivers, beside the start mesh's own figures. The whole-mesh minimum alone would
// report the bone's own worst face (0.0005 degrees on the bundled scapula) whatever the cuts do.
nlohmann::json cutFacesQuality(const TriangleMesh& start, const TriangleMesh& end) {
  using Corners = std::array<std::array<double, 3>, 3>;
  auto corners = [](const TriangleMesh& m, const Triangle& t) {
    Corners c;
    for (int k = 0; k < 3; ++k) c[std::size_t(k)] = {m.vertices[t[k]].x, m.vertices[t[k]].y, m.vertices[t[k]].z};
    std::sort(c.begin(), c.end());
    return c;
  };
  std::vector<Corners> before;
  before.reserve(start.triangles.size());
  for (const Triangle& t : start.triangles) before.push_back(corners(start, t));
  std::sort(before.begin(), before.end());
  TriangleMesh made;
  made.vertices = end.vertices;
  std::vector<double> angles;
  for (const Triangle& t : end.triangles)
    if (!std::binary_search(before.begin(), before.end(), corners(end, t))) {
      made.triangles.push_back(t);
      angles.push_back(smallestAngleDeg(end, t));
    }
  return {{"faces", made.triangles.size()},
          {"min_angle_deg", angles.empty() ? 0.0 : *std::min_element(angles.begin(), angles.end())},
          {"p1_angle_deg", percentile(angles, 0.01)},
          {"median_angle_deg", percentile(angles, 0.5)},
          {"faces_by_smallest_angle", facesBelowAngle(made)},
          {"start_mesh", {{"min_angle_deg", minAngleDeg(start)}, {"faces_by_smallest_angle", facesBelowAngle(start)}}}};
}

nlohmann::json transformJson(const Pose& p) {
  const RigidTransform t = toTransform(p);
  const auto& r = t.rotation;
  return nlohmann::json::array({r[0], r[1], r[2], t.translation.x, r[3], r[4], r[5], t.translation.y, r[6], r[7], r[8],
                                t.translation.z, 0, 0, 0, 1});
}

// bone.ply, tool.ply (reamer-local) and steps.json (one row-major 4x4 per step): the sequence the npm
// peers run (bench/peers/run_peer.mjs), and anyone can rerun elsewhere.
void exportSequence(const std::string& dir, const TriangleMesh& bone, const TriangleMesh& localTool,
                    const std::vector<Pose>& poses) {
  std::filesystem::create_directories(dir);
  writeMesh(bone, dir + "/bone.ply");
  writeMesh(localTool, dir + "/tool.ply");
  nlohmann::json seq = {{"frame", "tool.ply is in reamer-local coordinates; each step's 4x4 row-major matrix "
                                  "maps it into bone coordinates; subtract in order"},
                        {"steps", nlohmann::json::array()}};
  for (const Pose& p : poses) seq["steps"].push_back(transformJson(p));
  writeTextFile(dir + "/steps.json", seq.dump(1) + "\n");
}

// One npm peer's entry in "peers": its runner's figures, the ratio of its median to ReamSim's over the
// same steps (all of them, or the first `steps_completed` when a budget stopped it) and its end volume
// against ReamSim's. Refusals, budget stops and errors are carried over as the runner reported them.
nlohmann::json peerEntry(const nlohmann::json& r, const std::vector<double>& reamsimPerStep, double reamsimVolumeEnd) {
  nlohmann::json e = nlohmann::json::object();
  for (const char* key : {"package", "algorithm", "refused", "error", "stopped", "coordinates", "input_checks",
                          "setup_ms", "steps", "steps_completed", "median_ms", "p95_ms", "convert_median_ms",
                          "faces_start", "faces_end", "polygons_end", "volume_end_mm3", "volume_after_completed_mm3"})
    if (r.contains(key)) e[key] = r[key];
  if (r.contains("input") && r["input"].contains("bone")) e["input_bone_edges"] = r["input"]["bone"];
  if (r.contains("median_ms") && r["median_ms"].is_number() && r.contains("steps_completed")) {
    const std::size_t k = std::min<std::size_t>(r["steps_completed"].get<std::size_t>(), reamsimPerStep.size());
    std::vector<double> same;
    for (std::size_t i = 0; i < k; ++i)
      if (!std::isnan(reamsimPerStep[i])) same.push_back(reamsimPerStep[i]);
    if (!same.empty()) {
      e["ratio_to_reamsim"] = r["median_ms"].get<double>() / std::max(1e-9, percentile(same, 0.5));
      if (k < reamsimPerStep.size()) {
        e["ratio_over_first_steps"] = k;
        e["reamsim_median_ms_same_steps"] = percentile(same, 0.5);
      }
    }
    const bool stoppedEarly = k < reamsimPerStep.size();
    if (stoppedEarly && r.contains("faces_per_step")) e["faces_per_step"] = r["faces_per_step"];
  }
  // A volume is only defined for a closed bone: no comparison for an open one (csg.js runs on anything).
  const bool openBone = e.contains("input_bone_edges") && e["input_bone_edges"].value("border_edges", 0) > 0;
  if (openBone)
    e["volume_note"] = "the bone is open: volumes are not comparable";
  else if (r.contains("volume_end_mm3") && r["volume_end_mm3"].is_number())
    e["volume_end_diff_rel"] = std::abs(r["volume_end_mm3"].get<double>() - reamsimVolumeEnd) / reamsimVolumeEnd;
  return e;
}

// A subtraction timed as its caller sees it, from the call to the return: the engines' own `milliseconds`
// stop before their locals are released (for ReamSim's cut the exact patch meshes, ~3 % of a bundled cut).
template <class Engine>
auto timedSubtract(Engine& engine, const TriangleMesh& tool, double& ms) {
  const auto t0 = std::chrono::steady_clock::now();
  auto cut = engine.subtract(tool);
  ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  return cut;
}

// The thesis's Table 5-1: the reamer translated along X into the bone in four increments; vertices,
// faces and time after each subtraction, for the local engine and the reference.
nlohmann::json table51(const TriangleMesh& bone, const TriangleMesh& localTool, const Spot& spot) {
  const Vec3 x = spot.inward.x >= 0 ? Vec3{1, 0, 0} : Vec3{-1, 0, 0};
  LocalSubtractor local(bone);
  ReferenceSubtractor reference(bone);
  nlohmann::json rows = nlohmann::json::array();
  for (int i = 1; i <= 4; ++i) {
    // Tip 1 mm outside the glenoid centre along -X, then 1 mm per increment along X.
    const Pose pose{spot.centre - x * 1.0 + x * double(i), x, 0};
    const TriangleMesh tool = placed(localTool, pose);
    double localMs = 0, referenceMs = 0;
    const LocalCut c = timedSubtract(local, tool, localMs);
    const ReferenceCut r = timedSubtract(reference, tool, referenceMs);
    const TriangleMesh lm = local.mesh();
    rows.push_back({{"cut", i},
                    {"reamsim_vertices", lm.vertices.size()},
                    {"reamsim_faces", lm.triangles.size()},
                    {"reamsim_ms", localMs},
                    {"reamsim_removed_mm3", c.removedMm3},
                    {"cgal_faces", r.facesAfter},
                    {"cgal_ms", referenceMs},
                    {"cgal_removed_mm3", r.removedMm3}});
  }
  return {{"experiment", "thesis Table 5-1: reamer translated along X into the bone in 4 increments of 1 mm"},
          {"thesis_figures", "BSP CSG: 233 ms per subtraction at 1,000 faces; 1,000 -> 106,091 faces after 4 cuts"},
          {"rows", rows}};
}

// --loop: the same poses through the application's reaming loop (ReamController on a Document, the GUI's
// engines: the BVH collision without axial depth, the local cut with its clean-up): what a step costs the
// user, of which the Boolean is one part. Each step moves from the previous pose, as a plan does.
nlohmann::json appLoop(const TriangleMesh& bone, const ReamerSpec& spec, const TriangleMesh& localTool,
                       const std::vector<Pose>& poses, bool cleanup) {
  Document doc;
  auto& boneNode = doc.create<BoneNode>("Bone", BoneState::fromMesh(bone));
  auto& reamer = doc.create<ReamerNode>("Reamer", spec);
  reamer.setCuttingVolume(std::make_shared<const TriangleMesh>(localTool));
  auto& log = doc.create<LogNode>("Log");
  auto& alerts = doc.create<AlertNode>("Alerts");
  const auto t0 = std::chrono::steady_clock::now();
  ReamController controller(doc, boneNode, reamer, log, &alerts, localCutBackendFactory(cleanup),
                            makeBvhContactBackend(false));
  const double setupMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  std::vector<double> step, contact, cut, state, commit;  // of the steps that cut
  // The crash-recovery journal of the bone's history (HistoryJournal.h), appended after every cut as if each were
  // a copy of its own (the window appends every few seconds), then read back whole: what recovery costs.
  const std::string journalPath =
      (std::filesystem::temp_directory_path() / ("reamsim_bench_journal_" + std::to_string(::getpid()) + ".rsj")).string();
  std::filesystem::remove(journalPath);
  HistoryJournalWriter journal(journalPath);
  journal.append(boneNode.history().entries());
  const std::uint64_t firstRecordBytes = journal.bytes();
  std::vector<double> journalAppendMs, journalCutBytes;
  std::size_t failures = 0;
  for (const Pose& p : poses) {
    const auto s0 = std::chrono::steady_clock::now();
    try {
      const ReamStepOutcome o = controller.moveTo(p);
      if (!o.cut.changed) continue;
      step.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - s0).count());
      contact.push_back(o.times.contact);
      cut.push_back(o.times.cut);
      state.push_back(o.times.state);
      commit.push_back(o.commitMs);
      const std::uint64_t before = journal.bytes();
      const auto j0 = std::chrono::steady_clock::now();
      journal.append(boneNode.history().entries());
      journalAppendMs.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - j0).count());
      journalCutBytes.push_back(double(journal.bytes() - before));
    } catch (const std::exception&) {
      ++failures;
    }
  }
  std::vector<std::uint64_t> revisions;
  for (const BoneHistory::Entry& e : boneNode.history().entries()) revisions.push_back(e.revision);
  const auto r0 = std::chrono::steady_clock::now();
  const BoneHistory replayed = readHistoryJournal(journalPath, revisions, revisions.size() - 1);
  const double replayMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - r0).count();
  const bool replayedSame = replayed.current().liveTriangleCount() == boneNode.current().liveTriangleCount() &&
                            std::abs(replayed.current().volume() - boneNode.current().volume()) <=
                                1e-9 * std::abs(boneNode.current().volume());
  std::filesystem::remove(journalPath);
  // What a save and a reopen of the bone pay for its undo history (ui/SavedHistory.h does the same with these
  // calls): the whole history written at once into a fresh journal, then listed and replayed.
  const auto w0 = std::chrono::steady_clock::now();
  HistoryJournalWriter(journalPath).append(boneNode.history().entries());
  const double saveMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - w0).count();
  const std::uint64_t savedBytes = std::filesystem::file_size(journalPath);
  const auto o0 = std::chrono::steady_clock::now();
  const BoneHistory reopened = readHistoryJournal(journalPath, journalRevisions(journalPath), revisions.size() - 1);
  const double reopenMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - o0).count();
  const bool reopenedSame = reopened.size() == boneNode.history().size() &&
                            reopened.current().liveTriangleCount() == boneNode.current().liveTriangleCount() &&
                            std::abs(reopened.current().volume() - boneNode.current().volume()) <=
                                1e-9 * std::abs(boneNode.current().volume());
  std::filesystem::remove(journalPath);
  auto stats = [](const std::vector<double>& v) {
    return nlohmann::json{{"median_ms", percentile(v, 0.5)}, {"p95_ms", percentile(v, 0.95)}, {"p99_ms", percentile(v, 0.99)}};
  };
  return {{"what", "steps that cut, through ReamController (collision query + Boolean + next state + document commit)"},
          {"setup_ms", setupMs},
          {"cuts", step.size()},
          {"failures", failures},
          {"step", stats(step)},
          {"parts_median_ms", {{"contact", percentile(contact, 0.5)},
                               {"cut", percentile(cut, 0.5)},
                               {"state", percentile(state, 0.5)},
                               {"commit", percentile(commit, 0.5)}}},
          {"faces_end", boneNode.current().liveTriangleCount()},
          {"volume_end_mm3", boneNode.current().volume()},
          {"recovery_journal",
           {{"what", "the history journal appended after every cut (each with fdatasync), then replayed whole"},
            {"first_record_bytes", firstRecordBytes},
            {"bytes_per_cut_median", percentile(journalCutBytes, 0.5)},
            {"append_ms_median", percentile(journalAppendMs, 0.5)},
            {"append_ms_p99", percentile(journalAppendMs, 0.99)},
            {"states", revisions.size()},
            {"replay_ms", replayMs},
            {"replayed_state_matches", replayedSame}}},
          {"saved_history",
           {{"what", "the undo history a save writes beside the bone (one fresh journal, written whole), and its reopening "
                     "(listed and replayed)"},
            {"states", revisions.size()},
            {"bytes", savedBytes},
            {"save_ms", saveMs},
            {"reopen_ms", reopenMs},
            {"reopened_state_matches", reopenedSame}}}};
}

}  // namespace

int runBenchCut(const std::vector<std::string>& args) {
  CliArgs a(args,
            {"bone", "units", "subdivide", "steps", "depth", "tilt", "reamer", "check-every", "export-sequence",
             "peers-dir", "peers-budget-ms", "path", "cut-site", "cleanup-deviation-mm", "cleanup-min-edge-mm", "cleanup-min-angle-deg",
             "segments", "rings"},
            {"json", "peers", "table-5-1", "no-cleanup", "avoid-defects", "loop", "merge-coincident"});
  if (!a.positionals().empty()) throw UsageError("unexpected argument '" + a.positionals()[0] + "'");
  const std::string boneArg = a.value("bone", "default");
  const int steps = int(a.number("steps", 200));
  const int subdivisions = int(a.number("subdivide", 0));
  const int checkEvery = int(a.number("check-every", 0));
  if (steps < 1 || subdivisions < 0 || subdivisions > 3 || checkEvery < 0)
    throw UsageError("--steps >= 1, --subdivide 0..3, --check-every >= 0");

  TriangleMesh bone = benchMesh(boneArg, a.value("units", "auto"));  // as is: the local engine takes dirty bones
  // --merge-coincident: the first step of `ream`'s repair alone (vertices at one position, another index,
  // made one), so a CT mesh written strip by strip is cut as the application sees it; the peers get the
  // merged mesh too. Nothing else is repaired: borders and self-intersections stay.
  std::size_t mergedVertices = 0;
  if (a.has("merge-coincident")) bone = mergeCoincidentVertices(bone, &mergedVertices);
  for (int i = 0; i < subdivisions; ++i) bone = subdivideMidpoints(bone);  // the ~60k and ~240k scapulae
  const std::string pathKind = a.value("path", "jitter");
  if (pathKind != "jitter" && pathKind != "soak") throw UsageError("--path jitter|soak");
  // --segments / --rings: the preset at another resolution (how the reamed surface converges with it).
  const ReamerSpec spec = [&] {
    ReamerSpec s = loadPreset(a.value("reamer", "glenoid-36-R30"), reamerPresetsPath());
    s.segments = int(a.number("segments", s.segments));
    s.rings = int(a.number("rings", s.rings));
    try {
      validateReamerSpec(s);
    } catch (const std::invalid_argument& e) {
      throw UsageError(std::string("--segments/--rings: ") + e.what());
    }
    return s;
  }();
  const TriangleMesh localTool = buildCuttingSolid(spec);
  auto pathAt = [&](const Spot& s) {
    return pathKind == "soak" ? soakPath(s, steps, a.number("depth", 1.0))
                              : reamingPath(s, steps, a.number("depth", 3.0), a.number("tilt", 3.0));
  };
  const std::string site = a.value("cut-site", boneArg == "default" ? "glenoid" : "top");
  if (site != "glenoid" && site != "top") throw UsageError("--cut-site glenoid|top");
  const bool cleanSpot = a.has("avoid-defects") && boneArg != "default";
  const Spot spot = cleanSpot ? findCleanSpot(bone, localTool, pathAt) : findSpot(site, bone);
  const std::vector<Pose> poses = pathAt(spot);

  const double peersBudgetMs = a.number("peers-budget-ms", 60000);
  if (peersBudgetMs <= 0) throw UsageError("--peers-budget-ms > 0");
  if (a.has("export-sequence")) exportSequence(a.value("export-sequence"), bone, localTool, poses);

  // The machine's speed around ReamSim's steps (MachineSpeed.h): before the engine is made, and after.
  const nlohmann::json machineBefore = machineSpeed();
  const auto t0 = std::chrono::steady_clock::now();
  LocalSubtractor engine(bone);
  {
    BandCleanup cleanup;
    cleanup.enabled = !a.has("no-cleanup");
    cleanup.maxDeviationMm = a.number("cleanup-deviation-mm", cleanup.maxDeviationMm);
    cleanup.minEdgeMm = a.number("cleanup-min-edge-mm", cleanup.minEdgeMm);
    cleanup.minAngleDeg = a.number("cleanup-min-angle-deg", cleanup.minAngleDeg);
    engine.setBandCleanup(cleanup);
  }
  const double setupMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  std::vector<double> times, cutTimes;
  std::vector<double> perStep;  // one per step, NaN for a failed one (the peers' ratios over the same steps)
  std::size_t failures = 0, cuts = 0, checks = 0, exactSI = 0, roundedSI = 0, notClosed = 0, inputSIPairs = 0;
  std::map<std::string, std::size_t> failureKinds;
  double worstBookkeeping = 0, worstPiece = 0, removedTotal = 0, cleanupVolume = 0, cleanupDeviation = 0;
  std::size_t collapses = 0, flips = 0, roundingFailures = 0, cleanupReplanned = 0, redoneCuts = 0, movedOffSurface = 0;
  std::vector<double> cleanupTimes;
  std::map<std::string, std::vector<double>> phaseTimes;  // of the steps that cut
  std::map<std::string, std::vector<double>> sizes;       // of the steps that cut: faces handled
  const double volumeStart = engine.volumeMm3();
  const bool closedStart = engine.defects().borderEdges == 0;
  auto check = [&]() {
    const BoneInvariants inv = engine.checkInvariants();
    ++checks;
    if (closedStart && !(inv.closed && inv.outwardOriented)) ++notClosed;
    // The bone's own pairs (a dirty input) are not the engine's doing: counted apart, once.
    exactSI += inv.newSelfIntersectionsExact;
    roundedSI += inv.newSelfIntersectionsRounded;
    inputSIPairs = inv.inputSelfIntersectingPairs;
  };
  for (int i = 0; i < steps; ++i) {
    const TriangleMesh tool = placed(localTool, poses[i]);
    try {
      double ms = 0;
      const LocalCut c = timedSubtract(engine, tool, ms);
      times.push_back(ms);
      perStep.push_back(ms);
      if (c.changed) {
        ++cuts;
        cutTimes.push_back(ms);
        removedTotal += c.removedMm3;
        const double scale = std::max(1e-3, c.removedMm3);
        worstBookkeeping = std::max(worstBookkeeping, std::abs(c.removedMm3 - (c.volumeBeforeMm3 - c.volumeAfterMm3)) / scale);
        // The piece bone ∩ tool is what the Boolean removed; the band clean-up's change comes on top.
        worstPiece = std::max(worstPiece, std::abs(c.removedMm3 - c.cleanupVolumeMm3 - c.removedPieceMm3) / scale);
        cleanupVolume += c.cleanupVolumeMm3;
        cleanupDeviation = std::max(cleanupDeviation, c.cleanupDeviationMm);
        collapses += c.cleanupCollapses;
        flips += c.cleanupFlips;
        cleanupReplanned += c.cleanupReplanned ? 1 : 0;
        roundingFailures += c.roundingFailed ? 1 : 0;
        redoneCuts += c.redoneWithOffsetMm > 0 ? 1 : 0;
        movedOffSurface += c.toolMovedOffBoneSurface ? 1 : 0;
        cleanupTimes.push_back(c.cleanupMilliseconds);
        phaseTimes["setup"].push_back(c.phaseMilliseconds.setup);
        phaseTimes["corefine"].push_back(c.phaseMilliseconds.corefine);
        phaseTimes["classify"].push_back(c.phaseMilliseconds.classify);
        phaseTimes["rounding"].push_back(c.phaseMilliseconds.rounding);
        phaseTimes["rounding_check_thread"].push_back(c.phaseMilliseconds.roundingCheck);
        phaseTimes["commit"].push_back(c.phaseMilliseconds.commit);
        phaseTimes["cleanup"].push_back(c.cleanupMilliseconds);
        sizes["candidate_faces"].push_back(double(c.candidateFaces));
        sizes["near_bone_faces"].push_back(double(c.patchFaces));
        sizes["near_tool_faces"].push_back(double(c.nearToolFaces));
        sizes["removed_faces"].push_back(double(c.removedFaces));
        sizes["added_faces"].push_back(double(c.addedFaces));
        sizes["cleanup_collapses"].push_back(double(c.cleanupCollapses));
      }
    } catch (const CutError& e) {
      ++failures;
      ++failureKinds[toString(e.kind())];
      perStep.push_back(std::numeric_limits<double>::quiet_NaN());
    }
    if (checkEvery > 0 && (i + 1) % checkEvery == 0) check();
  }
  if (checkEvery > 0) check();
  const nlohmann::json machineAfter = machineSpeed();
  const TriangleMesh finalMesh = engine.mesh();

  nlohmann::json out = {
      {"bone", boneArg},
      {"allocator", allocatorName()},
      {"machine", {{"before", machineBefore}, {"after", machineAfter}}},
      {"subdivisions", subdivisions},
      {"merged_coincident_vertices", a.has("merge-coincident") ? nlohmann::json(mergedVertices) : nlohmann::json(nullptr)},
      {"reamer", spec.name},
      {"reamer_resolution", {{"segments", spec.segments}, {"rings", spec.rings}, {"faces", localTool.triangles.size()}}},
      {"faces_start", bone.triangles.size()},
      {"faces_end", finalMesh.triangles.size()},
      {"faces_ratio", double(finalMesh.triangles.size()) / double(bone.triangles.size())},
      {"steps", steps},
      {"path", pathKind},
      {"cut_site", cleanSpot ? "clean spot (--avoid-defects)" : site},
      {"spot", {{"centre", {spot.centre.x, spot.centre.y, spot.centre.z}}, {"inward", {spot.inward.x, spot.inward.y, spot.inward.z}}}},
      {"cuts", cuts},
      {"setup_ms", setupMs},
      {"median_ms", percentile(times, 0.5)},
      {"p95_ms", percentile(times, 0.95)},
      {"p99_ms", percentile(times, 0.99)},
      {"median_ms_changed", percentile(cutTimes, 0.5)},
      {"phases_median_ms_changed", [&] {
         nlohmann::json j = nlohmann::json::object();
         for (const auto& [name, t] : phaseTimes) j[name] = percentile(t, 0.5);
         return j;
       }()},
      {"cut_sizes_median_changed", [&] {
         nlohmann::json j = nlohmann::json::object();
         for (const auto& [name, n] : sizes) j[name] = percentile(n, 0.5);
         return j;
       }()},
      {"failures", failures},
      {"failure_kinds", failureKinds},
      {"checks", checks},
      {"closed", checks == 0 ? nlohmann::json(nullptr) : nlohmann::json(closedStart && notClosed == 0)},
      {"self_intersections", checks == 0 ? nlohmann::json(nullptr)
                                         : nlohmann::json({{"exact_checks_failed", exactSI},
                                                           {"rounded_checks_failed", roundedSI},
                                                           {"input_pairs_not_counted", inputSIPairs}})},
      {"volume_error_rel", worstBookkeeping},
      {"piece_volume_error_rel", worstPiece},
      {"removed_mm3", removedTotal},
      {"volume_drop_mm3", volumeStart - engine.volumeMm3()},
      {"exact_vertices_end", engine.exactVertexCount()},
      {"rounding_failures", roundingFailures},
      {"redone_with_offset", redoneCuts},
      {"moved_off_bone_surface", movedOffSurface},
      {"band_cleanup", {{"enabled", engine.bandCleanup().enabled},
                        {"max_deviation_mm", engine.bandCleanup().enabled ? nlohmann::json(cleanupDeviation)
                                                                          : nlohmann::json(nullptr)},  // as used
                        {"collapses", collapses},
                        {"flips", flips},
                        {"replanned_cuts", cleanupReplanned},
                        {"volume_change_mm3", cleanupVolume},
                        {"median_ms", percentile(cleanupTimes, 0.5)}}},
      {"min_angle_deg", minAngleDeg(finalMesh)},
      {"faces_by_smallest_angle", facesBelowAngle(finalMesh)},
      {"cut_faces", cutFacesQuality(bone, finalMesh)},
      {"defects", {{"self_intersecting_pairs", engine.defects().selfIntersectingPairs},
                   {"self_intersecting_faces", engine.defects().selfIntersectingFaces},
                   {"non_manifold_faces", engine.defects().nonManifoldFaces},
                   {"degenerate_faces", engine.defects().degenerateFaces},
                   {"border_edges", engine.defects().borderEdges}}}};
  if (spec.meshFile.empty() && !poses.empty()) {
    out["reamed_surface"] =
        reamedSurfaceJson(measureReamedSurface(finalMesh, spec, poses.back(), kReamedSurfaceBandMm), kReamedSurfaceBandMm);
  }

  if (a.has("peers")) {
    nlohmann::json peers;
    // manifold-3d first, right after ReamSim's own run: the ratio the issue asks for (>= 5x) compares two runs
    // seconds apart rather than half a minute (the CGAL reference's 200 steps took that long in between), so
    // that the machine's drift moves both alike.
    // The npm peers (node, bench/peers) run the exported sequence: --export-sequence DIR, else a scratch dir.
    const std::string peersDir = a.value("peers-dir", defaultPeersDir());
    const std::string why = nodePeersUnavailable(peersDir);
    if (!why.empty()) {
      peers["manifold_3d"] = {{"not_run", why}};
      peers["csgjs_bsp"] = {{"not_run", why}};
    } else {
      namespace fs = std::filesystem;
      const bool scratch = !a.has("export-sequence");
      const std::string seqDir = scratch ? (fs::temp_directory_path() / ("reamsim_bench_seq_" + std::to_string(::getpid()))).string()
                                         : a.value("export-sequence");
      if (scratch) exportSequence(seqDir, bone, localTool, poses);
      const double volumeEnd = engine.volumeMm3();
      peers["manifold_3d"] = peerEntry(runNodePeer(peersDir, "manifold-3d", seqDir, peersBudgetMs), perStep, volumeEnd);
      peers["csgjs_bsp"] = peerEntry(runNodePeer(peersDir, "csgjs-bsp", seqDir, peersBudgetMs), perStep, volumeEnd);
      std::error_code ec;
      if (scratch) fs::remove_all(seqDir, ec);
    }
    try {
      ReferenceSubtractor reference(bone);
      std::vector<double> refTimes;
      for (const Pose& p : poses) {
        double ms = 0;
        timedSubtract(reference, placed(localTool, p), ms);
        refTimes.push_back(ms);
      }
      const double med = percentile(refTimes, 0.5);
      peers["cgal_corefinement_epeck"] = {{"median_ms", med},
                                          {"ratio_to_reamsim", med / std::max(1e-9, percentile(times, 0.5))},
                                          {"volume_end_mm3", reference.volumeMm3()},
                                          {"volume_end_diff_rel", std::abs(reference.volumeMm3() - engine.volumeMm3()) /
                                                                      reference.volumeMm3()}};
    } catch (const std::exception& e) {
      peers["cgal_corefinement_epeck"] = {{"refused", e.what()}};
    }
    out["peers"] = peers;
  }
  if (a.has("loop")) {
    out["loop"] = appLoop(bone, spec, localTool, poses, !a.has("no-cleanup"));
    out["loop"]["moves_past_bone"] = movesPastBone(bone, spec, localTool, poses.front());
    out["loop"]["ream_to_depth_search"] = reamToDepthSearch(bone, spec, localTool, poses.front());
    out["loop"]["clear_placement"] = clearPlacement(bone, spec, localTool, poses.front());
    out["loop"]["glenoid_face"] = glenoidFaceCost(bone, poses.front());
    // On the bone the path reamed, at its last pose: the seat equals reamed_surface's (a check as well as a time).
    if (spec.meshFile.empty()) out["loop"]["preview_seat"] = previewSeatCost(finalMesh, spec, poses.back());
    out["loop"]["volume_end_diff_rel"] =
        std::abs(out["loop"]["volume_end_mm3"].get<double>() - engine.volumeMm3()) / engine.volumeMm3();
  }
  if (a.has("table-5-1")) out["table_5_1"] = table51(bone, localTool, spot);
  out["swept_hull"] = sweptHulls(localTool, poses);

  std::cout << out.dump(a.has("json") ? -1 : 2) << "\n";
  const bool clearPlacementWrong = out.contains("loop") && out["loop"].contains("clear_placement") &&
                                   out["loop"]["clear_placement"].value("not_nearest_clear", 0) > 0;
  return failures == 0 && notClosed == 0 && exactSI == 0 && !clearPlacementWrong ? kOk : kFailed;
}

}  // namespace reamsim::cli
