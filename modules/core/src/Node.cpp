#include "reamsim/core/Node.h"

#include "reamsim/core/Document.h"

#include <atomic>

namespace reamsim {

std::uint64_t Node::nextInstance() {
  static std::atomic<std::uint64_t> counter{0};
  return ++counter;
}

void Node::setName(std::string name) {
  if (name == name_) return;
  name_ = std::move(name);
  markModified();
}

void Node::markModified() {
  ++modifiedCount_;
  if (document_) document_->nodeModified(id_);
}

}  // namespace reamsim
