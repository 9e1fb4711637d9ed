// resampleSlantedSlices (SlantedSlices.h). The DICOM reader has vtkDICOMCTRectifier for its own series;
// NRRD, MetaImage and NIfTI headers carry the slant in their step vectors, and were refused before.
#include "SlantedSlices.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <new>

#include "reamsim/mesh/MeshError.h"

namespace reamsim::ct::io {
namespace {

constexpr double kPerpendicular = 1e-3;  // as checkVolume's test of the axes

}  // namespace

int slantedAxis(const std::array<Vec3, 3>& axes) {
  // The slice axis is the last one whose two others are perpendicular (the k axis first, as files store slices).
  for (int s : {2, 1, 0}) {
    const int p = (s + 1) % 3, q = (s + 2) % 3;
    if (std::abs(dot(axes[std::size_t(p)], axes[std::size_t(q)])) > kPerpendicular) continue;
    const Vec3 normal = normalized(cross(axes[std::size_t(p)], axes[std::size_t(q)]));
    const double along = std::abs(dot(normal, axes[std::size_t(s)]));
    if (along >= std::cos(kMaxSlantDegrees * M_PI / 180)) return s;
  }
  return -1;
}

bool resampleSlantedSlices(CtVolume& v, const std::function<bool()>& keepGoing) {
  // A volume that breaks checkVolume's other invariants is left for it to refuse with its own message.
  if (v.dims[0] < 2 || v.dims[1] < 2 || v.dims[2] < 2 || v.values.size() != v.voxelCount()) return true;
  const std::array<Vec3, 3> axes{v.axis(0), v.axis(1), v.axis(2)};
  bool perpendicular = true;
  for (int a = 0; a < 3; ++a)
    for (int b = a + 1; b < 3; ++b) perpendicular = perpendicular && std::abs(dot(axes[a], axes[b])) <= kPerpendicular;
  if (perpendicular) return true;
  const int s = slantedAxis(axes);
  if (s < 0) return true;  // checkVolume refuses it, naming the axes
  const int p = (s + 1) % 3, q = (s + 2) % 3;
  Vec3 normal = normalized(cross(axes[std::size_t(p)], axes[std::size_t(q)]));
  if (dot(normal, axes[std::size_t(s)]) < 0) normal = -normal;  // the slices keep their order
  // One step along s = the distance between slices along the normal + a shift within the slice plane, which the
  // new grid takes back slice by slice: new voxel (ip, iq, k) = old (ip - k·dp, iq - k·dq, k).
  const Vec3 step = axes[std::size_t(s)] * v.spacing[std::size_t(s)];
  const double between = dot(step, normal);
  const Vec3 shift = step - normal * between;
  const double dp = dot(shift, axes[std::size_t(p)]) / v.spacing[std::size_t(p)];
  const double dq = dot(shift, axes[std::size_t(q)]) / v.spacing[std::size_t(q)];

  const float air = *std::min_element(v.values.begin(), v.values.end());
  std::vector<float> out;
  try {
    out.resize(v.values.size());
  } catch (const std::bad_alloc&) {
    throw InputError(v.sourcePath, "out of memory resampling the slanted slices (" + std::to_string(v.values.size()) + " voxels)");
  }
  const int np = v.dims[std::size_t(p)], nq = v.dims[std::size_t(q)], ns = v.dims[std::size_t(s)];
  std::array<int, 3> at{};
  const auto old = [&](int ip, int iq, int k) {
    at[std::size_t(p)] = ip, at[std::size_t(q)] = iq, at[std::size_t(s)] = k;
    return v.values[v.index(at[0], at[1], at[2])];
  };
  std::size_t outside = 0;
  for (int k = 0; k < ns; ++k) {
    if (k % 8 == 0 && keepGoing && !keepGoing()) return false;
    for (int iq = 0; iq < nq; ++iq)
      for (int ip = 0; ip < np; ++ip) {
        const double fp = ip - k * dp, fq = iq - k * dq;
        at[std::size_t(p)] = ip, at[std::size_t(q)] = iq, at[std::size_t(s)] = k;
        float& value = out[v.index(at[0], at[1], at[2])];
        // Within half a voxel of the slice's edge the edge value holds (as a scanner's field of view ends).
        if (!(fp > -0.5 && fp < np - 0.5 && fq > -0.5 && fq < nq - 0.5)) {
          value = air;
          ++outside;
          continue;
        }
        const double cp = std::clamp(fp, 0.0, double(np - 1)), cq = std::clamp(fq, 0.0, double(nq - 1));
        const int p0 = std::min(int(cp), np - 2), q0 = std::min(int(cq), nq - 2);
        const double tp = cp - p0, tq = cq - q0;
        value = float((1 - tq) * ((1 - tp) * old(p0, q0, k) + tp * old(p0 + 1, q0, k)) +
                      tq * ((1 - tp) * old(p0, q0 + 1, k) + tp * old(p0 + 1, q0 + 1, k)));
      }
  }
  v.values = std::move(out);
  v.spacing[std::size_t(s)] = between;
  v.direction[std::size_t(s)] = normal.x;
  v.direction[3 + std::size_t(s)] = normal.y;
  v.direction[6 + std::size_t(s)] = normal.z;
  v.integerValued = v.integerValued && std::all_of(v.values.begin(), v.values.end(), [](float x) { return x == std::floor(x); });
  char note[320];
  std::snprintf(note, sizeof note,
                "the slices are slanted by %.1f° against their normal (axis %d; a gantry tilt?): they were resampled "
                "onto a rectangular grid (linear interpolation within each slice), %.1f%% of the voxels falling "
                "outside the scanned slices set to the lowest value",
                std::acos(std::min(1.0, between / norm(step))) * 180 / M_PI, s, 100.0 * double(outside) / double(out.size()));
  v.notes.push_back(note);
  return true;
}

}  // namespace reamsim::ct::io
