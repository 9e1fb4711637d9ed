#pragma once
// Progress reporting and cancellation for long operations. The callback receives the overall fraction
// (0..1) and the current stage's name; returning false cancels: the operation stops at the next check
// and throws ImportCancelled. It may be called from the calling thread only.
#include <functional>
#include <stdexcept>
#include <string>

namespace reamsim::ct {

using ProgressCallback = std::function<bool(double fraction, const std::string& stage)>;

class ImportCancelled : public std::runtime_error {
 public:
  explicit ImportCancelled(const std::string& stage) : std::runtime_error("cancelled during " + stage), stage_(stage) {}
  const std::string& stage() const { return stage_; }

 private:
  std::string stage_;
};

}  // namespace reamsim::ct
