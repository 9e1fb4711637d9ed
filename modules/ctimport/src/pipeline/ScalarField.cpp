// Threshold → signed field with a background border; optional Gaussian volume smoothing.
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "Stages.h"

namespace reamsim::ct::detail {
namespace {

std::vector<float> kernel(double sigma) {
  const int r = std::max(1, int(std::ceil(3 * sigma)));
  std::vector<float> k(std::size_t(2 * r + 1));
  double sum = 0;
  for (int i = -r; i <= r; ++i) sum += k[std::size_t(i + r)] = float(std::exp(-0.5 * i * i / (sigma * sigma)));
  for (float& x : k) x = float(x / sum);
  return k;
}

}  // namespace

void gaussianSmooth(std::vector<float>& values, const std::array<int, 3>& dims, const std::array<double, 3>& sigma,
                    const Tick& tick) {
  const std::size_t strides[3] = {1, std::size_t(dims[0]), std::size_t(dims[0]) * dims[1]};
  for (int axis = 0; axis < 3; ++axis) {
    if (sigma[std::size_t(axis)] < 0.05) continue;  // less than a twentieth of a voxel: nothing to do
    const std::vector<float> k = kernel(sigma[std::size_t(axis)]);
    const int r = int(k.size() / 2), n = dims[std::size_t(axis)];
    const std::size_t stride = strides[axis];
    const int a1 = (axis + 1) % 3, a2 = (axis + 2) % 3;
    const std::size_t lines = std::size_t(dims[std::size_t(a1)]) * dims[std::size_t(a2)];
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, lines), [&](const tbb::blocked_range<std::size_t>& range) {
      std::vector<float> line(static_cast<std::size_t>(n), 0.0f);
      for (std::size_t l = range.begin(); l != range.end(); ++l) {
        const std::size_t u = l % dims[std::size_t(a1)], w = l / dims[std::size_t(a1)];
        const std::size_t base = u * strides[a1] + w * strides[a2];
        for (int i = 0; i < n; ++i) line[std::size_t(i)] = values[base + std::size_t(i) * stride];
        for (int i = 0; i < n; ++i) {
          float s = 0;
          for (int t = -r; t <= r; ++t) s += k[std::size_t(t + r)] * line[std::size_t(std::clamp(i + t, 0, n - 1))];
          values[base + std::size_t(i) * stride] = s;
        }
      }
    });
    if (tick) tick((axis + 1) / 3.0);
  }
}

PaddedField buildField(const CtVolume& v, const ImportOptions& o, const Tick& tick) {
  if (o.upperThreshold && *o.upperThreshold < o.lowerThreshold)
    throw std::invalid_argument("the upper threshold (" + std::to_string(*o.upperThreshold) +
                                ") is below the lower threshold (" + std::to_string(o.lowerThreshold) + ")");
  const float* src = v.values.data();
  std::vector<float> smoothed;
  if (o.volumeSmoothingSigmaMm > 0) {
    smoothed = v.values;
    gaussianSmooth(smoothed, v.dims,
                   {o.volumeSmoothingSigmaMm / v.spacing[0], o.volumeSmoothingSigmaMm / v.spacing[1],
                    o.volumeSmoothingSigmaMm / v.spacing[2]},
                   [&](double f) { if (tick) tick(0.6 * f); });
    src = smoothed.data();
  }
  // Integer samples: put the iso-value half-way between integers so that no sample lies on it and
  // "value ≥ lower" (≤ upper) means exactly what it says.
  const bool integer = v.integerValued && o.volumeSmoothingSigmaMm <= 0;
  const double lo = integer ? std::ceil(o.lowerThreshold) - 0.5 : o.lowerThreshold;
  const double hi = !o.upperThreshold ? std::numeric_limits<double>::infinity()
                                      : (integer ? std::floor(*o.upperThreshold) + 0.5 : *o.upperThreshold);
  constexpr float kInsideOnIso = 1e-3f;  // a float sample exactly on the iso-value counts as inside

  PaddedField f;
  f.dims = {v.dims[0] + 2, v.dims[1] + 2, v.dims[2] + 2};
  f.values.assign(std::size_t(f.dims[0]) * f.dims[1] * f.dims[2], 0.0f);
  tbb::parallel_for(0, v.dims[2], [&](int k) {
    for (int j = 0; j < v.dims[1]; ++j) {
      const float* in = src + v.index(0, j, k);
      float* out = &f.values[f.index(1, j + 1, k + 1)];
      for (int i = 0; i < v.dims[0]; ++i) {
        const double x = in[i];
        double s = x - lo;
        if (o.upperThreshold) s = std::min(s, hi - x);
        float fs = float(s);
        if (fs == 0.0f) fs = kInsideOnIso;
        out[i] = fs;
      }
    }
  });
  if (tick) tick(0.9);
  // Border: the mirror image of the adjacent voxel, negative. An inside voxel at the edge of the scan thus
  // meets the surface exactly half way, on the boundary of the field of view.
  const int nx = f.dims[0], ny = f.dims[1], nz = f.dims[2];
  const auto pad = [&](int i, int j, int k, int ii, int jj, int kk) {
    const float inner = f.values[f.index(ii, jj, kk)];
    f.values[f.index(i, j, k)] = -std::max(std::abs(inner), kInsideOnIso);
  };
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        const bool border = i == 0 || j == 0 || k == 0 || i == nx - 1 || j == ny - 1 || k == nz - 1;
        if (!border) {
          if (j > 0 && j < ny - 1 && k > 0 && k < nz - 1) i = nx - 2;  // skip the interior of this row
          continue;
        }
        pad(i, j, k, std::clamp(i, 1, nx - 2), std::clamp(j, 1, ny - 2), std::clamp(k, 1, nz - 2));
      }
  if (tick) tick(1.0);
  return f;
}

}  // namespace reamsim::ct::detail
