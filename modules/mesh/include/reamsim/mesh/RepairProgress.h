#pragma once
// Progress and cancellation of long operations: a repair (and the volumetric remesh inside it), which can
// take minutes on a large dirty mesh, and the CT import (reamsim/ctimport/Progress.h names the same types).
// The callback is called from the calling thread with the fraction done (0..1) and the stage's name;
// returning false stops the work at its next check with an exception derived from StageCancelled.
#include <functional>
#include <stdexcept>
#include <string>
#include <utility>

namespace reamsim {

using ProgressCallback = std::function<bool(double fraction, const std::string& stage)>;
using RepairProgress = ProgressCallback;

// Thrown where a progress callback asked to stop; says at which stage.
class StageCancelled : public std::runtime_error {
 public:
  StageCancelled(const std::string& what, std::string stage) : std::runtime_error(what), stage_(std::move(stage)) {}
  const std::string& stage() const { return stage_; }

 private:
  std::string stage_;
};

class RepairCancelled : public StageCancelled {
 public:
  explicit RepairCancelled(const std::string& stage) : StageCancelled("repair cancelled during " + stage, stage) {}
};

// Reports `fraction` (of the whole) at `stage`; throws RepairCancelled when asked to stop.
inline void reportRepairProgress(const RepairProgress& progress, double fraction, const std::string& stage) {
  if (progress && !progress(fraction, stage)) throw RepairCancelled(stage);
}

// One stage's share [begin, end] of the whole, for work that checks as it goes (the remesh's marching
// tetrahedra, far-region signs, decimation and distances: seconds each at millions of triangles).
// keepGoing(f) reports begin + f (end - begin) at `stage` and says whether to go on; check(f) throws
// RepairCancelled instead; part(from, to) is the share [from, to] of this one, for work done in pieces.
// Made without a callback, it reports nothing and always goes on.
struct StageProgress {
  const RepairProgress* progress = nullptr;
  double begin = 0, end = 1;
  std::string stage;
  double at(double fraction) const { return begin + fraction * (end - begin); }
  StageProgress part(double from, double to) const { return {progress, at(from), at(to), stage}; }
  bool keepGoing(double fraction) const { return !progress || !*progress || (*progress)(at(fraction), stage); }
  void check(double fraction) const {
    if (!keepGoing(fraction)) throw RepairCancelled(stage);
  }
};

}  // namespace reamsim
