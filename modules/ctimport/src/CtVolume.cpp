#include "reamsim/ctimport/CtVolume.h"

#include <cmath>
#include <cstdio>
#include <string>

#include "reamsim/mesh/MeshError.h"

namespace reamsim::ct {
namespace {

constexpr double kMinSpacingMm = 1e-6, kMaxSpacingMm = 1e6, kMaxWorldMm = 1e7;

std::string num(double x) {
  char b[32];
  std::snprintf(b, sizeof b, "%g", x);
  return b;
}

std::string point(const Vec3& p) { return "(" + num(p.x) + ", " + num(p.y) + ", " + num(p.z) + ")"; }

}  // namespace

const char* toString(PatientSpace space) {
  switch (space) {
    case PatientSpace::LPS: return "LPS";
    case PatientSpace::RAS: return "RAS";
    case PatientSpace::Unspecified: return "unspecified";
  }
  return "unspecified";
}

Vec3 CtVolume::indexToWorld(double i, double j, double k) const {
  const double x = i * spacing[0], y = j * spacing[1], z = k * spacing[2];
  return {origin.x + direction[0] * x + direction[1] * y + direction[2] * z,
          origin.y + direction[3] * x + direction[4] * y + direction[5] * z,
          origin.z + direction[6] * x + direction[7] * y + direction[8] * z};
}

Vec3 CtVolume::worldToIndex(const Vec3& world) const {
  // direction is orthonormal: its inverse is its transpose.
  const Vec3 d = world - origin;
  return {dot(axis(0), d) / spacing[0], dot(axis(1), d) / spacing[1], dot(axis(2), d) / spacing[2]};
}

void checkVolume(const CtVolume& v) {
  const std::string& f = v.sourcePath;
  for (int a = 0; a < 3; ++a) {
    if (v.dims[a] < 2)
      throw InputError(f, "axis " + std::to_string(a) + " has " + std::to_string(v.dims[a]) +
                              " samples; a CT volume needs at least 2 along each axis");
    if (!std::isfinite(v.spacing[a]) || v.spacing[a] <= 0)
      throw InputError(f, "spacing along axis " + std::to_string(a) + " is " + std::to_string(v.spacing[a]) +
                              " mm; it must be a positive number");
  }
  if (!isFinite(v.origin)) throw InputError(f, "the origin is not finite");
  // Beyond these, world coordinates lose the precision of a voxel (an origin of 1e23 mm, found by fuzzing,
  // put every vertex of the mesh on the same double): a corrupt header rather than a scan.
  for (int a = 0; a < 3; ++a)
    if (v.spacing[a] < kMinSpacingMm || v.spacing[a] > kMaxSpacingMm)
      throw InputError(f, "spacing along axis " + std::to_string(a) + " is " + num(v.spacing[a]) +
                              " mm, outside 1e-6 .. 1e6 mm (corrupt header?)");
  for (int c = 0; c < 8; ++c) {  // every corner: with axes of mixed signs, any of them may be the farthest
    const Vec3 corner = v.indexToWorld(c & 1 ? v.dims[0] - 1 : 0, c & 2 ? v.dims[1] - 1 : 0, c & 4 ? v.dims[2] - 1 : 0);
    if (!(std::abs(corner.x) <= kMaxWorldMm && std::abs(corner.y) <= kMaxWorldMm && std::abs(corner.z) <= kMaxWorldMm))
      throw InputError(f, "the volume reaches " + point(corner) + " mm, beyond ±1e7 mm (10 km) of the patient origin (corrupt origin or spacing?)");
  }
  for (int a = 0; a < 3; ++a) {
    if (std::abs(norm(v.axis(a)) - 1) > 1e-4)
      throw InputError(f, "direction of axis " + std::to_string(a) + " is not a unit vector");
    for (int b = a + 1; b < 3; ++b)
      if (std::abs(dot(v.axis(a), v.axis(b))) > 1e-3)
        throw InputError(f, "axes " + std::to_string(a) + " and " + std::to_string(b) +
                                " are not perpendicular (sheared or tilted volumes are not supported)");
  }
  if (v.values.size() != v.voxelCount())
    throw InputError(f, "holds " + std::to_string(v.values.size()) + " values for " + std::to_string(v.voxelCount()) +
                            " voxels");
  for (std::size_t i = 0; i < v.values.size(); ++i)
    if (!std::isfinite(v.values[i])) {
      const std::size_t plane = std::size_t(v.dims[0]) * v.dims[1];
      throw InputError(f, "voxel (" + std::to_string(i % v.dims[0]) + ", " + std::to_string((i / v.dims[0]) % v.dims[1]) +
                              ", " + std::to_string(i / plane) + ") is not a finite number");
    }
}

Vec3 convertPoint(const Vec3& p, PatientSpace from, PatientSpace to) {
  if (from == to || from == PatientSpace::Unspecified || to == PatientSpace::Unspecified) return p;
  return {-p.x, -p.y, p.z};
}

}  // namespace reamsim::ct
