#pragma once
// The planning dock's measure of the glenoid face (reamsim/ream/GlenoidFace.h) on the bone as opened (its
// history's first state) and as it is now, taken on a worker thread: it costs O(bone) (~4 ms at 400k
// triangles, ~0.1 s on a CT bone of millions), and the dock asks on every reamer move. Each state is measured
// once per glenoid centre; the answers asked for last are kept (least recently asked dropped first), so a move,
// an undo or a redo among recent states asks nothing new, and the bone as opened, asked every time, stays.
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
    std::uint64_t revision = 0;        // of the bone state measured
    std::uint64_t openedRevision = 0;  // of the first state of the history it was in (which bone's it is)
    Vec3 centre;                       // the glenoid centre it was measured about
    std::optional<GlenoidFace> face;
    std::string error;                 // why there is no face
  };

  explicit GlenoidFaceMeasure(QObject* parent = nullptr);

  // Measures the bone as opened and as it is now about `centre`, unless known or being measured; cheap otherwise.
  void ask(const BoneNode& bone, const Vec3& centre);
  // What is known of state `revision` about `centre`; nullptr while it is being (or not yet) measured.
  const Measured* find(std::uint64_t revision, const Vec3& centre) const;
  // The last state measured of the history whose first state is `openedRevision`, other than that one, about
  // `centre`: what to show while the state now is being measured (a cut's, during reaming).
  const Measured* latestCut(std::uint64_t openedRevision, const Vec3& centre) const;
  bool measuring() const { return watcher_.isRunning(); }
  // How many times a bone as opened has been measured (once per bone and centre while its answer is kept).
  int openedMeasures() const { return openedMeasures_; }

 Q_SIGNALS:
  void measured();  // a job has finished: what find() knows has grown; ask again for what came since

 private:
  void keep(Measured m);                                   // at the front; the least recently asked dropped
  bool touch(std::uint64_t revision, const Vec3& centre);  // to the front when known

  static constexpr std::size_t kKept = 16;
  std::deque<Measured> known_;  // most recently asked first
  QFutureWatcher<std::vector<Measured>> watcher_;
  int openedMeasures_ = 0;
};

}  // namespace reamsim::ui
