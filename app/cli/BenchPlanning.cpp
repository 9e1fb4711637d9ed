#include "BenchPlanning.h"

#include <chrono>
#include <vector>

#include "BenchStats.h"
#include "reamsim/collision/MeshRayCast.h"
#include "reamsim/core/BoneState.h"
#include "reamsim/ream/GlenoidFace.h"
#include "reamsim/tools/ReamedSurface.h"

namespace reamsim::cli {
namespace {

// `runs` calls of `measure`, timed: "runs", "median_ms" and "max_ms".
template <class Measure>
nlohmann::json timed(int runs, Measure measure) {
  std::vector<double> ms;
  for (int i = 0; i < runs; ++i) {
    const auto t0 = std::chrono::steady_clock::now();
    measure();
    ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
  }
  return {{"runs", runs}, {"median_ms", percentile(ms, 0.5)}, {"max_ms", percentile(ms, 1.0)}};
}

}  // namespace

nlohmann::json glenoidFaceCost(const TriangleMesh& bone, const Pose& first) {
  const BoneState state = BoneState::fromMesh(bone);
  const std::optional<MeshHit> hit = firstHit(state, first.tip, first.axis);
  if (!hit) return {{"error", "the path's first pose's axis meets no bone"}};
  GlenoidFace face;
  nlohmann::json out = timed(21, [&] { face = measureGlenoidFace(state, hit->point); });
  out["what"] = "the planning dock's measure of the glenoid face (measureGlenoidFace, default radius) about where the "
                "path's first axis meets the bone, on the bone as opened";
  out["faces"] = state.liveTriangleCount();
  out["face_triangles"] = face.triangles;
  out["face_area_mm2"] = face.areaMm2;
  out["outward"] = {face.outward.x, face.outward.y, face.outward.z};
  return out;
}

nlohmann::json previewSeatCost(const TriangleMesh& reamed, const ReamerSpec& spec, const Pose& last) {
  const BoneState state = BoneState::fromMesh(reamed);
  ReamedSurfaceReport seat;
  nlohmann::json out = timed(11, [&] { seat = measureReamedSurface(state.toMesh(), spec, last); });
  out["what"] = "what a removal preview adds for its seat (previewSeat: the bone state as a mesh, then "
                "measureReamedSurface) of the bone the path reamed, at its last pose (seated_fraction: reamed_surface's)";
  out["faces"] = state.liveTriangleCount();
  out["seated_fraction"] = seat.seatedFraction;
  return out;
}

}  // namespace reamsim::cli
