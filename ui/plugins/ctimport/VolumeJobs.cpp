#include "VolumeJobs.h"

#include <algorithm>
#include <cmath>
#include <exception>
#include <vector>

#include "reamsim/ctimport/Preview.h"
#include "reamsim/ctimport/VolumeIO.h"

namespace reamsim::ui::ct_import {
namespace {

// Percentiles from at most ~1M samples taken at a regular stride: enough for a display window.
void percentiles(const std::vector<float>& values, float& low, float& high) {
  const std::size_t stride = std::max<std::size_t>(1, values.size() / 1000000);
  std::vector<float> s;
  s.reserve(values.size() / stride + 1);
  for (std::size_t i = 0; i < values.size(); i += stride) s.push_back(values[i]);
  if (s.empty()) return;
  const auto at = [&](double q) {
    const std::size_t k = std::min(s.size() - 1, std::size_t(q * double(s.size() - 1)));
    std::nth_element(s.begin(), s.begin() + std::ptrdiff_t(k), s.end());
    return s[k];
  };
  low = at(0.005);
  high = at(0.995);
}

}  // namespace

LoadOutcome loadVolume(const QString& path, const ct::ProgressCallback& progress) {
  LoadOutcome out;
  try {
    auto volume = std::make_shared<ct::CtVolume>(ct::readVolume(path.toStdString(), progress));
    const auto [mn, mx] = std::minmax_element(volume->values.begin(), volume->values.end());
    out.minValue = *mn;
    out.maxValue = *mx;
    percentiles(volume->values, out.lowPercentile, out.highPercentile);
    out.looksLikeHu = volume->valueUnit == "HU" || out.minValue <= -500;
    out.volume = std::move(volume);
  } catch (const ct::ImportCancelled&) {
    out.cancelled = true;
  } catch (const std::exception& e) {
    out.error = QString::fromStdString(e.what());
  }
  return out;
}

PreviewOutcome computePreview(const VolumePtr& volume, const ct::ImportOptions& options, std::uint64_t generation) {
  PreviewOutcome out;
  out.generation = generation;
  try {
    out.mesh = ct::previewSurface(*volume, options).mesh;
  } catch (const std::exception& e) {
    out.error = QString::fromStdString(e.what());
  }
  return out;
}

ImportOutcome runImport(const VolumePtr& volume, const ct::ImportOptions& options, const ct::ProgressCallback& progress) {
  ImportOutcome out;
  try {
    out.result = ct::importBone(*volume, options, progress);
  } catch (const ct::ImportCancelled& e) {
    out.cancelledStage = QString::fromStdString(e.stage());
  } catch (const std::exception& e) {
    out.error = QString::fromStdString(e.what());
  }
  return out;
}

}  // namespace reamsim::ui::ct_import
