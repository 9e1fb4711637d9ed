// bench collision: times the collision queries of modules/collision over poses near the bone surface, and in
// the same run the thesis's brute-force path (bounding boxes + Moeller-Trumbore over all faces) and CGAL's
// AABB_tree for the queries CGAL has; then times the BVH's local update after a sequence of real cuts.
// Prints one JSON object (docs/COLLISION.md explains every field).
#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <locale>
#include <nlohmann/json.hpp>
#include <numeric>
#include <random>

#include "BenchStats.h"
#include "CliArgs.h"
#include "Commands.h"
#include "DefaultCase.h"
#include "HandHeldPath.h"
#include "MachineSpeed.h"
#include "reamsim/collision/BoneCollider.h"
#include "reamsim/collision/CgalAabbBaseline.h"
#include "reamsim/collision/MeshRayCast.h"
#include "reamsim/collision/SyntheticCut.h"
#include "reamsim/collision/ThesisContact.h"
#include "reamsim/csg/LocalSubtractor.h"
#include "reamsim/csg/ReferenceSubtractor.h"
#include "reamsim/mesh/MeshError.h"
#include "reamsim/mesh/MeshIO.h"
#include "reamsim/tools/ReamerFile.h"
#include "reamsim/tools/ReamerGeometry.h"
#include "reamsim/tools/ReamerPresets.h"

namespace reamsim::cli {
namespace {

using Clock = std::chrono::steady_clock;
using nlohmann::json;
constexpr double kPi = 3.14159265358979323846;

double microsSince(Clock::time_point t0) {
  return std::chrono::duration<double, std::micro>(Clock::now() - t0).count();
}

// `within_20us`: how many samples meet the 20 µs target. A median near the line moves with the
// machine's speed; the count says how many queries a change has to bring under it (docs/COLLISION.md).
json summary(const std::vector<double>& us) {
  if (us.empty()) return nullptr;
  return {{"median_us", percentile(us, 0.5)},
          {"p99_us", percentile(us, 0.99)},
          {"mean_us", std::accumulate(us.begin(), us.end(), 0.0) / double(us.size())},
          {"samples", us.size()},
          {"within_20us", std::count_if(us.begin(), us.end(), [](double t) { return t <= 20.0; })}};
}

// Runs f(i) for i in [0, n), one timing per call, stopping early (after at least minSamples) once the time
// budget is spent: the brute-force paths take seconds per query on large bones.
template <class F>
std::vector<double> timeEach(std::size_t n, F&& f, double budgetSeconds = 1e300, std::size_t minSamples = 3) {
  std::vector<double> us;
  us.reserve(n);
  const auto start = Clock::now();
  for (std::size_t i = 0; i < n; ++i) {
    const auto t0 = Clock::now();
    f(i);
    us.push_back(microsSince(t0));
    if (us.size() >= minSamples && microsSince(start) * 1e-6 > budgetSeconds) break;
  }
  return us;
}

Vec3 rotate(const Vec3& v, const Vec3& k, double angle) {
  return v * std::cos(angle) + cross(k, v) * std::sin(angle) + k * (dot(k, v) * (1 - std::cos(angle)));
}

// Area-weighted surface samples: a point and its triangle's unit normal.
class SurfaceSampler {
 public:
  explicit SurfaceSampler(const TriangleMesh& m) : m_(m) {
    double acc = 0;
    for (const Triangle& t : m.triangles) {
      acc += norm(cross(m.vertices[t[1]] - m.vertices[t[0]], m.vertices[t[2]] - m.vertices[t[0]]));
      cumulative_.push_back(acc);
    }
  }
  void sample(std::mt19937_64& rng, Vec3& point, Vec3& normal) const {
    std::uniform_real_distribution<double> u(0, 1);
    const double r = u(rng) * cumulative_.back();
    const std::size_t i = std::min(cumulative_.size() - 1, static_cast<std::size_t>(
        std::upper_bound(cumulative_.begin(), cumulative_.end(), r) - cumulative_.begin()));
    const Triangle& t = m_.triangles[i];
    double a = u(rng), b = u(rng);
    if (a + b > 1) { a = 1 - a; b = 1 - b; }
    const Vec3 p0 = m_.vertices[t[0]], e1 = m_.vertices[t[1]] - p0, e2 = m_.vertices[t[2]] - p0;
    point = p0 + e1 * a + e2 * b;
    normal = normalized(cross(e1, e2));
  }

 private:
  const TriangleMesh& m_;
  std::vector<double> cumulative_;
};

// A pose whose tip is `offset` mm off the surface along the feed axis, tilted up to maxTiltDeg from the normal.
Pose poseNear(const SurfaceSampler& s, std::mt19937_64& rng, double minOffset, double maxOffset, double maxTiltDeg) {
  std::uniform_real_distribution<double> u(0, 1);
  Vec3 p, n;
  s.sample(rng, p, n);
  const Vec3 k = rotate(anyPerpendicular(n), n, 2 * kPi * u(rng));
  Pose pose;
  pose.axis = normalized(rotate(-n, k, maxTiltDeg * kPi / 180 * u(rng)));
  pose.tip = p - pose.axis * (minOffset + (maxOffset - minOffset) * u(rng));
  pose.rollDeg = 360 * u(rng);
  return pose;
}

RigidTransform turned(const RigidTransform& t, const Vec3& k, double angle) {
  RigidTransform out = t;
  for (int c = 0; c < 3; ++c) {
    const Vec3 col = rotate({t.rotation[c], t.rotation[3 + c], t.rotation[6 + c]}, k, angle);
    out.rotation[c] = col.x;
    out.rotation[3 + c] = col.y;
    out.rotation[6 + c] = col.z;
  }
  return out;
}

TriangleMesh posed(const TriangleMesh& local, const RigidTransform& t) {
  TriangleMesh out = local;
  for (Vec3& v : out.vertices) v = t.apply(v);
  return out;
}

struct Reamer {
  std::string name;
  ReamerModel model;
  int segments = 0, rings = 0;  // a preset's tessellation as benchmarked (0 for a mesh file)
};

// The collision issue measures its queries with a reamer of 2k-5k faces. The presets' own 96 x 12 give
// 1,484 faces since their cap rings follow the radius (docs/REAMERS.md), so the bench refines a preset to
// 128 x 16 (2,5xx faces) unless --segments / --rings say otherwise.
constexpr int kBenchSegments = 128, kBenchRings = 16;

// A preset is modelled as the application models a reamer node (its cutting volume and the spec it was
// built from); `solidOnly` drops the spec, as for a cutting solid read from a file.
Reamer loadReamer(const std::string& arg, bool solidOnly, int segments, int rings) {
  if (std::filesystem::is_regular_file(arg))
    return {std::filesystem::path(arg).filename().string(), ReamerModel::fromSolid(loadCuttingSolidFromFile(arg))};
  ReamerSpec spec = loadPreset(arg, reamerPresetsPath());
  spec.segments = segments;
  spec.rings = rings;
  return {spec.name, ReamerModel::fromCuttingVolume(buildCuttingSolid(spec), solidOnly ? nullptr : &spec), segments,
          rings};
}

struct CutSite {
  Vec3 point, outward;  // a surface point and the direction out of the bone there
  std::string name;
};

// Applies an update to `collider`, timing it as the best of three runs on copies (the machine is shared:
// the minimum is the cost of the update itself, not of whatever else was scheduled).
template <class F>
BvhUpdateStats timedUpdate(BoneCollider& collider, F&& apply) {
  double best = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 2; ++k) {
    BoneCollider copy = collider;
    best = std::min(best, apply(copy).milliseconds);
  }
  BvhUpdateStats s = apply(collider);
  s.milliseconds = std::min(best, s.milliseconds);
  return s;
}

// The penetrating ticks' axial penetration by the parametric reamer's face-as-height-field path and by the
// general two-tree path (the same solid read as a plain mesh), alternating which goes first tick by tick,
// so the ratio comes from one run; and whether the two depths agree.
json penetrationAgainstGeneralPath(const BoneCollider& collider, const ReamerModel& rm, const std::vector<HandHeldTick>& ticks) {
  const ReamerModel general = ReamerModel::fromSolid(rm.solid());
  std::vector<double> fastUs, generalUs;
  std::size_t disagreements = 0;
  for (std::size_t i = 0; i < ticks.size(); ++i) {
    PenetrationResult r[2];
    double us[2];
    for (int k = 0; k < 2; ++k) {
      const int which = (i + k) % 2;  // 0: the face path, 1: the general path
      const auto t0 = Clock::now();
      r[which] = collider.axialPenetration(which == 0 ? rm : general, ticks[i].to);
      us[which] = microsSince(t0);
    }
    disagreements += r[0].penetrating != r[1].penetrating || r[0].enclosed != r[1].enclosed ||
                     !(std::abs(r[0].depthMm - r[1].depthMm) <= kChainToleranceRelative * std::max(1.0, rm.radius()));
    if (!r[0].penetrating) continue;
    fastUs.push_back(us[0]);
    generalUs.push_back(us[1]);
  }
  json j = {{"what", "penetrating ticks of the hand-held path again: the parametric reamer's face as a height field "
                     "(CapShadow, the path used) against the general path over the same solid read as a plain mesh "
                     "(reamer and bone trees paired), alternating which goes first"},
            {"ticks", fastUs.size()},
            {"disagreements", disagreements}};  // over all ticks, penetrating or not
  if (!fastUs.empty()) {
    j["median_us"] = summary(fastUs)["median_us"];
    j["general_path_median_us"] = summary(generalUs)["median_us"];
    j["general_over_this"] = double(j["general_path_median_us"]) / double(j["median_us"]);
  }
  return j;
}

// The BVH's local update after a sequence of feed steps at one site: exact CGAL cuts (closed bones) followed
// by commitByDiff + the slot diff, ReamSim's own cutting engine (LocalSubtractor with its band clean-up, the
// cut the application makes) followed by the slot diff, or the synthetic dent cut (open bones).
json benchUpdates(const TriangleMesh& mesh, BoneState state, BoneCollider& collider, const ReamerModel& reamer,
                  const CutSite& site, int steps, const std::string& mode) {
  std::unique_ptr<ReferenceSubtractor> engine;
  std::unique_ptr<LocalSubtractor> local;
  std::string kind = "dent (synthetic: touched faces replaced, inside vertices pushed onto the reamer)";
  if (mode == "local") {
    local = std::make_unique<LocalSubtractor>(state);
    kind = "local (ReamSim's cutting engine with its band clean-up, as the application cuts) + changed slots";
  } else if (mode != "dent") {
    try {
      engine = std::make_unique<ReferenceSubtractor>(mesh);
      kind = "exact (CGAL corefinement reference) + BoneState::commitByDiff + changed slots";
    } catch (const std::exception& e) {
      if (mode == "exact") throw;
      std::fprintf(stderr, "note: exact cuts unavailable (%s); using the synthetic dent cut\n", e.what());
    }
  }
  std::vector<double> updateMs, diffMs;
  std::vector<double> removed, added;
  std::size_t rebuiltSubtrees = 0;
  for (int k = 0; k < steps; ++k) {
    Pose p;
    p.axis = -site.outward;
    p.tip = site.point + site.outward * 0.5 + p.axis * (0.35 * (k + 1));  // 0.35 mm feed per step
    const RigidTransform T = toTransform(p);
    if (engine || local) {
      BoneState next;
      if (local) {
        try {
          if (!local->subtract(posed(reamer.solid(), T)).changed) continue;
        } catch (const CutError& e) {  // the tool reached a defect or an open border: that step is not cut
          std::fprintf(stderr, "note: feed step %d not cut by ReamSim's engine (%s)\n", k + 1, e.what());
          continue;
        }
        next = local->state();
      } else {
        if (!engine->subtract(posed(reamer.solid(), T)).changed) continue;
        next = BoneState::commitByDiff(state, engine->mesh());
      }
      const auto t0 = Clock::now();
      const SlotChanges changes = collider.changesTo(next);
      diffMs.push_back(microsSince(t0) * 1e-3);
      const BvhUpdateStats s = timedUpdate(collider, [&](BoneCollider& c) { return c.update(next, changes.removed, changes.added); });
      updateMs.push_back(s.milliseconds);
      removed.push_back(double(s.removed));
      added.push_back(double(s.added));
      rebuiltSubtrees += s.rebuiltSubtrees;
      state = next;
    } else {
      const OverlapResult touched = collider.overlap(reamer, T);
      if (touched.touchedSlots.empty()) continue;
      const MeshDelta delta = dentDelta(state, touched.touchedSlots, reamer, T);
      DeltaPlacement placement;
      const BoneState next = state.applyDelta(delta, &placement);
      const BvhUpdateStats s = timedUpdate(collider, [&](BoneCollider& c) { return c.applyDelta(next, delta, placement); });
      updateMs.push_back(s.milliseconds);
      removed.push_back(double(s.removed));
      added.push_back(double(s.added));
      rebuiltSubtrees += s.rebuiltSubtrees;
      state = next;
    }
  }
  const std::string problem = collider.bvh().validate();
  if (!problem.empty()) throw std::runtime_error("BVH inconsistent after the cuts: " + problem);
  const double fresh = BoneCollider(state).bvh().quality().sahCost;
  auto median = [](std::vector<double> v) { return v.empty() ? 0.0 : percentile(std::move(v), 0.5); };
  json j = {{"kind", kind},
            {"site", site.name},
            {"feed_steps", steps},
            {"cuts", updateMs.size()},
            {"median_ms", median(updateMs)},
            {"max_ms", updateMs.empty() ? 0.0 : *std::max_element(updateMs.begin(), updateMs.end())},
            {"median_removed_faces", median(removed)},
            {"median_added_faces", median(added)},
            {"faces_after", state.liveTriangleCount()},
            {"rebuilt_subtrees", rebuiltSubtrees},
            {"sah_cost_vs_fresh_build", fresh > 0 ? collider.bvh().quality().sahCost / fresh : 0.0}};
  if (!diffMs.empty()) j["slot_diff_ms_median"] = median(diffMs);
  return j;
}

void addComparison(json& q, const std::string& key, const std::vector<double>& ours, const std::vector<double>& other,
                   const std::string& otherName) {
  if (other.empty()) {
    q[otherName] = nullptr;
    return;
  }
  q[otherName] = summary(other);
  q[key] = percentile(other, 0.5) / std::max(1e-3, percentile(ours, 0.5));
}

// The random motions' first contacts one per row (--samples-out): what the JSON's medians and mean work counts
// summarise, so that which motions sit near the 20 us line, and why, can be read without a patch.
// Opened before the bench runs, so that a path it cannot write is said at once, not after minutes of timing.
std::ofstream openSamplesFile(const std::string& path) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out) throw InputError(path, "cannot write the samples file (" + std::string(std::strerror(errno)) + ")");
  out.imbue(std::locale::classic());
  return out;
}

void writeFirstContactSamples(std::ofstream& out, const std::string& path, const std::vector<double>& us,
                              const std::vector<int>& kind, const std::vector<FirstContactResult::Work>& work,
                              const std::vector<std::size_t>& pairs) {
  static const char* const kOutcome[3] = {"no_contact", "touching_at_start", "contact_during_motion"};
  out << "motion,outcome,us,start_test_nodes,sweep_pass_nodes,hull_bounds,pair_bounds,exact_pairs\n";
  char time[32];
  for (std::size_t i = 0; i < us.size(); ++i) {
    std::snprintf(time, sizeof time, "%.3f", us[i]);
    out << i << ',' << kOutcome[kind[i]] << ',' << time << ',' << work[i].startTestNodes << ','
        << work[i].sweepPassNodes << ',' << work[i].hullBounds << ',' << work[i].pairBounds << ',' << pairs[i] << '\n';
  }
  out.flush();
  if (!out) throw InputError(path, "could not write the samples file (disk full?)");
}

}  // namespace

int runBenchCollision(const std::vector<std::string>& args) {
  CliArgs a(args,
            {"bone", "reamer", "segments", "rings", "units", "poses", "seed", "label", "cut-site", "cut", "cut-steps", "thesis-budget-s",
             "cgal-budget-s", "hand-held-approaches", "samples-out"},
            {"json", "no-baselines", "solid-only"});
  if (!a.positionals().empty()) throw UsageError("unexpected argument '" + a.positionals()[0] + "'");
  const std::string boneArg = a.required("bone");
  const std::size_t n = static_cast<std::size_t>(a.number("poses", 1000));
  const std::uint64_t seed = static_cast<std::uint64_t>(a.number("seed", 1));
  const int cutSteps = static_cast<int>(a.number("cut-steps", 6));
  const double thesisBudget = a.number("thesis-budget-s", 20), cgalBudget = a.number("cgal-budget-s", 20);
  const std::string cutMode = a.value("cut", "auto");
  if (cutMode != "auto" && cutMode != "exact" && cutMode != "dent")
    throw UsageError("--cut must be auto, exact or dent, not '" + cutMode + "'");
  if (n < 10) throw UsageError("--poses must be at least 10");
  const int handApproaches = static_cast<int>(a.number("hand-held-approaches", 8));
  if (handApproaches < 0) throw UsageError("--hand-held-approaches must be 0 (none) or more");
  const std::string samplesPath = a.value("samples-out", "");
  if (a.has("samples-out") && samplesPath.empty()) throw UsageError("--samples-out needs a file name");
  std::ofstream samplesOut;
  if (!samplesPath.empty()) samplesOut = openSamplesFile(samplesPath);

  // Bone: used as given (no repair): the bench measures the mesh it is pointed at.
  std::vector<std::string> notes;
  const TriangleMesh mesh = benchMesh(boneArg, a.value("units", "auto"), &notes);
  for (const std::string& note : notes) std::fprintf(stderr, "note: %s: %s\n", boneArg.c_str(), note.c_str());
  std::string label = a.value("label", boneArg);
  if (boneArg == "default" && !a.has("label"))
    label = "bundled default scapula (repaired), resources/" + std::string(kDefaultBoneFile);
  if (mesh.triangles.empty()) throw InputError(boneArg, "the mesh has no triangles");
  const std::string reamerArg = a.value("reamer", "glenoid-36-R30");
  if ((a.has("segments") || a.has("rings")) && std::filesystem::is_regular_file(reamerArg))
    throw UsageError("--segments and --rings refine a preset, not a reamer read from a file");
  const Reamer reamer = loadReamer(reamerArg, a.has("solid-only"), static_cast<int>(a.number("segments", kBenchSegments)),
                                   static_cast<int>(a.number("rings", kBenchRings)));
  const ReamerModel& rm = reamer.model;

  // The machine's speed around the timed queries (MachineSpeed.h): before the tree is built, and after.
  const json machineBefore = machineSpeed();

  // --- build ---
  const BoneState state = BoneState::fromMesh(mesh);
  BoneCollider collider(state);
  const TriangleBvh& bvh = collider.bvh();
  const Bounds boneBounds = computeBounds(mesh);

  // --- query sets: poses near the surface, motions towards it, rays ---
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  const SurfaceSampler sampler(mesh);
  std::vector<RigidTransform> poses, from, to, tickFrom, tickTo;
  std::vector<Vec3> rayOrigin, rayDir;
  for (std::size_t i = 0; i < n; ++i) {
    const Pose p = poseNear(sampler, rng, -1.5, 3.0, 20);
    poses.push_back(toTransform(p));
    // Motion: from 0.5-3 mm off the surface, 0-4 mm along the feed with 0.5 mm drift and up to 5 degrees of turn.
    const Pose s = poseNear(sampler, rng, 0.5, 3.0, 20);
    const RigidTransform f = toTransform(s);
    RigidTransform t = turned(f, normalized(Vec3{u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5}), 5 * kPi / 180 * u(rng));
    t.translation = s.tip + s.axis * (4 * u(rng)) + anyPerpendicular(s.axis) * (0.5 * (u(rng) - 0.5));
    from.push_back(f);
    to.push_back(t);
    // Haptic tick: one 1 ms step of a hand-held device at up to 100 mm/s and 100 deg/s (<= 0.1 mm of travel,
    // <= 0.1 degree of turn), starting 0-0.1 mm before the pose where a feed along the axis first touches the
    // bone: the ticks right before and at contact, where the query has work to do (about half touch).
    RigidTransform hf, ht;
    for (int attempt = 0; attempt < 20; ++attempt) {
      const Pose hs = poseNear(sampler, rng, 0.5, 3.0, 20);
      RigidTransform far = toTransform(hs);
      far.translation = hs.tip + hs.axis * 6.0;
      const FirstContactResult touch = collider.firstContact(rm, toTransform(hs), far);
      hf = toTransform(hs);
      hf.translation = hs.tip + hs.axis * std::max(0.0, 6.0 * touch.t - 0.1 * u(rng));
      ht = turned(hf, normalized(Vec3{u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5}), 0.1 * kPi / 180 * u(rng));
      ht.translation = hf.translation + hs.axis * (0.1 * u(rng)) + anyPerpendicular(hs.axis) * (0.02 * (u(rng) - 0.5));
      if (touch.hit && touch.t > 0) break;
    }
    tickFrom.push_back(hf);
    tickTo.push_back(ht);
    // Rays: along the feed from 5 mm behind the tip (the thesis's probe direction) and in random directions.
    rayOrigin.push_back(p.tip - p.axis * 5.0);
    rayDir.push_back(i % 2 ? p.axis : normalized(Vec3{u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5}));
  }

  // --- BVH queries (warm the caches first) ---
  std::size_t positives[8] = {};
  for (std::size_t i = 0; i < std::min<std::size_t>(n, 50); ++i) (void)collider.faceDistance(rm, poses[i]);
  json queries;
  const auto tOverlapAny = timeEach(n, [&](std::size_t i) { positives[0] += collider.overlap(rm, poses[i], OverlapMode::AnyContact).overlap; });
  std::size_t touchedTotal = 0;
  const auto tOverlapAll = timeEach(n, [&](std::size_t i) { touchedTotal += collider.overlap(rm, poses[i]).touchedSlots.size(); });
  std::size_t pairs[3] = {};
  std::size_t distanceNodes = 0;
  const auto tDistance = timeEach(n, [&](std::size_t i) {
    const DistanceResult r = collider.faceDistance(rm, poses[i]);
    positives[2] += r.distanceMm == 0;
    pairs[0] += r.trianglePairs;
    distanceNodes += r.nodesOpened;
  });
  std::vector<int> contactKind(n, 0);  // 0 no contact, 1 touching at the start, 2 contact during the motion
  std::vector<FirstContactResult::Work> contactWork(n);
  std::vector<std::size_t> contactPairs(n, 0);
  const auto tContact = timeEach(n, [&](std::size_t i) {
    const FirstContactResult r = collider.firstContact(rm, from[i], to[i]);
    positives[3] += r.hit;
    pairs[1] += r.trianglePairs;
    contactKind[i] = !r.hit ? 0 : (r.t == 0 ? 1 : 2);
    contactWork[i] = r.work;
    contactPairs[i] = r.trianglePairs;
  });
  if (samplesOut.is_open()) writeFirstContactSamples(samplesOut, samplesPath, tContact, contactKind, contactWork, contactPairs);
  std::size_t tickHits = 0, tickPairs = 0;
  const auto tTick = timeEach(n, [&](std::size_t i) {
    const FirstContactResult r = collider.firstContact(rm, tickFrom[i], tickTo[i]);
    tickHits += r.hit;
    tickPairs += r.trianglePairs;
  });
  const auto tRay = timeEach(n, [&](std::size_t i) { positives[4] += collider.firstHit(rayOrigin[i], rayDir[i]).has_value(); });
  const auto tRayCulled = timeEach(n, [&](std::size_t i) { positives[5] += collider.firstHit(rayOrigin[i], rayDir[i], Culling::BackFaces).has_value(); });
  std::size_t crossings = 0;
  const auto tRayAll = timeEach(n, [&](std::size_t i) { crossings += collider.allHits(rayOrigin[i], rayDir[i]).size(); });
  const auto tPenetration = timeEach(n, [&](std::size_t i) {
    const PenetrationResult r = collider.axialPenetration(rm, poses[i]);
    positives[7] += r.depthMm > 0;
    pairs[2] += r.trianglePairs;
  });

  const json machineAfter = machineSpeed();

  queries["overlap_any"] = summary(tOverlapAny);
  queries["overlap_any"]["overlapping_poses"] = positives[0];
  queries["overlap_faces"] = summary(tOverlapAll);
  queries["overlap_faces"]["mean_touched_faces"] = double(touchedTotal) / double(n);
  queries["min_distance"] = summary(tDistance);
  queries["min_distance"]["touching_poses"] = positives[2];
  queries["min_distance"]["mean_triangle_pairs"] = double(pairs[0]) / double(n);
  queries["min_distance"]["mean_nodes_opened"] = double(distanceNodes) / double(n);
  queries["first_contact"] = summary(tContact);
  queries["first_contact"]["motions_with_contact"] = positives[3];
  queries["first_contact"]["mean_triangle_pairs"] = double(pairs[1]) / double(n);
  {
    // The three kinds of motion cost very differently: say which is which rather than only the mix.
    std::vector<double> kind[3];
    for (std::size_t i = 0; i < tContact.size(); ++i) kind[contactKind[i]].push_back(tContact[i]);
    queries["first_contact"]["by_outcome"] = {{"no_contact", summary(kind[0])},
                                              {"touching_at_start", summary(kind[1])},
                                              {"contact_during_motion", summary(kind[2])}};
    // What each kind of motion did, as mean counts per query (FirstContactResult::Work): where its time goes.
    const char* names[3] = {"no_contact", "touching_at_start", "contact_during_motion"};
    for (int k = 0; k < 3; ++k) {
      double startNodes = 0, passNodes = 0, hullBounds = 0, pairBounds = 0, exactPairs = 0, count = 0;
      for (std::size_t i = 0; i < n; ++i) {
        if (contactKind[i] != k) continue;
        startNodes += double(contactWork[i].startTestNodes);
        passNodes += double(contactWork[i].sweepPassNodes);
        hullBounds += double(contactWork[i].hullBounds);
        pairBounds += double(contactWork[i].pairBounds);
        exactPairs += double(contactPairs[i]);
        ++count;
      }
      if (count == 0) continue;
      queries["first_contact"]["by_outcome"][names[k]]["mean_work"] = {
          {"start_test_nodes", startNodes / count}, {"sweep_pass_nodes", passNodes / count},
          {"hull_bounds", hullBounds / count},      {"pair_bounds", pairBounds / count},
          {"exact_pairs", exactPairs / count}};
    }
  }
  queries["first_contact_haptic_tick"] = summary(tTick);
  queries["first_contact_haptic_tick"]["motions_with_contact"] = tickHits;
  queries["first_contact_haptic_tick"]["mean_triangle_pairs"] = double(tickPairs) / double(n);
  queries["ray_first_hit"] = summary(tRay);
  queries["ray_first_hit"]["hits"] = positives[4];
  queries["ray_first_hit_culled"] = summary(tRayCulled);
  queries["ray_first_hit_culled"]["hits"] = positives[5];
  queries["ray_all_hits"] = summary(tRayAll);
  queries["ray_all_hits"]["mean_crossings"] = double(crossings) / double(n);
  queries["penetration_depth"] = summary(tPenetration);
  queries["penetration_depth"]["penetrating_poses"] = positives[7];
  queries["penetration_depth"]["mean_triangle_pairs"] = double(pairs[2]) / double(n);

  json thesisInfo = nullptr, cgalInfo = nullptr, checks = json::object();
  if (!a.has("no-baselines")) {
    // --- the thesis's path: boxes + Moeller-Trumbore over all faces ---
    std::vector<Vec3> probesLocal;
    for (std::uint32_t f : rm.faceTriangles())
      for (std::uint32_t v : rm.solid().triangles[f]) probesLocal.push_back(rm.solid().vertices[v]);
    std::sort(probesLocal.begin(), probesLocal.end(),
              [](const Vec3& p, const Vec3& q) { return std::tie(p.x, p.y, p.z) < std::tie(q.x, q.y, q.z); });
    probesLocal.erase(std::unique(probesLocal.begin(), probesLocal.end()), probesLocal.end());
    auto thesisAt = [&](const RigidTransform& T, double step) {
      std::vector<Vec3> probes;
      probes.reserve(probesLocal.size());
      for (const Vec3& p : probesLocal) probes.push_back(T.apply(p));
      return thesisContactQuery(mesh, boneBounds, posed(rm.solid(), T), probes, T.applyToDirection({0, 0, 1}), step);
    };
    const auto thContact = timeEach(n, [&](std::size_t i) { (void)thesisAt(poses[i], 0.0); }, thesisBudget);
    const auto thMotion = timeEach(n, [&](std::size_t i) {
      const Vec3 d = to[i].translation - from[i].translation;
      (void)thesisAt(from[i], norm(d));
    }, thesisBudget);
    const auto thRay = timeEach(n, [&](std::size_t i) { (void)firstHit(mesh, rayOrigin[i], rayDir[i]); }, thesisBudget, 20);
    const auto thRayCulled = timeEach(n, [&](std::size_t i) { (void)firstHit(mesh, rayOrigin[i], rayDir[i], Culling::BackFaces); }, thesisBudget, 20);
    const auto thRayAll = timeEach(n, [&](std::size_t i) { (void)allHits(mesh, rayOrigin[i], rayDir[i]); }, thesisBudget, 20);
    // A click on the bone in the view (BoneView::boneSurfaceAt): the brute force over the bone state in place,
    // against the same over a mesh copy of the state (what the view did before session 55).
    const auto pickInPlace = timeEach(n, [&](std::size_t i) { (void)firstHit(state, rayOrigin[i], rayDir[i]); }, thesisBudget, 20);
    const auto pickWithCopy = timeEach(n, [&](std::size_t i) { (void)firstHit(state.toMesh(), rayOrigin[i], rayDir[i]); },
                                       thesisBudget, 20);
    queries["view_pick"] = summary(pickInPlace);
    addComparison(queries["view_pick"], "speedup_vs_mesh_copy", pickInPlace, pickWithCopy, "with_mesh_copy");
    for (const char* k : {"overlap_any", "overlap_faces", "min_distance", "penetration_depth"})
      addComparison(queries[k], "speedup_vs_thesis", k == std::string("overlap_any") ? tOverlapAny
                                                     : k == std::string("overlap_faces") ? tOverlapAll
                                                     : k == std::string("min_distance") ? tDistance : tPenetration,
                    thContact, "thesis");
    addComparison(queries["first_contact"], "speedup_vs_thesis", tContact, thMotion, "thesis");
    addComparison(queries["ray_first_hit"], "speedup_vs_thesis", tRay, thRay, "thesis");
    addComparison(queries["ray_first_hit_culled"], "speedup_vs_thesis", tRayCulled, thRayCulled, "thesis");
    addComparison(queries["ray_all_hits"], "speedup_vs_thesis", tRayAll, thRayAll, "thesis");
    thesisInfo = {{"what", "modules/collision ThesisContact (bounding boxes, then one Moeller-Trumbore ray per "
                           "cutting-face vertex along the feed, brute force over all faces) for the pose queries and "
                           "the motion (feed = step); MeshRayCast brute force for the rays"},
                  {"cutting_face_probes", probesLocal.size()},
                  {"budget_s_per_query_type", thesisBudget}};

    // Cross-check while the brute force is at hand: identical first hits.
    std::size_t agree = 0, checked = std::min<std::size_t>(n, 100);
    for (std::size_t i = 0; i < checked; ++i) {
      const auto b = firstHit(mesh, rayOrigin[i], rayDir[i]);
      const auto v = collider.firstHit(rayOrigin[i], rayDir[i]);
      agree += b.has_value() == v.has_value() && (!b || b->t == v->t);
    }
    checks["ray_first_hit_identical_to_brute_force"] = std::to_string(agree) + "/" + std::to_string(checked);

    // --- CGAL AABB_tree (Epick) for the queries it has ---
    const CgalAabbBaseline cgal(mesh);
    const auto cgRay = timeEach(n, [&](std::size_t i) {
      double t;
      std::size_t tri;
      (void)cgal.firstHit(rayOrigin[i], rayDir[i], t, tri);
    }, cgalBudget, 20);
    const auto cgRayAll = timeEach(n, [&](std::size_t i) { (void)cgal.countHits(rayOrigin[i], rayDir[i]); }, cgalBudget, 20);
    std::vector<std::array<Vec3, 3>> worldTris(rm.solid().triangles.size());
    auto placeReamer = [&](const RigidTransform& T) {
      for (std::size_t k = 0; k < worldTris.size(); ++k) {
        const Triangle& t = rm.solid().triangles[k];
        worldTris[k] = {T.apply(rm.solid().vertices[t[0]]), T.apply(rm.solid().vertices[t[1]]),
                        T.apply(rm.solid().vertices[t[2]])};
      }
    };
    const auto cgAny = timeEach(n, [&](std::size_t i) {
      placeReamer(poses[i]);
      for (const auto& t : worldTris)
        if (cgal.intersects(t[0], t[1], t[2])) break;
    }, cgalBudget, 20);
    const auto cgFaces = timeEach(n, [&](std::size_t i) {
      placeReamer(poses[i]);
      std::vector<std::size_t> hit;
      for (const auto& t : worldTris) cgal.intersectedTriangles(t[0], t[1], t[2], hit);
      std::sort(hit.begin(), hit.end());
      hit.erase(std::unique(hit.begin(), hit.end()), hit.end());
    }, cgalBudget, 20);
    addComparison(queries["ray_first_hit"], "speedup_vs_cgal", tRay, cgRay, "cgal");
    addComparison(queries["ray_all_hits"], "speedup_vs_cgal", tRayAll, cgRayAll, "cgal");
    addComparison(queries["overlap_any"], "speedup_vs_cgal", tOverlapAny, cgAny, "cgal");
    addComparison(queries["overlap_faces"], "speedup_vs_cgal", tOverlapAll, cgFaces, "cgal");
    for (const char* k : {"min_distance", "first_contact", "ray_first_hit_culled", "penetration_depth"})
      queries[k]["cgal"] = nullptr;
    cgalInfo = {{"what", "CGAL 5.5 AABB_tree<AABB_traits<Epick, AABB_triangle_primitive>>: first_intersection(Ray_3), "
                         "number_of_intersected_primitives(Ray_3), do_intersect / all_intersected_primitives with each "
                         "cutting-solid triangle (surface crossings only; no inside faces). No triangle-triangle distance, "
                         "continuous collision, culling or directional depth in AABB_tree: null there"},
                {"build_ms", cgal.buildMilliseconds()},
                {"triangles", cgal.triangleCount()},
                {"budget_s_per_query_type", cgalBudget}};
  }

  // --- local update after cuts ---
  CutSite site;
  const std::string siteArg = a.value("cut-site", boneArg == "default" ? "glenoid" : "random");
  if (siteArg == "glenoid") {
    const DefaultBone d = loadDefaultBone();
    site = {d.glenoid.centre, d.glenoid.outwardAxis, "glenoid of the bundled scapula (resources/bones/scapula_R_glenoid.json)"};
  } else if (siteArg == "random") {
    Vec3 p, nrm;
    std::mt19937_64 siteRng(seed + 7);
    sampler.sample(siteRng, p, nrm);
    site = {p, nrm, "random surface point (seed " + std::to_string(seed) + ")"};
  } else {
    throw UsageError("--cut-site must be glenoid or random, not '" + siteArg + "'");
  }
  // --- a hand-held session at the site, tick by tick (HandHeldPath.h): the warm-cache figures a device sees ---
  HandHeldPathOptions handOptions;
  handOptions.approaches = handApproaches;
  handOptions.seed = seed;
  const std::vector<HandHeldTick> ticks = handHeldPath(collider, rm, site.point, site.outward, handOptions);
  json handHeld = nullptr;
  if (!ticks.empty()) {
    std::vector<double> contactUs, distanceUs, byKind[3], distanceByKind[2];
    std::vector<double> penetrationUs, overlapUs, penetrationByKind[2];
    std::vector<double> oneQueryDistances;
    std::size_t contactPairs = 0, distancePairs = 0, penetrationPairs = 0;
    contactUs.reserve(ticks.size());
    distanceUs.reserve(ticks.size());
    for (const HandHeldTick& tick : ticks) {  // in order, as the device sends them
      auto t0 = Clock::now();
      const FirstContactResult r = collider.firstContact(rm, tick.from, tick.to);
      contactUs.push_back(microsSince(t0));
      byKind[!r.hit ? 0 : (r.t == 0 ? 1 : 2)].push_back(contactUs.back());
      contactPairs += r.trianglePairs;
      t0 = Clock::now();
      const DistanceResult d = collider.faceDistance(rm, tick.to);
      distanceUs.push_back(microsSince(t0));
      distanceByKind[d.distanceMm == 0].push_back(distanceUs.back());
      distancePairs += d.trianglePairs;
      oneQueryDistances.push_back(d.distanceMm);
      t0 = Clock::now();
      const PenetrationResult pr = collider.axialPenetration(rm, tick.to);
      penetrationUs.push_back(microsSince(t0));
      penetrationByKind[pr.penetrating].push_back(penetrationUs.back());
      penetrationPairs += pr.trianglePairs;
      t0 = Clock::now();
      (void)collider.overlap(rm, tick.to, OverlapMode::AnyContact);
      overlapUs.push_back(microsSince(t0));
    }
    // The same ticks again with the distance asked of a FaceDistanceTracker, as a device loop would (the
    // other queries in between as above, so the caches see the same traffic); its answers are checked
    // against the one-pose query's.
    FaceDistanceTracker tracker;
    std::vector<double> trackedUs;
    std::size_t trackedDisagreements = 0;
    for (std::size_t i = 0; i < ticks.size(); ++i) {
      const HandHeldTick& tick = ticks[i];
      (void)collider.firstContact(rm, tick.from, tick.to);
      const auto t0 = Clock::now();
      const DistanceResult d = tracker.query(bvh, rm, tick.to);
      trackedUs.push_back(microsSince(t0));
      const double ref = oneQueryDistances[i];
      trackedDisagreements += !(std::abs(d.distanceMm - ref) <= 1e-9 * (1 + ref));
      (void)collider.axialPenetration(rm, tick.to);
      (void)collider.overlap(rm, tick.to, OverlapMode::AnyContact);
    }
    auto withMax = [](const std::vector<double>& us) {
      json j = summary(us);
      if (!us.empty()) j["max_us"] = *std::max_element(us.begin(), us.end());
      return j;
    };
    handHeld = {{"what", "1 kHz ticks of a hand-held reamer at the cut site: approaches from " +
                             std::to_string(handOptions.approaches) + " directions (tilt <= 15 deg), fed at 20 mm/s "
                             "from 3 mm before the first contact to 0.5 mm beyond it (no cut), held 100 ticks, backed "
                             "off at 40 mm/s; tremor 0.05 mm and 0.1 deg. Queries in the order a device sends them, so "
                             "caches stay warm, unlike the random poses of `queries`"},
                {"ticks", ticks.size()},
                {"first_contact", withMax(contactUs)},
                {"min_distance", withMax(distanceUs)},
                {"min_distance_tracked", withMax(trackedUs)},
                {"penetration_depth", withMax(penetrationUs)},
                {"overlap_any", withMax(overlapUs)}};
    handHeld["penetration_depth"]["mean_triangle_pairs"] = double(penetrationPairs) / double(ticks.size());
    handHeld["penetration_depth"]["by_outcome"] = {{"apart", withMax(penetrationByKind[0])},
                                                   {"penetrating", withMax(penetrationByKind[1])}};
    handHeld["first_contact"]["mean_triangle_pairs"] = double(contactPairs) / double(ticks.size());
    handHeld["min_distance"]["mean_triangle_pairs"] = double(distancePairs) / double(ticks.size());
    handHeld["min_distance_tracked"]["what"] = "min distance from a FaceDistanceTracker over the same ticks (exact: "
                                               "answers from the triangles its last search collected while a motion "
                                               "bound proves none other nearer)";
    handHeld["min_distance_tracked"]["tree_searches"] = tracker.stats().searches;
    handHeld["min_distance_tracked"]["disagreements_with_one_pose_query"] = trackedDisagreements;
    handHeld["min_distance"]["by_outcome"] = {{"apart", withMax(distanceByKind[0])},
                                              {"touching", withMax(distanceByKind[1])}};
    handHeld["first_contact"]["by_outcome"] = {{"no_contact", withMax(byKind[0])},
                                               {"touching_at_start", withMax(byKind[1])},
                                               {"contact_during_motion", withMax(byKind[2])}};
    if (rm.capShadow()) handHeld["penetration_depth"]["against_general_path"] = penetrationAgainstGeneralPath(collider, rm, ticks);
  }

  // A collider built afresh for each sequence of cuts (a copy would lack the spare capacity a built tree
  // keeps for edits): both start from the bone as loaded.
  BoneCollider referenceCollider(state);
  const json update = benchUpdates(mesh, state, referenceCollider, rm, site, cutSteps,
                                   cutMode == "auto" ? (collider.closed() ? "auto" : "dent") : cutMode);
  // The same feed cut by ReamSim's own engine (the cut the application makes: smaller edits, as its band
  // clean-up coarsens the new faces). Only where that engine can cut (it refuses tools reaching defects).
  json updateLocal = nullptr;
  if (collider.closed() && cutMode != "dent") {
    try {
      BoneCollider localCollider(state);
      updateLocal = benchUpdates(mesh, state, localCollider, rm, site, cutSteps, "local");
    } catch (const std::exception& e) {
      std::fprintf(stderr, "note: no update after ReamSim's own cuts (%s)\n", e.what());
    }
  }

  const BvhQuality q = bvh.quality();
  json out = {{"bench", "collision"},
              {"allocator", allocatorName()},
              {"machine", {{"before", machineBefore}, {"after", machineAfter}}},
              {"bone", {{"source", boneArg}, {"label", label}, {"faces", mesh.triangles.size()},
                        {"vertices", mesh.vertices.size()}, {"closed", collider.closed()},
                        {"bounds_diagonal_mm", boneBounds.diagonal()}}},
              {"reamer", {{"name", reamer.name}, {"segments", reamer.segments}, {"rings", reamer.rings},
                          {"faces", rm.solid().triangles.size()},
                          {"cutting_face_triangles", rm.faceTriangles().size()}, {"radius_mm", rm.radius()},
                          {"ideal_solid", rm.idealSolid().valid}}},
              {"faces", mesh.triangles.size()},
              {"poses", n},
              {"seed", seed},
              {"build_ms", collider.buildMilliseconds()},
              {"bvh", {{"nodes", q.nodes}, {"leaves", q.leaves}, {"max_depth", q.maxDepth}, {"sah_cost", q.sahCost},
                       {"huge_page_mb", double(bvh.hugePageBytes()) / (1 << 20)}}},
              {"update_after_cut_ms", update["median_ms"]},
              {"update", update},
              {"update_after_local_cut_ms", updateLocal.is_null() ? json(nullptr) : updateLocal["median_ms"]},
              {"update_local", updateLocal},
              {"queries", queries},
              {"hand_held_path", handHeld},
              {"thesis", thesisInfo},
              {"cgal", cgalInfo},
              {"checks", checks}};
  if (!samplesPath.empty()) out["queries"]["first_contact"]["samples_file"] = samplesPath;
  // The targets (stated for 400k faces; evaluated on whatever bone was given).
  bool all100 = !a.has("no-baselines"), fasterThanCgal = !a.has("no-baselines");
  for (auto& [name, qv] : out["queries"].items()) {
    if (qv.contains("speedup_vs_thesis")) all100 = all100 && qv["speedup_vs_thesis"].get<double>() >= 100;
    if (qv.contains("speedup_vs_cgal")) fasterThanCgal = fasterThanCgal && qv["speedup_vs_cgal"].get<double>() > 1;
  }
  const std::size_t reamerFaces = rm.solid().triangles.size();
  auto handHeldWithin20us = [&](const char* query) {
    return handHeld.is_object() ? json(handHeld[query]["median_us"].get<double>() <= 20) : json(nullptr);
  };
  out["targets"] = {{"reamer_has_2k_to_5k_faces", reamerFaces >= 2000 && reamerFaces <= 5000},
                    {"min_distance_median_le_20us", percentile(tDistance, 0.5) <= 20},
                    {"first_contact_median_le_20us", percentile(tContact, 0.5) <= 20},
                    {"hand_held_min_distance_median_le_20us", handHeldWithin20us("min_distance")},
                    {"hand_held_min_distance_tracked_median_le_20us", handHeldWithin20us("min_distance_tracked")},
                    {"hand_held_first_contact_median_le_20us", handHeldWithin20us("first_contact")},
                    {"update_after_cut_le_1ms", update["median_ms"].get<double>() <= 1.0},
                    {"update_after_local_cut_le_1ms",
                     updateLocal.is_null() ? json(nullptr) : json(updateLocal["median_ms"].get<double>() <= 1.0)},
                    {"all_queries_ge_100x_thesis", all100},
                    {"faster_than_cgal_where_comparable", fasterThanCgal}};

  if (a.has("json")) {
    std::cout << out.dump() << "\n";
    return kOk;
  }
  std::printf("bone %s: %zu faces; reamer %s (%zu faces); build %.1f ms; update after cut %.3f ms (%s)\n",
              label.c_str(), mesh.triangles.size(), reamer.name.c_str(), rm.solid().triangles.size(),
              collider.buildMilliseconds(), update["median_ms"].get<double>(), update["kind"].get<std::string>().c_str());
  std::printf("%-22s %10s %10s %14s %12s\n", "query", "median_us", "p99_us", "x_thesis", "x_cgal");
  for (auto& [name, qv] : out["queries"].items()) {
    auto ratio = [&](const char* k) { return qv.contains(k) ? std::to_string(qv[k].get<double>()) : std::string("-"); };
    std::printf("%-22s %10.2f %10.2f %14s %12s\n", name.c_str(), qv["median_us"].get<double>(),
                qv["p99_us"].get<double>(), ratio("speedup_vs_thesis").c_str(), ratio("speedup_vs_cgal").c_str());
  }
  if (handHeld.is_object())
    std::printf("hand-held path at the %s, %zu ticks: first contact %.2f / %.2f us, min distance %.2f / %.2f us, "
                "tracked %.2f / %.2f us (median / p99)\n", site.name.c_str(), ticks.size(),
                handHeld["first_contact"]["median_us"].get<double>(), handHeld["first_contact"]["p99_us"].get<double>(),
                handHeld["min_distance"]["median_us"].get<double>(), handHeld["min_distance"]["p99_us"].get<double>(),
                handHeld["min_distance_tracked"]["median_us"].get<double>(),
                handHeld["min_distance_tracked"]["p99_us"].get<double>());
  return kOk;
}

}  // namespace reamsim::cli
