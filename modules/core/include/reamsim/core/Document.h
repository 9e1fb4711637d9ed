#pragma once
// The scene: owns the nodes and tells observers what changed.
//
// Threading: single-threaded by contract. Every call, and every callback, happens on the thread that
// owns the Document (the GUI's UI thread; workers post results to it). BoneState values, in
// contrast, are immutable and may be read from any thread.
//
// Notifications (DocumentEvent) are delivered in the order they happened, with these rules:
//  - Never re-entrantly: a change made by an observer is queued and delivered after every observer
//    has seen the current event. All observers therefore see the same sequence.
//  - Inside a BatchScope (nestable) nothing is delivered until the outermost scope ends. Pending
//    events are coalesced: a node modified many times is reported once (at its first position); a
//    node added in the same pending set is reported only as added; a removed node's pending
//    modifications are dropped; a node added and removed before delivery is not reported at all.
//  - Callbacks see the document's state at delivery time, so find(id) may return nullptr if an
//    earlier observer of the same event removed the node.
//  - An observer unsubscribed during a callback is not called again, even for the event in
//    progress; one subscribed during a callback receives the next event.
//  - Observers must not throw. Destroying the Document from a callback is not supported.
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <unordered_map>
#include <vector>

#include "reamsim/core/Node.h"
#include "reamsim/core/NodeId.h"
#include "reamsim/core/Signal.h"

namespace reamsim {

struct DocumentEvent {
  enum class Type { NodeAdded, NodeRemoved, NodeModified };
  Type type;
  NodeId id;
  friend bool operator==(const DocumentEvent& a, const DocumentEvent& b) { return a.type == b.type && a.id == b.id; }
};

class Document {
 public:
  Document() = default;
  ~Document();
  Document(const Document&) = delete;
  Document& operator=(const Document&) = delete;

  // Takes ownership and assigns a fresh id; a node this document removed comes back under its own id (an
  // undone removal: commands and views that name it by id find it again). No other node is ever given an id
  // this document issued. An empty name becomes the id text, e.g. "Bone1". Throws std::invalid_argument for a
  // null node or one that belongs to a document.
  Node& add(std::unique_ptr<Node> node);
  template <class T>
  T& add(std::unique_ptr<T> node) {
    return static_cast<T&>(add(std::unique_ptr<Node>(std::move(node))));
  }
  template <class T, class... A>
  T& create(A&&... args) {
    return add(std::make_unique<T>(std::forward<A>(args)...));
  }

  // Detaches the node and hands it back (drop it to destroy); nullptr when the id is unknown.
  std::unique_ptr<Node> remove(NodeId id);

  Node* find(NodeId id) const;
  template <class T>
  T* findAs(NodeId id) const {
    Node* n = find(id);
    return n && n->kind() == T::kKind ? static_cast<T*>(n) : nullptr;
  }
  bool contains(NodeId id) const { return find(id) != nullptr; }
  std::size_t size() const { return nodes_.size(); }

  std::vector<Node*> nodes() const;  // in insertion order
  std::vector<Node*> nodesOfKind(NodeKind kind) const;
  template <class T>
  std::vector<T*> nodesOf() const {
    std::vector<T*> out;
    for (Node* n : nodesOfKind(T::kKind)) out.push_back(static_cast<T*>(n));
    return out;
  }
  template <class T>
  T* firstOf() const {
    for (const auto& n : nodes_)
      if (n->kind() == T::kKind) return static_cast<T*>(n.get());
    return nullptr;
  }

  using Callback = std::function<void(const DocumentEvent&)>;
  Subscription subscribe(Callback callback);
  Subscription onNodeAdded(std::function<void(NodeId)> callback);
  Subscription onNodeRemoved(std::function<void(NodeId)> callback);
  Subscription onNodeModified(std::function<void(NodeId)> callback);
  // NodeModified for one node only (the per-node "Modified" notification).
  Subscription observeNode(NodeId id, std::function<void()> callback);

  // RAII batch: notifications are held and coalesced until the outermost scope is destroyed.
  class BatchScope {
   public:
    explicit BatchScope(Document& doc) : doc_(doc) { ++doc_.batchDepth_; }
    ~BatchScope() { doc_.endBatch(); }
    BatchScope(const BatchScope&) = delete;
    BatchScope& operator=(const BatchScope&) = delete;

   private:
    Document& doc_;
  };
  bool inBatch() const { return batchDepth_ > 0; }

 private:
  friend class Node;
  void nodeModified(NodeId id);
  void post(DocumentEvent event);
  void endBatch();
  void deliver();

  std::vector<std::unique_ptr<Node>> nodes_;
  std::unordered_map<NodeId, Node*> index_;
  std::unordered_map<NodeKind, std::uint64_t> lastSerial_;
  // The nodes removed (their Node::instance_), by id: only they get their id back. 16 bytes a removal.
  std::unordered_map<NodeId, std::uint64_t> removed_;
  Signal<DocumentEvent> signal_;
  std::deque<DocumentEvent> pending_;
  int batchDepth_ = 0;
  bool delivering_ = false;
};

}  // namespace reamsim
