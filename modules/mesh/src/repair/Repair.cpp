#include "reamsim/mesh/Repair.h"

#include <cstdio>
#include <exception>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>

#include "ReportJson.h"
#include "SoupRepair.h"

namespace reamsim {
namespace {
std::string format(const char* fmt, double a, double b = 0, double c = 0, double d = 0) {
  char buf[512];
  std::snprintf(buf, sizeof buf, fmt, a, b, c, d);
  return buf;
}
}  // namespace

RepairResult repairMesh(const TriangleMesh& input, const RepairOptions& options) {
  RepairResult result;
  RepairReport& rep = result.report;
  const RepairProgress& progress = options.progress;
  // "done" on every return, so that a caller's progress display can close (not while an exception
  // unwinds: the callback may throw to cancel).
  struct Done {
    const RepairProgress& progress;
    int exceptions = std::uncaught_exceptions();
    ~Done() {
      if (!progress || std::uncaught_exceptions() != exceptions) return;
      try {
        progress(1.0, "done");
      } catch (...) {  // a cancel asked for now comes too late to matter: the work is done
      }
    }
  } done{progress};
  // Validation at the given share of the whole: counting self-intersections takes seconds at millions of
  // triangles, and checks for a cancel as it goes.
  const auto validate = [&progress](const TriangleMesh& mesh, double begin, double end, const char* stage) {
    ValidationOptions options;
    options.progress = StageProgress{&progress, begin, end, stage};
    return validateMesh(mesh, options);
  };
  rep.before = validate(input, 0.0, 0.05, "validation");
  if (rep.before.isCleanSolid()) {
    result.mesh = input;
    rep.after = rep.before;
    rep.actions.push_back("none needed: the mesh is a closed, outward-oriented solid without self-intersections");
    return result;
  }

  reportRepairProgress(progress, 0.05, "topological repair");
  SoupRepairResult soup = repairSoupTopology(input, options.maxHoleBoundaryEdges);
  rep.mergedVertices = soup.verticesRemoved;
  rep.removedFaces = soup.facesRemoved;
  rep.orientableWithoutSplitting = soup.orientableWithoutSplitting;
  rep.holesClosed = soup.holesClosed;
  rep.holesLeftOpen = soup.holesLeftOpen;
  rep.flippedToOutward = soup.flippedToOutward;
  if (soup.verticesRemoved)
    rep.actions.push_back(std::to_string(soup.verticesRemoved) + " duplicate or unused vertices merged/removed");
  if (soup.facesRemoved)
    rep.actions.push_back(std::to_string(soup.facesRemoved) + " degenerate or duplicate faces removed");
  rep.actions.push_back(soup.orientableWithoutSplitting
                            ? "faces oriented consistently"
                            : "faces oriented as far as possible; the surface is not consistently orientable "
                              "(non-manifold or Möbius-like parts): vertices were split");
  if (soup.holesClosed)
    rep.actions.push_back(std::to_string(soup.holesClosed) + " holes with at most " +
                          std::to_string(options.maxHoleBoundaryEdges) + " boundary edges triangulated");
  if (soup.holesLeftOpen) rep.actions.push_back(std::to_string(soup.holesLeftOpen) + " larger holes left open");
  if (soup.flippedToOutward) rep.actions.push_back("all faces flipped so that normals point outward");

  result.mesh = std::move(soup.mesh);
  rep.after = validate(result.mesh, 0.1, 0.15, "validation");
  if (rep.after.isCleanSolid() || !options.allowRemesh) {
    if (!rep.after.isCleanSolid())
      rep.actions.push_back("still not a clean solid, and volumetric remeshing was not allowed");
    return result;
  }

  std::string why;
  if (!rep.after.closed) why += " open or non-manifold;";
  if (!rep.after.consistentlyOriented) why += " not consistently oriented;";
  if (rep.after.selfIntersectingPairs.value_or(0) > 0)
    why += " " + std::to_string(*rep.after.selfIntersectingPairs) + " self-intersecting face pairs;";
  RemeshResult remesh;
  try {
    RemeshOptions remeshOptions = options.remesh;
    if (progress)  // the remesh's fractions mapped onto [0.15, 0.9] of the repair
      remeshOptions.progress = [&progress](double f, const std::string& stage) { return progress(0.15 + 0.75 * f, stage); };
    remesh = volumetricRemesh(soup.orientedSoup, remeshOptions);
  } catch (const std::invalid_argument& e) {
    // Refused before the work (a grid or band beyond its limit: wrong units, a stray vertex far away): the
    // report says why, and the caller keeps the mesh as the topological repair left it (not a clean solid).
    rep.actions.push_back("after topological repair the surface was still" + why.substr(0, why.size() - 1) +
                          "; volumetric remesh refused: " + e.what());
    return result;
  }
  rep.remeshed = true;
  rep.remesh = remesh.stats;
  const RemeshStats& s = remesh.stats;
  rep.actions.push_back("after topological repair the surface was still" + why.substr(0, why.size() - 1) +
                        format(": rebuilt by volumetric remesh (winding-number sign, %.3g mm grid, marching "
                               "tetrahedra)", s.voxelMm));
  if (s.voxelMm != s.requestedVoxelMm)
    rep.actions.push_back(format("remesh grid coarsened from %.3g to %.3g mm: at %.3g mm its band near the surface "
                                 "would have held %.3g million points, and the surface out roughly twice as many triangles; "
                                 "`reamsim-cli repair --voxel MM` repairs at any grid",
                                 s.requestedVoxelMm, s.voxelMm, s.requestedVoxelMm, double(s.requestedBandPoints) / 1e6));
  if (s.trianglesAfter != s.trianglesBeforeDecimation)
    rep.actions.push_back("remeshed surface decimated from " + std::to_string(s.trianglesBeforeDecimation) + " to " +
                          std::to_string(s.trianglesAfter) + " triangles (checked free of self-intersections)");
  rep.actions.push_back(format("distance from the result to the input: max %.3f mm, mean %.3f mm; from the input "
                               "to the result: max %.3f mm, mean %.3f mm",
                               s.maxOutputToInputMm, s.meanOutputToInputMm, s.maxInputToOutputMm, s.meanInputToOutputMm));
  result.mesh = std::move(remesh.mesh);
  rep.after = validate(result.mesh, 0.9, 1.0, "validation of the result");
  return result;
}

RepairOptions importRepairOptions() {
  RepairOptions options;
  options.remesh.coarsenAboveBandPoints = 2'500'000;
  return options;
}

std::string toText(const RepairReport& r) {
  std::ostringstream out;
  out << "== before repair ==\n" << toText(r.before) << "== repair ==\n";
  for (const std::string& a : r.actions) out << "- " << a << "\n";
  out << "== after repair ==\n" << toText(r.after);
  out << "result: " << (r.success() ? "closed, outward-oriented solid without self-intersections"
                                    : "NOT a clean solid (see above)")
      << "\n";
  return out.str();
}

std::string toJson(const RepairReport& r, int indent) {
  nlohmann::json j;
  j["before"] = toJsonValue(r.before);
  j["after"] = toJsonValue(r.after);
  j["actions"] = r.actions;
  j["merged_vertices"] = r.mergedVertices;
  j["removed_faces"] = r.removedFaces;
  j["orientable_without_splitting"] = r.orientableWithoutSplitting;
  j["holes_closed"] = r.holesClosed;
  j["holes_left_open"] = r.holesLeftOpen;
  j["flipped_to_outward"] = r.flippedToOutward;
  j["remeshed"] = r.remeshed;
  if (r.remesh) {
    const RemeshStats& s = *r.remesh;
    j["remesh"] = {{"voxel_mm", s.voxelMm},
                   {"grid", {s.grid[0], s.grid[1], s.grid[2]}},
                   {"requested_voxel_mm", s.requestedVoxelMm},
                   {"band_points", s.bandPoints},
                   {"winding_terms_per_point", s.windingTermsPerPoint},
                   {"band_ms", s.windingMilliseconds},
                   {"triangles_before_decimation", s.trianglesBeforeDecimation},
                   {"triangles_after", s.trianglesAfter},
                   {"max_result_to_input_mm", s.maxOutputToInputMm},
                   {"mean_result_to_input_mm", s.meanOutputToInputMm},
                   {"max_input_to_result_mm", s.maxInputToOutputMm},
                   {"mean_input_to_result_mm", s.meanInputToOutputMm},
                   {"ms", s.milliseconds}};
  }
  j["success"] = r.success();
  return j.dump(indent);
}

}  // namespace reamsim
