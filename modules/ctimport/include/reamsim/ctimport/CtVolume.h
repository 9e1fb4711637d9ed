#pragma once
// A CT volume as every reader returns it: scalar values on a regular grid, placed in patient space.
//   world = origin + direction · (i·spacing[0], j·spacing[1], k·spacing[2])
// `direction` has orthonormal columns: the world directions of the i, j and k axes. World coordinates are in
// millimetres in the patient coordinate system named by `space` (see docs/CT_IMPORT.md).
#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include "reamsim/mesh/Vec3.h"

namespace reamsim::ct {

// LPS: +x toward the patient's left, +y posterior, +z superior (DICOM, ITK/MetaImage, NRRD "LPS").
// RAS: +x right, +y anterior, +z superior (NIfTI). The two differ by a 180° turn about z (x and y negated),
// which keeps handedness. Unspecified: the file names no anatomical frame (e.g. NRRD "3D-left-handed").
enum class PatientSpace { LPS, RAS, Unspecified };

const char* toString(PatientSpace space);  // "LPS", "RAS", "unspecified"

struct CtVolume {
  std::array<int, 3> dims{0, 0, 0};
  std::array<double, 3> spacing{1, 1, 1};  // mm, > 0
  Vec3 origin;                             // world position of voxel (0,0,0)'s centre
  std::array<double, 9> direction{1, 0, 0, 0, 1, 0, 0, 0, 1};  // row-major 3×3, orthonormal columns
  PatientSpace space = PatientSpace::Unspecified;
  std::vector<float> values;  // i fastest, then j, then k; rescale slope/intercept already applied
  bool integerValued = true;  // every value is an integer (stored integer type with integral rescale)
  std::string valueUnit;      // "HU" when the file says or implies Hounsfield units, else ""
  std::string sourcePath;
  std::string format;              // "nrrd", "metaimage", "nifti", "dicom"
  std::vector<std::string> notes;  // what the reader did that the user should know

  std::size_t voxelCount() const { return std::size_t(dims[0]) * dims[1] * dims[2]; }
  std::size_t index(int i, int j, int k) const { return (std::size_t(k) * dims[1] + j) * dims[0] + i; }
  float at(int i, int j, int k) const { return values[index(i, j, k)]; }
  Vec3 axis(int a) const { return {direction[a], direction[3 + a], direction[6 + a]}; }
  Vec3 indexToWorld(double i, double j, double k) const;
  Vec3 worldToIndex(const Vec3& world) const;  // continuous index (inverse of indexToWorld)
};

// Checks the invariants above (dims ≥ 2, spacing within 1e-6 .. 1e6 mm, every voxel within ±1e7 mm of the
// origin of patient space, orthonormal direction, value count, finite values); throws InputError naming
// `volume.sourcePath` otherwise. Readers call it before returning.
void checkVolume(const CtVolume& volume);

// Maps a point or a whole mesh between LPS and RAS (x and y negated). Identity when either is Unspecified.
Vec3 convertPoint(const Vec3& p, PatientSpace from, PatientSpace to);

}  // namespace reamsim::ct
