#include "reamsim/ctimport/Preview.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "pipeline/Stages.h"

namespace reamsim::ct {

SliceImage extractSlice(const CtVolume& v, SliceAxis axis, int index, double lower, std::optional<double> upper) {
  const int a = int(axis), u = (a + 1) % 3, w = (a + 2) % 3;
  // Rows run along the lower-numbered remaining axis: K slice → (i, j), J slice → (i, k), I slice → (j, k).
  const int col = std::min(u, w), row = std::max(u, w);
  if (index < 0 || index >= v.dims[std::size_t(a)])
    throw std::out_of_range("slice " + std::to_string(index) + " is outside 0.." + std::to_string(v.dims[std::size_t(a)] - 1));
  SliceImage s;
  s.width = v.dims[std::size_t(col)];
  s.height = v.dims[std::size_t(row)];
  s.values.resize(std::size_t(s.width) * s.height);
  s.mask.resize(s.values.size());
  for (int y = 0; y < s.height; ++y)
    for (int x = 0; x < s.width; ++x) {
      int ijk[3];
      ijk[a] = index;
      ijk[col] = x;
      ijk[row] = y;
      const float value = v.at(ijk[0], ijk[1], ijk[2]);
      const std::size_t p = std::size_t(y) * s.width + x;
      s.values[p] = value;
      s.mask[p] = value >= lower && (!upper || value <= *upper) ? 1 : 0;
    }
  s.pixelSpacing[0] = v.spacing[std::size_t(col)];
  s.pixelSpacing[1] = v.spacing[std::size_t(row)];
  double o[3] = {0, 0, 0};
  o[a] = index;
  s.origin = v.indexToWorld(o[0], o[1], o[2]);
  s.rowDirection = v.axis(col);
  s.columnDirection = v.axis(row);
  s.space = v.space;
  return s;
}

CtVolume downsample(const CtVolume& v, int maxSamples) {
  if (maxSamples < 2) throw std::invalid_argument("downsample: at least 2 samples per axis");
  std::array<int, 3> f{};
  for (int a = 0; a < 3; ++a) f[std::size_t(a)] = (v.dims[std::size_t(a)] + maxSamples - 1) / maxSamples;
  if (f[0] == 1 && f[1] == 1 && f[2] == 1) return v;
  CtVolume out;
  out.sourcePath = v.sourcePath;
  out.format = v.format;
  out.space = v.space;
  out.valueUnit = v.valueUnit;
  out.direction = v.direction;
  out.integerValued = false;
  for (int a = 0; a < 3; ++a) {
    out.dims[std::size_t(a)] = std::max(2, v.dims[std::size_t(a)] / f[std::size_t(a)]);
    out.spacing[std::size_t(a)] = v.spacing[std::size_t(a)] * f[std::size_t(a)];
  }
  // A block's average sits at the centre of the block.
  out.origin = v.indexToWorld((f[0] - 1) / 2.0, (f[1] - 1) / 2.0, (f[2] - 1) / 2.0);
  out.values.assign(out.voxelCount(), 0.0f);
  for (int k = 0; k < out.dims[2]; ++k)
    for (int j = 0; j < out.dims[1]; ++j)
      for (int i = 0; i < out.dims[0]; ++i) {
        double sum = 0;
        int n = 0;
        for (int dk = 0; dk < f[2]; ++dk)
          for (int dj = 0; dj < f[1]; ++dj)
            for (int di = 0; di < f[0]; ++di) {
              const int x = i * f[0] + di, y = j * f[1] + dj, z = k * f[2] + dk;
              if (x >= v.dims[0] || y >= v.dims[1] || z >= v.dims[2]) continue;
              sum += v.at(x, y, z);
              ++n;
            }
        out.values[out.index(i, j, k)] = float(sum / std::max(n, 1));
      }
  return out;
}

ImportResult previewSurface(const CtVolume& volume, const ImportOptions& options, int maxSamples) {
  const CtVolume small = downsample(volume, maxSamples);
  ImportOptions o = options;
  o.smoothingIterations = std::min(o.smoothingIterations, 10);
  o.targetFaces = 0;
  o.volumeSmoothingSigmaMm = 0;  // the block average already smooths
  // The preview skips the self-intersection search and repair: build the stages directly.
  ImportResult r;
  detail::PaddedField field = detail::buildField(small, o, {});
  std::optional<std::array<int, 3>> seed;
  if (o.component == ComponentMode::Seed && o.seedWorld) {
    const Vec3 idx = small.worldToIndex(*o.seedWorld);
    seed = std::array<int, 3>{int(std::lround(idx.x)) + 1, int(std::lround(idx.y)) + 1, int(std::lround(idx.z)) + 1};
  }
  detail::keepRegions(field, o.component, seed, o.fillCavities, {});
  r.mesh = detail::extractIsosurface(field, small, {});
  if (o.smoothingIterations > 0) {
    const double v0 = signedVolume(r.mesh);
    r.mesh = detail::windowedSincSmooth(r.mesh, o.smoothingIterations, o.smoothingPassBand, {});
    detail::restoreVolume(r.mesh, v0);
  }
  r.space = small.space;
  if (o.outputSpace && small.space != PatientSpace::Unspecified && *o.outputSpace != small.space) {
    for (Vec3& p : r.mesh.vertices) p = convertPoint(p, small.space, *o.outputSpace);
    r.space = *o.outputSpace;
  }
  r.report.source = volume.sourcePath;
  r.report.dims = small.dims;
  r.report.spacing = small.spacing;
  r.report.isosurfaceFaces = r.mesh.triangles.size();
  return r;
}

}  // namespace reamsim::ct
