#pragma once
// Proximity alerts between a reamer and a bone. They live in one AlertNode so they reuse the
// document's notification path instead of a second observer mechanism.
#include <string>
#include <vector>

#include "reamsim/core/Node.h"

namespace reamsim {

enum class AlertKind { BoundsOverlap, Contact };

struct Alert {
  AlertKind kind = AlertKind::BoundsOverlap;
  NodeId reamer;
  NodeId bone;
  double distanceMm = 0;  // minimum distance reamer-bone when known (0 at contact)

  friend bool operator==(const Alert& a, const Alert& b) {
    return a.kind == b.kind && a.reamer == b.reamer && a.bone == b.bone && a.distanceMm == b.distanceMm;
  }
  friend bool operator!=(const Alert& a, const Alert& b) { return !(a == b); }
};

// "Reamer1 / Bone1: bounding boxes overlap (distance 1.25 mm)" or "...: contact".
std::string describe(const Alert& alert);

class AlertNode : public Node {
 public:
  static constexpr NodeKind kKind = NodeKind::Alert;
  explicit AlertNode(std::string name = {}) : Node(std::move(name)) {}
  NodeKind kind() const override { return kKind; }

  const std::vector<Alert>& alerts() const { return alerts_; }
  bool has(AlertKind kind) const;
  // Replaces the active alerts; reports a modification only when they actually changed, because the
  // collision check re-evaluates them on every pose update.
  void setAlerts(std::vector<Alert> alerts);
  void clear() { setAlerts({}); }

 private:
  std::vector<Alert> alerts_;
};

}  // namespace reamsim
