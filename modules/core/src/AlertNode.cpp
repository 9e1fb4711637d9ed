#include <cstdio>

#include "reamsim/core/AlertNode.h"

namespace reamsim {

std::string describe(const Alert& alert) {
  std::string text = alert.reamer.toString() + " / " + alert.bone.toString() + ": ";
  if (alert.kind == AlertKind::Contact) return text + "contact";
  char distance[64];
  std::snprintf(distance, sizeof distance, " (distance %.2f mm)", alert.distanceMm);
  return text + "bounding boxes overlap" + distance;
}

bool AlertNode::has(AlertKind kind) const {
  for (const Alert& a : alerts_)
    if (a.kind == kind) return true;
  return false;
}

void AlertNode::setAlerts(std::vector<Alert> alerts) {
  if (alerts == alerts_) return;
  alerts_ = std::move(alerts);
  markModified();
}

}  // namespace reamsim
