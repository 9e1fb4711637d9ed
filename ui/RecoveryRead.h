#pragma once
// Reading a crash-recovery copy back — the copied bone, its undo history, the bones beside — on a worker: a CT
// bone of millions of faces takes seconds to read and validate (its self-intersection count ~20 s at 17
// million), and the window shows a progress dialog with Cancel meanwhile (MainWindow::offerRecovery). Nothing
// here touches the document; the window installs what was read.
#include <optional>
#include <string>
#include <vector>

#include "RecoveryFiles.h"
#include "reamsim/core/BoneHistory.h"
#include "reamsim/ui/PluginInterfaces.h"

namespace reamsim::ui {

struct RecoveredRead {
  bool cancelled = false;  // the progress callback said stop: nothing read is to be used
  std::string error;       // the copied bone could not be read: nothing else was
  ImportedBone bone;
  // The undo history up to the crash, when the copy has one and it reads back ending at the copied bone;
  // otherwise `historyError` says why (empty: the copy has none).
  std::optional<BoneHistory> history;
  std::string historyError;
  struct Beside {
    std::optional<ImportedBone> bone;
    std::string error;  // when `bone` is unset
  };
  std::vector<Beside> beside;  // as RecoveredBone::beside, in order
};

// Reads `copy`'s files with `importer` (no repair: the copy is what the session cut). `progress` hears each
// stage and stops the reading by returning false.
RecoveredRead readRecoveryCopy(const MeshImportInterface& importer, const RecoveredBone& copy,
                               const ProgressCallback& progress);

}  // namespace reamsim::ui
