#pragma once
// Strong, printable node identifier. The kind is packed into the top byte so an id alone prints as
// "Bone1" or "Reamer2"; the low 56 bits are a per-document, per-kind serial that is never reused.
#include <cstdint>
#include <functional>
#include <optional>
#include <ostream>
#include <string>
#include <string_view>

namespace reamsim {

enum class NodeKind : std::uint8_t { Bone = 1, Reamer = 2, Plan = 3, Log = 4, Alert = 5, Interaction = 6 };

// "Bone", "Reamer", "Plan", "Log", "Alert", "Interaction".
const char* kindName(NodeKind kind);

class NodeId {
 public:
  static constexpr std::uint64_t kSerialMask = (std::uint64_t{1} << 56) - 1;

  constexpr NodeId() = default;  // the invalid id
  static constexpr NodeId make(NodeKind kind, std::uint64_t serial) {
    return NodeId((std::uint64_t{static_cast<std::uint8_t>(kind)} << 56) | (serial & kSerialMask));
  }
  static constexpr NodeId fromValue(std::uint64_t value) { return NodeId(value); }
  // Inverse of toString(); nullopt for anything else ("Bone0", "bone1", "Bone", "Knee3").
  static std::optional<NodeId> parse(std::string_view text);

  constexpr bool valid() const { return value_ != 0; }
  constexpr std::uint64_t value() const { return value_; }
  constexpr NodeKind kind() const { return static_cast<NodeKind>(value_ >> 56); }
  constexpr std::uint64_t serial() const { return value_ & kSerialMask; }
  std::string toString() const;  // "Bone1"; "<invalid>" for the invalid id

  friend constexpr bool operator==(NodeId a, NodeId b) { return a.value_ == b.value_; }
  friend constexpr bool operator!=(NodeId a, NodeId b) { return a.value_ != b.value_; }
  friend constexpr bool operator<(NodeId a, NodeId b) { return a.value_ < b.value_; }

 private:
  explicit constexpr NodeId(std::uint64_t value) : value_(value) {}
  std::uint64_t value_ = 0;
};

std::ostream& operator<<(std::ostream& os, NodeId id);

}  // namespace reamsim

template <>
struct std::hash<reamsim::NodeId> {
  std::size_t operator()(reamsim::NodeId id) const noexcept { return std::hash<std::uint64_t>{}(id.value()); }
};
