#include "reamsim/core/LogNode.h"

namespace reamsim {

void LogNode::append(CutLogEntry entry) {
  entries_.push_back(std::move(entry));
  markModified();
}

}  // namespace reamsim
