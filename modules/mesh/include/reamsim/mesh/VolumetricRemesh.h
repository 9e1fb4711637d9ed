#pragma once
// Volumetric remesh of an arbitrary triangle soup into a closed, consistently outward-oriented,
// self-intersection-free surface.
//  - inside/outside from the generalized winding number (robust to holes, flipped and overlapping
//    faces; summed over a tree of clusters, reamsim/mesh/WindingNumber.h), distance from an AABB tree;
//    both sampled on a regular grid of `voxelMm`, only in a narrow band around the input (the rest is
//    labelled by connected components);
//  - marching tetrahedra on the Kuhn (6-tetrahedra) subdivision of the grid: the zero set of a
//    piecewise-linear field with no zero at the grid points is a closed 2-manifold whose triangles lie
//    in disjoint tetrahedra, so it cannot self-intersect; crossing points are kept at least 0.1 % of an
//    edge away from grid points so that rounding cannot fold them;
//  - optional decimation to a target face count (Garland–Heckbert), accepted only if the result
//    still has no self-intersection (otherwise a milder target is tried).
#include <cstddef>

#include "reamsim/mesh/RepairProgress.h"
#include "reamsim/mesh/TriangleMesh.h"

namespace reamsim {

struct RemeshOptions {
  double voxelMm = 0.5;             // grid spacing: the resolution of the rebuilt surface
  std::size_t targetTriangles = 0;  // 0 = keep the marching-tetrahedra output
  std::size_t maxGridPoints = 200'000'000;  // refuse larger grids with a clear message
  // Refuse a band (the grid points near the surface, each given a distance and a winding number) larger
  // than this: what follows (the marching tetrahedra, the distances both ways, the validation) grows with
  // it. Measured: the 400k CT skull holds 9.3 million at 0.5 mm, the bundled scapula's original 2.0 million
  // at 0.5 mm and 13.2 million at 0.25; fuzzed files with one vertex of a box moved 65 m away 16.4 and 82
  // million, which ran for more than two minutes and for hours.
  std::size_t maxBandPoints = 15'000'000;
  // Refuse more than about this many winding-number terms (exact solid angles and far clusters'
  // expansions, FastWindingNumber), estimated from a sample of the band before the band is evaluated.
  // Until session 47 the winding number was summed over every triangle at every band point: the 400k CT
  // skull at 0.5 mm would have taken 3.7e12 solid angles, hours on two cores.
  double maxWindingTerms = 2e10;
  // 0: the grid is `voxelMm` (or refused by the limits above). Otherwise a grid whose band near the surface
  // would hold more points than this is coarsened until it does not, and the stats say so: what an import
  // uses (importRepairOptions(), Repair.h), where a 400k CT mesh at 0.5 mm would come out at 17 million
  // triangles after minutes of work.
  std::size_t coarsenAboveBandPoints = 0;
  // Called between slices of the band and between stages; returning false throws RepairCancelled.
  RepairProgress progress;
};

struct RemeshStats {
  double voxelMm = 0;           // the grid used
  double requestedVoxelMm = 0;  // the grid asked for (larger when coarsened, see coarsenAboveBandPoints)
  std::size_t requestedBandPoints = 0;  // candidate band points at the requested grid
  int grid[3] = {0, 0, 0};
  std::size_t bandPoints = 0;
  double windingTermsPerPoint = 0;  // estimated from the sample the limit is checked on
  double windingMilliseconds = 0;   // the band's distances and winding numbers
  std::size_t trianglesBeforeDecimation = 0;
  std::size_t trianglesAfter = 0;
  // Fidelity, measured both ways (vertices of one surface against the other surface):
  double maxOutputToInputMm = 0, meanOutputToInputMm = 0;
  double maxInputToOutputMm = 0, meanInputToOutputMm = 0;
  double milliseconds = 0;
};

struct RemeshResult {
  TriangleMesh mesh;
  RemeshStats stats;
};

// Throws std::invalid_argument for empty input, non-finite coordinates or a grid over the limit, and
// RepairCancelled when `options.progress` asks it to stop.
RemeshResult volumetricRemesh(const TriangleMesh& soup, const RemeshOptions& options = {});

// Decimation that keeps the surface closed and free of self-intersections; returns false (and leaves
// `mesh` unchanged) if no acceptable decimation was found. Used by volumetricRemesh. Checks `progress`
// between attempts and every few thousand collapses (RepairCancelled, `mesh` unchanged).
bool decimateWithoutSelfIntersections(TriangleMesh& mesh, std::size_t targetTriangles,
                                      const StageProgress& progress = {});

// Distance from each vertex of `from` to the surface `to` (CGAL AABB tree): max and mean. Checks
// `progress` between slices of vertices.
void surfaceDistance(const TriangleMesh& from, const TriangleMesh& to, double& maxMm, double& meanMm,
                     const StageProgress& progress = {});

}  // namespace reamsim
