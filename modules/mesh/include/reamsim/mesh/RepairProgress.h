#pragma once
// Progress and cancellation of a repair (and of the volumetric remesh inside it), which can take minutes
// on a large dirty mesh. The callback is called from the calling thread with the fraction done (0..1) and
// the stage's name; returning false stops the work at its next check with RepairCancelled.
#include <functional>
#include <stdexcept>
#include <string>

namespace reamsim {

using RepairProgress = std::function<bool(double fraction, const std::string& stage)>;

class RepairCancelled : public std::runtime_error {
 public:
  explicit RepairCancelled(const std::string& stage) : std::runtime_error("repair cancelled during " + stage), stage_(stage) {}
  const std::string& stage() const { return stage_; }

 private:
  std::string stage_;
};

// Reports `fraction` of a stage that spans [begin, end] of the whole; throws RepairCancelled when asked to stop.
inline void reportRepairProgress(const RepairProgress& progress, double begin, double end, double fraction,
                                 const std::string& stage) {
  if (progress && !progress(begin + (end - begin) * fraction, stage)) throw RepairCancelled(stage);
}

}  // namespace reamsim
