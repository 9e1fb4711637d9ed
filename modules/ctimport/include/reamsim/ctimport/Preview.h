#pragma once
// What a thin GUI plugin needs besides importBone (no Qt, no rendering here):
//  - orthogonal slices of the volume with the threshold mask, to draw with the threshold overlaid;
//  - a quick low-resolution surface for a live preview while the threshold is being dragged.
#include <cstdint>
#include <optional>
#include <vector>

#include "reamsim/ctimport/CtImport.h"
#include "reamsim/ctimport/CtVolume.h"

namespace reamsim::ct {

enum class SliceAxis { I = 0, J = 1, K = 2 };  // the volume axis held fixed

struct SliceImage {
  int width = 0, height = 0;         // pixels; row-major, `width` along `rowDirection`
  std::vector<float> values;         // the volume's values (HU for CT)
  std::vector<std::uint8_t> mask;    // 1 where lower ≤ value (≤ upper): the threshold overlay
  double pixelSpacing[2] = {1, 1};   // mm along a row, between rows
  Vec3 origin;                       // world position of pixel (0, 0)
  Vec3 rowDirection, columnDirection;  // world directions of increasing column / row index
  PatientSpace space = PatientSpace::Unspecified;
};

// Throws std::out_of_range if `index` is outside the volume along `axis`.
SliceImage extractSlice(const CtVolume& volume, SliceAxis axis, int index, double lowerThreshold,
                        std::optional<double> upperThreshold = std::nullopt);

// Averages blocks of voxels so that no axis has more than `maxSamples` samples (geometry kept consistent).
CtVolume downsample(const CtVolume& volume, int maxSamples);

// importBone on a volume downsampled to `maxSamples` per axis, with light smoothing, no decimation and
// no self-intersection repair: tens of milliseconds for a clinical CT. For display only.
ImportResult previewSurface(const CtVolume& volume, const ImportOptions& options, int maxSamples = 96);

}  // namespace reamsim::ct
