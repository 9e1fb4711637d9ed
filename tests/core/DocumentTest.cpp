#include <gtest/gtest.h>

#include <memory>
#include <vector>

#include "reamsim/core/AlertNode.h"
#include "reamsim/core/BoneNode.h"
#include "reamsim/core/Document.h"
#include "reamsim/core/LogNode.h"
#include "reamsim/core/PlanNode.h"
#include "reamsim/core/ReamerNode.h"

using namespace reamsim;
using Type = DocumentEvent::Type;

namespace {
struct Recorder {
  std::vector<DocumentEvent> events;
  Subscription sub;
  explicit Recorder(Document& doc) : sub(doc.subscribe([this](const DocumentEvent& e) { events.push_back(e); })) {}
};
DocumentEvent added(NodeId id) { return {Type::NodeAdded, id}; }
DocumentEvent removed(NodeId id) { return {Type::NodeRemoved, id}; }
DocumentEvent modified(NodeId id) { return {Type::NodeModified, id}; }
}  // namespace

TEST(Document, IdsAreStableUniqueAndNeverGivenToAnotherNode) {
  Document doc;
  BoneNode& bone = doc.create<BoneNode>();
  ReamerNode& r1 = doc.create<ReamerNode>("44 mm");
  const NodeId r1Id = r1.id();
  ReamerNode& r2 = doc.create<ReamerNode>();
  EXPECT_EQ(bone.id().toString(), "Bone1");
  EXPECT_EQ(r1Id.toString(), "Reamer1");
  EXPECT_EQ(r2.id().toString(), "Reamer2");
  EXPECT_EQ(bone.name(), "Bone1");  // empty name defaults to the id
  EXPECT_EQ(r1.name(), "44 mm");

  std::unique_ptr<Node> detached = doc.remove(r1Id);
  ASSERT_TRUE(detached);
  EXPECT_EQ(detached->document(), nullptr);
  EXPECT_EQ(doc.find(r1Id), nullptr);
  EXPECT_EQ(doc.create<ReamerNode>().id().toString(), "Reamer3");
  // A node from elsewhere never gets an id this document issued, even one whose node is gone...
  Document other;
  std::unique_ptr<Node> foreign = other.remove(other.create<ReamerNode>().id());  // "Reamer1" over there
  EXPECT_EQ(foreign->id().toString(), "Reamer1");
  EXPECT_EQ(doc.add(std::move(foreign)).id().toString(), "Reamer4");
  // ...while the removed node itself comes back under its own id (an undone removal).
  Node& back = doc.add(std::move(detached));
  EXPECT_EQ(back.id(), r1Id);
  EXPECT_EQ(doc.find(r1Id), &back);
  detached = doc.remove(r1Id);
  EXPECT_EQ(doc.add(std::move(detached)).id(), r1Id);  // again
  EXPECT_EQ(doc.find(bone.id()), &bone);  // others unaffected
  EXPECT_EQ(doc.findAs<BoneNode>(bone.id()), &bone);
  EXPECT_EQ(doc.findAs<ReamerNode>(bone.id()), nullptr);
  EXPECT_EQ(doc.size(), 5u);
  EXPECT_EQ(doc.nodesOf<ReamerNode>().size(), 4u);
  EXPECT_EQ(doc.firstOf<BoneNode>(), &bone);
  ASSERT_TRUE(doc.remove(r1Id));
  EXPECT_EQ(doc.remove(r1Id), nullptr);  // already gone
}

TEST(Document, AddRejectsNull) {
  Document doc;
  EXPECT_THROW(doc.add(std::unique_ptr<Node>()), std::invalid_argument);
  EXPECT_EQ(doc.size(), 0u);
}

TEST(Document, NotificationsInOrder) {
  Document doc;
  Recorder rec(doc);
  ReamerNode& r = doc.create<ReamerNode>();
  PlanNode& p = doc.create<PlanNode>();
  r.setPose(Pose{{0, 0, 1}, {0, 0, 1}, 0});
  p.addPose(Pose{});
  r.setPose(Pose{});
  const NodeId rid = r.id(), pid = p.id();
  doc.remove(pid);
  EXPECT_EQ(rec.events, (std::vector<DocumentEvent>{added(rid), added(pid), modified(rid), modified(pid), modified(rid),
                                                    removed(pid)}));
  EXPECT_EQ(r.modifiedCount(), 2u);
}

TEST(Document, BatchCoalescesModificationsAndKeepsAddRemoveOrder) {
  Document doc;
  ReamerNode& r = doc.create<ReamerNode>();
  LogNode& log = doc.create<LogNode>();
  PlanNode& plan = doc.create<PlanNode>();
  const NodeId planId = plan.id();
  Recorder rec(doc);
  NodeId boneId, alertId;
  {
    Document::BatchScope batch(doc);
    for (int i = 0; i < 10; ++i) r.setPose(advancedAlongAxis(r.pose(), 0.1));
    log.append({});
    r.setName("moved");
    boneId = doc.create<BoneNode>().id();
    doc.findAs<BoneNode>(boneId)->setImportReport("ok");  // folded into the add
    plan.setReamerSpecName("x");                            // dropped: plan removed below
    doc.remove(planId);
    AlertNode& alert = doc.create<AlertNode>();            // added and removed: not reported
    alertId = alert.id();
    alert.setAlerts({Alert{AlertKind::Contact, r.id(), boneId, 0}});
    doc.remove(alertId);
    EXPECT_TRUE(rec.events.empty());
  }
  EXPECT_EQ(rec.events,
            (std::vector<DocumentEvent>{modified(r.id()), modified(log.id()), added(boneId), removed(planId)}));
  EXPECT_EQ(r.modifiedCount(), 11u);  // the counter still sees every change
  EXPECT_FALSE(doc.inBatch());
}

TEST(Document, NestedBatchesDeliverAtOutermostEnd) {
  Document doc;
  ReamerNode& r = doc.create<ReamerNode>();
  Recorder rec(doc);
  {
    Document::BatchScope outer(doc);
    r.setPose(Pose{});
    {
      Document::BatchScope inner(doc);
      r.setPose(Pose{});
      doc.create<LogNode>();
    }
    EXPECT_TRUE(rec.events.empty());
    EXPECT_TRUE(doc.inBatch());
    r.setPose(Pose{});
  }
  ASSERT_EQ(rec.events.size(), 2u);
  EXPECT_EQ(rec.events[0], modified(r.id()));
  EXPECT_EQ(rec.events[1].type, Type::NodeAdded);
}

TEST(Document, UnsubscribeDuringCallback) {
  Document doc;
  std::vector<int> calls;
  Subscription second;
  Subscription first = doc.subscribe([&](const DocumentEvent&) {
    calls.push_back(1);
    second.reset();  // the second observer must not be called, not even for this event
  });
  second = doc.subscribe([&](const DocumentEvent&) { calls.push_back(2); });
  Subscription self;
  self = doc.subscribe([&](const DocumentEvent&) {
    calls.push_back(3);
    self.reset();  // unsubscribing oneself is safe; the std::function stays alive until it returns
  });
  doc.create<LogNode>();
  doc.create<LogNode>();
  EXPECT_EQ(calls, (std::vector<int>{1, 3, 1}));
  EXPECT_FALSE(second.connected());
  EXPECT_TRUE(first.connected());
}

TEST(Document, SubscriptionIsRaiiAndMayOutliveTheDocument) {
  std::vector<DocumentEvent> events;
  Subscription outlives;
  {
    Document doc;
    {
      Subscription s = doc.subscribe([&](const DocumentEvent& e) { events.push_back(e); });
      doc.create<LogNode>();
    }
    doc.create<LogNode>();  // s is gone
    EXPECT_EQ(events.size(), 1u);
    outlives = doc.subscribe([](const DocumentEvent&) {});
  }
  outlives.reset();  // document destroyed first: harmless
  EXPECT_FALSE(outlives.connected());
}

TEST(Document, ModificationsFromCallbacksAreQueuedNotReentrant) {
  Document doc;
  ReamerNode& r = doc.create<ReamerNode>();
  std::vector<std::pair<int, DocumentEvent>> seen;
  int depth = 0;
  Subscription a = doc.subscribe([&](const DocumentEvent& e) {
    ++depth;
    EXPECT_EQ(depth, 1) << "delivery must not nest";
    seen.push_back({1, e});
    if (e.type == Type::NodeAdded) r.setName("seen " + e.id.toString());  // change made by an observer
    --depth;
  });
  Subscription b = doc.subscribe([&](const DocumentEvent& e) { seen.push_back({2, e}); });
  const NodeId logId = doc.create<LogNode>().id();
  // Both observers see the add before anyone sees the modification it triggered.
  ASSERT_EQ(seen.size(), 4u);
  EXPECT_EQ(seen[0], std::make_pair(1, added(logId)));
  EXPECT_EQ(seen[1], std::make_pair(2, added(logId)));
  EXPECT_EQ(seen[2], std::make_pair(1, modified(r.id())));
  EXPECT_EQ(seen[3], std::make_pair(2, modified(r.id())));
}

TEST(Document, RemovalByAnObserverAndSubscriptionDuringCallback) {
  Document doc;
  std::vector<std::string> log;
  Subscription late;
  Subscription remover = doc.onNodeAdded([&](NodeId id) {
    log.push_back("added " + id.toString());
    if (id.kind() == NodeKind::Plan) doc.remove(id);
    if (!late.connected()) late = doc.subscribe([&](const DocumentEvent& e) { log.push_back("late " + e.id.toString()); });
  });
  Subscription watcher = doc.onNodeAdded([&](NodeId id) {
    // Delivered after the first observer removed it: state at delivery time.
    log.push_back(doc.contains(id) ? "present" : "absent");
  });
  doc.create<PlanNode>();
  EXPECT_EQ(log, (std::vector<std::string>{"added Plan1", "absent", "late Plan1"}));
}

TEST(Document, ObserveNodeAndFilteredSubscriptions) {
  Document doc;
  ReamerNode& a = doc.create<ReamerNode>();
  ReamerNode& b = doc.create<ReamerNode>();
  int aChanges = 0, removedCount = 0;
  Subscription s1 = doc.observeNode(a.id(), [&] { ++aChanges; });
  Subscription s2 = doc.onNodeRemoved([&](NodeId) { ++removedCount; });
  a.setPose(Pose{});
  b.setPose(Pose{});
  a.setSpec(ReamerSpec{});
  doc.remove(b.id());
  EXPECT_EQ(aChanges, 2);
  EXPECT_EQ(removedCount, 1);
}
