#include "reamsim/core/Node.h"

#include "reamsim/core/Document.h"

namespace reamsim {

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
