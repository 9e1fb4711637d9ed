#pragma once
// The planning dock's measure of the glenoid face (reamsim/ream/GlenoidFace.h) on the bone as opened (its
// history's first state) and as it is now, taken on a worker thread: it costs O(bone) (~3 ms at 400k
// triangles, ~0.1 s on a CT bone of millions), and the dock asks on every reamer move. Each state is measured
// once per glenoid centre and the last few answers are kept, so a move, an undo or a redo asks nothing new.
#include <QFutureWatcher>
#include <QObject>
#include <cstdint>
#include <deque>
#include <optional>
#include <string>
#include <vector>

#include "reamsim/core/BoneNode.h"
#include "reamsim/ream/GlenoidFace.h"

namespace reamsim::ui {

class GlenoidFaceMeasure : public QObject {
  Q_OBJECT
 public:
  struct Measured {
    std::uint64_t revision = 0;      // of the bone state measured
    Vec3 centre;                     // the glenoid centre it was measured about
    std::optional<GlenoidFace> face;
    std::string error;               // why there is no face
  };

  explicit GlenoidFaceMeasure(QObject* parent = nullptr);

  // Measures the bone as opened and as it is now about `centre`, unless known or being measured; cheap otherwise.
  void ask(const BoneNode& bone, const Vec3& centre);
  // What is known of state `revision` about `centre`; nullptr while it is being (or not yet) measured.
  const Measured* find(std::uint64_t revision, const Vec3& centre) const;
  bool measuring() const { return watcher_.isRunning(); }

 Q_SIGNALS:
  void measured();  // a job has finished: what find() knows has grown; ask again for what came since

 private:
  static constexpr std::size_t kKept = 8;  // answers kept, newest first
  std::deque<Measured> known_;
  QFutureWatcher<std::vector<Measured>> watcher_;
};

}  // namespace reamsim::ui
