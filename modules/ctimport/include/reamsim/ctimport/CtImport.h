#pragma once
// From a CT volume to a clean, closed bone mesh (docs/CT_IMPORT.md):
//   threshold (HU, optional upper bound) → optional volume smoothing → keep the largest (or the picked)
//   connected bone region, fill internal cavities → pad with background so the surface closes where the bone
//   leaves the field of view → flying-edges isosurface → windowed-sinc smoothing with volume correction →
//   quadric decimation to a target face count → validation (the Foundation's ValidationReport).
// The isosurface of a piecewise-linear field is free of self-intersections; smoothing and decimation can
// create some in thin bone. They are searched for exactly and undone locally (smoothing: affected vertices
// return to the isosurface; decimation: re-run with the region locked); what was done is in the report.
#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "reamsim/ctimport/CtVolume.h"
#include "reamsim/ctimport/Progress.h"
#include "reamsim/mesh/TriangleMesh.h"
#include "reamsim/mesh/Validation.h"

namespace reamsim::ct {

enum class ComponentMode {
  Largest,  // the largest 6-connected region above the threshold
  Seed,     // the region containing (or nearest to, within 3 voxels) `seedWorld`
  All,      // every region (several shells)
};

struct ImportOptions {
  double lowerThreshold = 250;                 // bone: value ≥ lower (HU for CT)
  std::optional<double> upperThreshold;        // and value ≤ upper (e.g. 3000 to leave out metal)
  double volumeSmoothingSigmaMm = 0;           // Gaussian on the volume before thresholding; 0 = off
  ComponentMode component = ComponentMode::Largest;
  std::optional<Vec3> seedWorld;               // for ComponentMode::Seed, in the volume's patient space
  bool fillCavities = true;                    // closed pockets below threshold inside the bone become bone
  int smoothingIterations = 15;                // windowed sinc; 0 = off
  double smoothingPassBand = 0.1;              // lower = smoother (VTK's recommendation 0.01-0.1)
  std::size_t targetFaces = 150000;            // 0 = no decimation
  std::optional<PatientSpace> outputSpace = PatientSpace::LPS;  // nullopt: the volume's own space
  bool cgalSelfIntersectionCheck = false;      // also count with the Foundation's CGAL check (slow on big meshes)
};

struct StageTime {
  std::string stage;
  double ms = 0;
};

struct ImportReport {
  std::string source, format, valueUnit;
  PatientSpace volumeSpace = PatientSpace::Unspecified, outputSpace = PatientSpace::Unspecified;
  std::array<int, 3> dims{0, 0, 0};
  std::array<double, 3> spacing{0, 0, 0};
  float minValue = 0, maxValue = 0;
  double lowerThreshold = 0;
  std::optional<double> upperThreshold;
  double volumeSmoothingSigmaMm = 0;

  std::size_t voxelsInRange = 0;        // voxels within the threshold range
  std::size_t regions = 0;              // 6-connected regions among them
  std::size_t keptVoxels = 0;           // in the kept region(s)
  std::size_t cavityVoxelsFilled = 0;
  std::vector<std::string> fieldOfViewCuts;  // volume faces the bone touches ("-x" ... "+z"), closed by caps

  std::size_t isosurfaceFaces = 0;
  double isosurfaceVolumeMm3 = 0;
  std::size_t smoothingRestoredVertices = 0;  // returned to the isosurface to remove self-intersections
  double smoothingVolumeCorrectionMm = 0;     // normal offset that restored the isosurface volume
  bool decimated = false;
  std::size_t decimationAttempts = 0;
  std::size_t decimationGuardedVertices = 0;   // where the exact self-intersection guard had to run
  bool repaired = false;                      // repairMesh had to run (see notes)

  ValidationReport validation;                // of the final mesh
  std::string selfIntersectionCheck;          // which search produced validation.selfIntersectingPairs
  std::vector<StageTime> stages;
  double totalMs = 0;
  std::vector<std::string> notes;             // readers' notes, fallbacks, warnings — in words
};

struct ImportResult {
  TriangleMesh mesh;                          // mm, in `space`
  PatientSpace space = PatientSpace::Unspecified;
  ImportReport report;
};

// Throws std::invalid_argument for inconsistent options (upper < lower, seed outside the volume ...),
// std::runtime_error if nothing lies in the threshold range, ImportCancelled if `progress` returns false.
ImportResult importBone(const CtVolume& volume, const ImportOptions& options = {},
                        const ProgressCallback& progress = {});

std::string toText(const ImportReport& report);
std::string toJson(const ImportReport& report, int indent = 2);

}  // namespace reamsim::ct
