#pragma once
// Base of everything a Document holds (the MRML idea, small): an id, a name, and a modification
// counter. Setters of derived nodes call markModified(), which bumps the counter and, when the node
// belongs to a Document, reports NodeModified through it (coalesced inside a Document::BatchScope).
#include <cstdint>
#include <string>

#include "reamsim/core/NodeId.h"

namespace reamsim {

class Document;

class Node {
 public:
  virtual ~Node() = default;
  Node(const Node&) = delete;
  Node& operator=(const Node&) = delete;

  virtual NodeKind kind() const = 0;
  NodeId id() const { return id_; }  // invalid until added to a Document
  Document* document() const { return document_; }

  const std::string& name() const { return name_; }
  void setName(std::string name);

  // Incremented on every markModified(), batched or not; lets views skip redundant refreshes.
  std::uint64_t modifiedCount() const { return modifiedCount_; }
  void markModified();

 protected:
  explicit Node(std::string name) : name_(std::move(name)) {}

 private:
  friend class Document;
  NodeId id_;
  const std::uint64_t instance_ = nextInstance();  // which object this is (addresses are reused, this is not)
  static std::uint64_t nextInstance();
  Document* document_ = nullptr;
  std::string name_;
  std::uint64_t modifiedCount_ = 0;
};

}  // namespace reamsim
