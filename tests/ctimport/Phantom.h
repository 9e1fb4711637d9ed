#pragma once
// Synthetic CT phantoms of known geometry, and writers that put them into every supported file format
// (by hand from the format specifications for NRRD, MetaImage and NIfTI; through vtk-dicom for DICOM),
// so that the readers are tested against files they did not write themselves.
#include <array>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "reamsim/mesh/Vec3.h"

namespace phantom {

using reamsim::Vec3;

// A regular grid placed in LPS patient space: world = origin + D · (i·s0, j·s1, k·s2).
struct Grid {
  std::array<int, 3> dims{0, 0, 0};
  std::array<double, 3> spacing{1, 1, 1};
  Vec3 origin;
  std::array<double, 9> direction{1, 0, 0, 0, 1, 0, 0, 0, 1};  // row-major, columns = axis directions
  Vec3 axis(int a) const { return {direction[a], direction[3 + a], direction[6 + a]}; }
  Vec3 world(double i, double j, double k) const;
  std::size_t voxels() const { return std::size_t(dims[0]) * dims[1] * dims[2]; }
};

// Inside test of a solid, in world (LPS) coordinates.
using Solid = std::function<bool(const Vec3&)>;

// Sphere of radius R around `center` pierced by a cylinder (radius r < R, length L) along `axis` through
// the centre; optionally a separate small sphere (a loose fragment).
struct SphereAndCylinder {
  Vec3 center{10, -20, 35};
  Vec3 axis{0, 0, 1};
  double sphereRadius = 12, cylinderRadius = 5, cylinderLength = 44;
  bool fragment = false;
  Vec3 fragmentCenter{10 + 19, -20, 35};
  double fragmentRadius = 3.5;

  bool inside(const Vec3& p) const;
  bool insideMain(const Vec3& p) const;
  // π r² L + (4π/3)(R² − r²)^{3/2}: cylinder plus the sphere outside it ("napkin ring").
  double mainVolume() const;
  double fragmentVolume() const;
};

// A rotation (unit quaternion from axis and angle), as a row-major direction matrix.
std::array<double, 9> rotation(const Vec3& axis, double degrees);

// A grid of `spacing` around `center` with orientation `direction`, big enough for a ball of `radius`.
Grid gridAround(const Vec3& center, double radius, const std::array<double, 3>& spacing,
                const std::array<double, 9>& direction);

// CT values: `bone` HU inside, `tissue` outside, partial volume at the boundary from n³ sub-samples.
std::vector<float> sample(const Grid& grid, const Solid& solid, float tissue = 40, float bone = 1200, int n = 4);

// --- writers: every one throws std::runtime_error if it cannot write ---------------------------------------
void writeNrrd(const std::string& path, const Grid& g, const std::vector<float>& hu);  // attached, int16 LE, LPS
// Detached header + gzip float32 big-endian data, header in RAS space (the reader must convert).
void writeNrrdDetachedGzipRas(const std::string& nhdr, const Grid& g, const std::vector<float>& hu);
// Detached header + one raw int16 file per slice ("slice%03d.raw 0 N-1 1").
void writeNrrdSlices(const std::string& nhdr, const Grid& g, const std::vector<float>& hu);
void writeMha(const std::string& path, const Grid& g, const std::vector<float>& hu, bool compressed);
void writeMhdRaw(const std::string& mhd, const Grid& g, const std::vector<float>& hu);  // data in .raw beside it
// NIfTI-1 single file, uint16 with scl_inter -1024, sform in RAS; gzip-compressed if the name ends in .gz.
void writeNifti(const std::string& path, const Grid& g, const std::vector<float>& hu);
// DICOM CT series (one file per slice) through vtk-dicom's writer and CT generator; `transferSyntax`
// empty = explicit VR little endian (uncompressed), e.g. "1.2.840.10008.1.2.5" for RLE lossless.
// `filePattern` (printf, with the directory and the slice number) names the files.
void writeDicomSeries(const std::string& directory, const Grid& g, const std::vector<float>& hu,
                      const std::string& transferSyntax = "", const std::string& filePattern = "%s/IM-%04d.dcm");

// A DICOMDIR (the index of a DICOM CD, PS3.10 / PS3.3 F) in `root` for `files` (paths relative to `root`,
// components of up to 8 characters A-Z 0-9 _), by hand in explicit VR little endian: one PATIENT, STUDY and
// SERIES record per series found in the files (their UIDs read back from them) and one IMAGE record per file.
void writeDicomDir(const std::string& root, const std::vector<std::string>& files);

// One multi-frame DICOM file (vtk-dicom's secondary capture: it has no enhanced CT writer), uint16 = HU + 1024.
void writeDicomMultiFrame(const std::string& path, const Grid& g, const std::vector<float>& hu);

void writeBytes(const std::string& path, const std::string& bytes);
std::string readBytes(const std::string& path);

}  // namespace phantom
