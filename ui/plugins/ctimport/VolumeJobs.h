#pragma once
// The CT import dialog's work off the UI thread (QtConcurrent): reading a volume, the live preview
// surface, the full import. Each returns an outcome value (never throws); the dialog applies it on the
// UI thread. Progress goes back to the UI thread through ProgressRelay, which also carries Cancel.
#include <QObject>
#include <QPointer>
#include <QString>
#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>

#include "reamsim/ctimport/CtImport.h"
#include "reamsim/ctimport/CtVolume.h"
#include "reamsim/ctimport/Progress.h"
#include "reamsim/ui/ProgressRelay.h"  // progressRelay

namespace reamsim::ui::ct_import {

using VolumePtr = std::shared_ptr<const ct::CtVolume>;

struct LoadOutcome {
  VolumePtr volume;
  float minValue = 0, maxValue = 0;
  float lowPercentile = 0, highPercentile = 0;  // 0.5 % and 99.5 %: a window for data that is not HU
  bool looksLikeHu = false;                      // says HU, or has air (≤ -500) in it
  QString error;                                 // names the file and the problem
  bool cancelled = false;
};
LoadOutcome loadVolume(const QString& path, const ct::ProgressCallback& progress);

struct PreviewOutcome {
  std::uint64_t generation = 0;  // which request this answers (older ones are dropped)
  TriangleMesh mesh;
  QString error;                 // e.g. nothing in the threshold range
};
PreviewOutcome computePreview(const VolumePtr& volume, const ct::ImportOptions& options, std::uint64_t generation);

struct ImportOutcome {
  ct::ImportResult result;
  QString error;
  QString cancelledStage;  // non-empty: cancelled by the user during this stage
};
ImportOutcome runImport(const VolumePtr& volume, const ct::ImportOptions& options, const ct::ProgressCallback& progress);

}  // namespace reamsim::ui::ct_import
