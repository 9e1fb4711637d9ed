#include "BenchPlanning.h"

#include <chrono>
#include <vector>

#include "BenchStats.h"
#include "reamsim/collision/MeshRayCast.h"
#include "reamsim/core/BoneState.h"
#include "reamsim/ream/GlenoidFace.h"
#include "reamsim/tools/ReamedSurface.h"

namespace reamsim::cli {

nlohmann::json glenoidFaceCost(const TriangleMesh& bone, const Pose& first) {
  const BoneState state = BoneState::fromMesh(bone);
  const std::optional<MeshHit> hit = firstHit(state, first.tip, first.axis);
  if (!hit) return {{"error", "the path's first pose's axis meets no bone"}};
  constexpr int kRuns = 21;
  std::vector<double> ms;
  GlenoidFace face;
  for (int i = 0; i < kRuns; ++i) {
    const auto t0 = std::chrono::steady_clock::now();
    face = measureGlenoidFace(state, hit->point);
    ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
  }
  return {{"what", "the planning dock's measure of the glenoid face (measureGlenoidFace, default radius) about "
                   "where the path's first axis meets the bone, on the bone as opened"},
          {"runs", kRuns},
          {"faces", state.liveTriangleCount()},
          {"median_ms", percentile(ms, 0.5)},
          {"max_ms", percentile(ms, 1.0)},
          {"face_triangles", face.triangles},
          {"face_area_mm2", face.areaMm2},
          {"outward", {face.outward.x, face.outward.y, face.outward.z}}};
}

nlohmann::json previewSeatCost(const TriangleMesh& reamed, const ReamerSpec& spec, const Pose& last) {
  const BoneState state = BoneState::fromMesh(reamed);
  constexpr int kRuns = 11;
  std::vector<double> ms;
  ReamedSurfaceReport seat;
  for (int i = 0; i < kRuns; ++i) {
    const auto t0 = std::chrono::steady_clock::now();
    seat = measureReamedSurface(state.toMesh(), spec, last);
    ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
  }
  return {{"what", "what a removal preview adds for its seat (previewSeat: the bone state as a mesh, then "
                   "measureReamedSurface) of the bone the path reamed, at its last pose (seated_fraction: reamed_surface's)"},
          {"runs", kRuns},
          {"faces", state.liveTriangleCount()},
          {"median_ms", percentile(ms, 0.5)},
          {"max_ms", percentile(ms, 1.0)},
          {"seated_fraction", seat.seatedFraction}};
}

}  // namespace reamsim::cli
