#include "reamsim/core/NodeId.h"


namespace reamsim {

namespace {
constexpr NodeKind kKinds[] = {NodeKind::Bone, NodeKind::Reamer, NodeKind::Plan, NodeKind::Log, NodeKind::Alert,
                              NodeKind::Interaction};
}

const char* kindName(NodeKind kind) {
  switch (kind) {
    case NodeKind::Bone: return "Bone";
    case NodeKind::Reamer: return "Reamer";
    case NodeKind::Plan: return "Plan";
    case NodeKind::Log: return "Log";
    case NodeKind::Alert: return "Alert";
    case NodeKind::Interaction: return "Interaction";
  }
  return "Node";
}

std::string NodeId::toString() const {
  if (!valid()) return "<invalid>";
  return std::string(kindName(kind())) + std::to_string(serial());
}

std::optional<NodeId> NodeId::parse(std::string_view text) {
  for (NodeKind kind : kKinds) {
    const std::string_view prefix = kindName(kind);
    if (text.size() <= prefix.size() || text.substr(0, prefix.size()) != prefix) continue;
    const std::string_view digits = text.substr(prefix.size());
    // Canonical form only (no leading zero); 17 digits cannot overflow, the mask check bounds it.
    if (digits[0] == '0' || digits.size() > 17) return std::nullopt;
    std::uint64_t serial = 0;
    for (char c : digits) {
      if (c < '0' || c > '9') return std::nullopt;
      serial = serial * 10 + static_cast<std::uint64_t>(c - '0');
    }
    if (serial > kSerialMask) return std::nullopt;
    return make(kind, serial);
  }
  return std::nullopt;
}

std::ostream& operator<<(std::ostream& os, NodeId id) { return os << id.toString(); }

}  // namespace reamsim
