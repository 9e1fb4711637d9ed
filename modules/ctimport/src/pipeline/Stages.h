#pragma once
// The import pipeline's stages, each in its own file; ImportPipeline.cpp runs them in order.
#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "reamsim/ctimport/CtImport.h"
#include "reamsim/ctimport/CtVolume.h"
#include "reamsim/ctimport/SelfIntersections.h"
#include "reamsim/mesh/TriangleMesh.h"

namespace reamsim::ct::detail {

// Called with a stage-local fraction in [0,1]; throws ImportCancelled when the user cancels.
using Tick = std::function<void(double)>;

// The signed field whose zero set is the bone surface: > 0 inside the threshold range, < 0 outside, never 0.
// It has one voxel of background on every side (so the surface closes at the field of view) and is
// indexed like the volume shifted by one: padded (i+1, j+1, k+1) is volume voxel (i, j, k).
struct PaddedField {
  std::array<int, 3> dims{0, 0, 0};
  std::vector<float> values;
  std::size_t index(int i, int j, int k) const { return (std::size_t(k) * dims[1] + j) * dims[0] + i; }
};

// Separable Gaussian (σ per axis in voxels, kernel ±3σ, edges replicated), in place.
void gaussianSmooth(std::vector<float>& values, const std::array<int, 3>& dims, const std::array<double, 3>& sigma,
                    const Tick& tick);

PaddedField buildField(const CtVolume& volume, const ImportOptions& options, const Tick& tick);

struct RegionStats {
  std::size_t inRange = 0, regions = 0, kept = 0, cavities = 0;
  std::array<bool, 6> touches{};  // bone on the volume's -x,+x,-y,+y,-z,+z faces
};
// Keeps the chosen region(s) of the positive set and fills enclosed cavities, by editing field values.
// `seed` is a padded index (ComponentMode::Seed). Throws std::runtime_error if nothing is in range.
RegionStats keepRegions(PaddedField& field, ComponentMode mode, const std::optional<std::array<int, 3>>& seed,
                        bool fillCavities, const Tick& tick);

// Flying edges on the field, mapped to world coordinates of `volume`, outward oriented.
TriangleMesh extractIsosurface(const PaddedField& field, const CtVolume& volume, const Tick& tick);

// Windowed-sinc smoothing (VTK); same topology, new vertex positions.
TriangleMesh windowedSincSmooth(const TriangleMesh& mesh, int iterations, double passBand, const Tick& tick);

// Offsets every vertex along its normal by one common distance so that the enclosed volume becomes
// `targetVolume` (first order, refined twice); returns the distance (mm).
double restoreVolume(TriangleMesh& mesh, double targetVolume);

// Returns vertices of faces involved in self-intersections (and their neighbours) to their positions in
// `reference` (same topology, free of self-intersections) until none is left. Returns the number of
// vertices restored; `everything` is set if it had to give up and restore all.
// `finalCheck` receives a full search of the resulting mesh.
std::size_t restoreWhereSelfIntersecting(TriangleMesh& mesh, const TriangleMesh& reference, bool& everything,
                                         SelfIntersectionResult& finalCheck, const Tick& tick);

struct DecimationOutcome {
  TriangleMesh mesh;
  SelfIntersectionResult check;  // the exact search on `mesh` (when decimated)
  bool decimated = false;
  std::size_t attempts = 0, guardedVertices = 0, selfIntersectingPairs = 0;
};
// Decimates to `target` and keeps the volume; while the result self-intersects, re-runs with the exact
// guard around the offending places (the last attempt guards everything and cannot fail).
DecimationOutcome decimateWithoutIntersections(const TriangleMesh& mesh, std::size_t target, double targetVolume,
                                               const Tick& tick);

}  // namespace reamsim::ct::detail
