#include <gtest/gtest.h>

#include <sstream>
#include <unordered_set>

#include "reamsim/core/NodeId.h"

using namespace reamsim;

TEST(NodeId, PrintsKindAndSerial) {
  EXPECT_EQ(NodeId::make(NodeKind::Bone, 1).toString(), "Bone1");
  EXPECT_EQ(NodeId::make(NodeKind::Reamer, 2).toString(), "Reamer2");
  EXPECT_EQ(NodeId().toString(), "<invalid>");
  std::ostringstream os;
  os << NodeId::make(NodeKind::Plan, 7);
  EXPECT_EQ(os.str(), "Plan7");
}

TEST(NodeId, ParseRoundTripsAndRejectsNonCanonical) {
  for (NodeKind k : {NodeKind::Bone, NodeKind::Reamer, NodeKind::Plan, NodeKind::Log, NodeKind::Alert, NodeKind::Interaction}) {
    const NodeId id = NodeId::make(k, 42);
    EXPECT_EQ(NodeId::parse(id.toString()), id);
  }
  for (const char* bad : {"Bone", "Bone0", "Bone01", "bone1", "Knee3", "Bone1x", "", "Bone99999999999999999"})
    EXPECT_FALSE(NodeId::parse(bad).has_value()) << bad;
}

TEST(NodeId, KindIsPartOfIdentity) {
  const NodeId a = NodeId::make(NodeKind::Bone, 1), b = NodeId::make(NodeKind::Reamer, 1);
  EXPECT_NE(a, b);
  EXPECT_EQ(a.kind(), NodeKind::Bone);
  EXPECT_EQ(b.serial(), 1u);
  EXPECT_FALSE(NodeId().valid());
  std::unordered_set<NodeId> set{a, b, a};
  EXPECT_EQ(set.size(), 2u);
}
