#include "reamsim/core/Document.h"

#include <algorithm>
#include <stdexcept>

namespace reamsim {

Document::~Document() {
  for (auto& n : nodes_) n->document_ = nullptr;  // nodes die with us; no notifications
}

Node& Document::add(std::unique_ptr<Node> node) {
  if (!node) throw std::invalid_argument("Document::add: null node");
  if (node->document_) throw std::invalid_argument("Document::add: node already belongs to a document");
  const NodeKind kind = node->kind();
  // A node this document removed comes back under its id (undo of a removal: commands that name it by id
  // still find it); any other node gets a new one.
  const auto removed = removed_.find(node->id_);
  if (node->id_.valid() && removed != removed_.end() && removed->second == node->instance_ && !index_.count(node->id_))
    removed_.erase(removed);
  else
    node->id_ = NodeId::make(kind, ++lastSerial_[kind]);
  node->document_ = this;
  if (node->name_.empty()) node->name_ = node->id_.toString();
  Node& ref = *node;
  index_.emplace(ref.id_, &ref);
  nodes_.push_back(std::move(node));
  post({DocumentEvent::Type::NodeAdded, ref.id_});
  return ref;
}

std::unique_ptr<Node> Document::remove(NodeId id) {
  auto it = std::find_if(nodes_.begin(), nodes_.end(), [&](const auto& n) { return n->id_ == id; });
  if (it == nodes_.end()) return nullptr;
  std::unique_ptr<Node> node = std::move(*it);
  nodes_.erase(it);
  index_.erase(id);
  node->document_ = nullptr;
  removed_[id] = node->instance_;
  post({DocumentEvent::Type::NodeRemoved, id});
  return node;
}

Node* Document::find(NodeId id) const {
  auto it = index_.find(id);
  return it == index_.end() ? nullptr : it->second;
}

std::vector<Node*> Document::nodes() const {
  std::vector<Node*> out;
  out.reserve(nodes_.size());
  for (const auto& n : nodes_) out.push_back(n.get());
  return out;
}

std::vector<Node*> Document::nodesOfKind(NodeKind kind) const {
  std::vector<Node*> out;
  for (const auto& n : nodes_)
    if (n->kind() == kind) out.push_back(n.get());
  return out;
}

Subscription Document::subscribe(Callback callback) { return signal_.connect(std::move(callback)); }

namespace {
Document::Callback filtered(DocumentEvent::Type type, std::function<void(NodeId)> callback) {
  return [type, cb = std::move(callback)](const DocumentEvent& e) {
    if (e.type == type) cb(e.id);
  };
}
}  // namespace

Subscription Document::onNodeAdded(std::function<void(NodeId)> callback) {
  return subscribe(filtered(DocumentEvent::Type::NodeAdded, std::move(callback)));
}
Subscription Document::onNodeRemoved(std::function<void(NodeId)> callback) {
  return subscribe(filtered(DocumentEvent::Type::NodeRemoved, std::move(callback)));
}
Subscription Document::onNodeModified(std::function<void(NodeId)> callback) {
  return subscribe(filtered(DocumentEvent::Type::NodeModified, std::move(callback)));
}
Subscription Document::observeNode(NodeId id, std::function<void()> callback) {
  return subscribe([id, cb = std::move(callback)](const DocumentEvent& e) {
    if (e.type == DocumentEvent::Type::NodeModified && e.id == id) cb();
  });
}

void Document::nodeModified(NodeId id) { post({DocumentEvent::Type::NodeModified, id}); }

// Coalescing only looks at events not yet delivered; the queue stays short because of it.
void Document::post(DocumentEvent event) {
  using Type = DocumentEvent::Type;
  auto pendingOf = [&](Type type) {
    return std::find(pending_.begin(), pending_.end(), DocumentEvent{type, event.id});
  };
  switch (event.type) {
    case Type::NodeAdded:
      pending_.push_back(event);
      break;
    case Type::NodeModified:
      if (pendingOf(Type::NodeModified) == pending_.end() && pendingOf(Type::NodeAdded) == pending_.end())
        pending_.push_back(event);
      break;
    case Type::NodeRemoved: {
      if (auto m = pendingOf(Type::NodeModified); m != pending_.end()) pending_.erase(m);
      if (auto a = pendingOf(Type::NodeAdded); a != pending_.end()) {
        pending_.erase(a);  // nobody has seen it: report nothing
      } else {
        pending_.push_back(event);
      }
      break;
    }
  }
  deliver();
}

void Document::endBatch() {
  --batchDepth_;
  deliver();
}

// Drains the queue unless a batch is open or a delivery is already running further up the stack
// (that loop will pick up whatever the callbacks queued).
void Document::deliver() {
  if (batchDepth_ > 0 || delivering_) return;
  delivering_ = true;
  struct Reset {
    bool& flag;
    ~Reset() { flag = false; }
  } reset{delivering_};
  while (!pending_.empty() && batchDepth_ == 0) {
    const DocumentEvent event = pending_.front();
    pending_.pop_front();
    signal_.emit(event);
  }
}

}  // namespace reamsim
