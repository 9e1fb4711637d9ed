#include <gtest/gtest.h>

#include "TestMeshes.h"
#include "reamsim/core/AlertNode.h"
#include "reamsim/core/BoneNode.h"
#include "reamsim/core/Document.h"
#include "reamsim/core/InteractionNode.h"
#include "reamsim/core/LogNode.h"
#include "reamsim/core/PlanNode.h"
#include "reamsim/core/ReamerNode.h"

using namespace reamsim;

TEST(Nodes, ReamerSpecChangeDropsCachedCuttingVolume) {
  Document doc;
  ReamerNode& r = doc.create<ReamerNode>();
  r.setCuttingVolume(std::make_shared<TriangleMesh>(test::box(1, 1, 1)));
  ASSERT_TRUE(r.cuttingVolume());
  r.setPose(Pose{{1, 2, 3}, {0, 1, 0}, 0});
  EXPECT_TRUE(r.cuttingVolume());  // the volume is in reamer-local coordinates: pose does not matter
  ReamerSpec spec;
  spec.diameterMm = 50;
  r.setSpec(spec);
  EXPECT_FALSE(r.cuttingVolume());
  EXPECT_EQ(r.spec().diameterMm, 50);
  EXPECT_EQ(r.modifiedCount(), 3u);
}

TEST(Nodes, BoneNodeCommitsUndoesAndNotifies) {
  Document doc;
  BoneNode& bone = doc.create<BoneNode>("scapula", BoneState::fromMesh(test::box(2, 2, 2)));
  int changes = 0;
  Subscription s = doc.observeNode(bone.id(), [&] { ++changes; });
  EXPECT_NEAR(bone.current().volume(), 8, 1e-12);
  const std::uint64_t rev = bone.commit(BoneState::fromMesh(test::box(1, 1, 1)), "cut 1");
  EXPECT_EQ(bone.currentRevision(), rev);
  EXPECT_NEAR(bone.current().volume(), 1, 1e-12);
  EXPECT_TRUE(bone.undo());
  EXPECT_NEAR(bone.current().volume(), 8, 1e-12);
  EXPECT_FALSE(bone.undo());  // nothing to undo: no notification
  EXPECT_TRUE(bone.redo());
  bone.setImportReport("3 holes filled");
  bone.setOriginalMesh(std::make_shared<TriangleMesh>(test::box(2, 2, 2)));
  EXPECT_EQ(changes, 5);
  EXPECT_EQ(bone.importReport(), "3 holes filled");
}

TEST(Nodes, PlanAndLog) {
  Document doc;
  PlanNode& plan = doc.create<PlanNode>();
  plan.setReamerSpecName("44 mm spherical");
  plan.addPose(Pose{});
  plan.addPose(advancedAlongAxis(Pose{}, 1));
  plan.setFeedDescription("1 mm steps");
  EXPECT_EQ(plan.poses().size(), 2u);
  EXPECT_EQ(*plan.feedDescription(), "1 mm steps");

  LogNode& log = doc.create<LogNode>();
  EXPECT_EQ(log.cumulativeMm3(), 0);
  CutLogEntry e;
  e.stepIndex = 0;
  e.contact = true;
  e.removedMm3 = 12.5;
  e.cumulativeMm3 = 12.5;
  e.contactPoint = Vec3{1, 2, 3};
  e.boneStateId = 2;
  log.append(e);
  e.stepIndex = 1;
  e.cumulativeMm3 = 20;
  log.append(e);
  EXPECT_EQ(log.size(), 2u);
  EXPECT_EQ(log.last().stepIndex, 1u);
  EXPECT_EQ(log.cumulativeMm3(), 20);

  // A row's note is the one thing that changes after it is appended: a change is reported and counted, the
  // same note again is not.
  int modified = 0;
  const Subscription sub = doc.observeNode(log.id(), [&] { ++modified; });
  EXPECT_EQ(log.notesRevision(), 0u);
  log.setNote(0, "seated");
  EXPECT_EQ(log.entries()[0].note, "seated");
  EXPECT_EQ(log.entries()[1].note, "");
  EXPECT_EQ(log.notesRevision(), 1u);
  EXPECT_EQ(modified, 1);
  log.setNote(0, "seated");
  EXPECT_EQ(log.notesRevision(), 1u);
  EXPECT_EQ(modified, 1);
  log.setNote(0, "");
  EXPECT_EQ(log.notesRevision(), 2u);
  EXPECT_THROW(log.setNote(2, "no such row"), std::out_of_range);
  EXPECT_EQ(log.notesRevision(), 2u);
}

TEST(Nodes, AlertsReportOnlyRealChanges) {
  Document doc;
  AlertNode& alerts = doc.create<AlertNode>();
  const NodeId r = NodeId::make(NodeKind::Reamer, 1), b = NodeId::make(NodeKind::Bone, 1);
  const std::vector<Alert> overlap{{AlertKind::BoundsOverlap, r, b, 1.25}};
  alerts.setAlerts(overlap);
  alerts.setAlerts(overlap);  // unchanged: no modification
  EXPECT_EQ(alerts.modifiedCount(), 1u);
  EXPECT_TRUE(alerts.has(AlertKind::BoundsOverlap));
  EXPECT_FALSE(alerts.has(AlertKind::Contact));
  EXPECT_EQ(describe(overlap[0]), "Reamer1 / Bone1: bounding boxes overlap (distance 1.25 mm)");
  EXPECT_EQ(describe(Alert{AlertKind::Contact, r, b, 0}), "Reamer1 / Bone1: contact");
  alerts.clear();
  EXPECT_TRUE(alerts.alerts().empty());
  EXPECT_EQ(alerts.modifiedCount(), 2u);
}

// A placement asked for from outside the loop waits in the node until the loop takes it.
TEST(Nodes, ReamerPlacementRequestWaitsUntilTaken) {
  Document doc;
  ReamerNode& r = doc.create<ReamerNode>();
  int reports = 0;
  Subscription s = doc.observeNode(r.id(), [&] { ++reports; });
  EXPECT_FALSE(r.placementRequest());
  r.requestPlacement(Pose{{1, 2, 3}, {0, 0, -1}, 0});
  EXPECT_EQ(reports, 1);
  EXPECT_EQ(r.pose().tip.x, 0);  // asked for, not moved
  const auto taken = r.takePlacementRequest();
  ASSERT_TRUE(taken);
  EXPECT_EQ(taken->pose.tip.y, 2);
  EXPECT_FALSE(taken->clearOfBone);
  EXPECT_FALSE(r.placementRequest());
  EXPECT_FALSE(r.takePlacementRequest());
  EXPECT_EQ(reports, 1);  // taking it reports nothing
  r.requestPlacement(Pose{{1, 2, 3}, {0, 0, -1}, 0}, true);  // Aim's: clear of the bone
  EXPECT_TRUE(r.takePlacementRequest()->clearOfBone);
}

TEST(Nodes, ABoneKeepsItsLandmarksAndTheyGoWithItsContent) {
  Document doc;
  BoneNode& bone = doc.create<BoneNode>("scapula", BoneState::fromMesh(test::box(2, 2, 2)));
  int reports = 0;
  Subscription s = doc.observeNode(bone.id(), [&] { ++reports; });
  EXPECT_FALSE(bone.landmarks().complete());
  bone.setLandmark(ScapulaLandmark::InferiorAngle, Vec3{1, 2, 3});
  bone.setLandmark(ScapulaLandmark::GlenoidCentre, Vec3{4, 5, 6});
  bone.setLandmark(ScapulaLandmark::TrigonumScapulae, Vec3{7, 8, 9});
  EXPECT_FALSE(bone.landmarks().complete());  // no side yet
  bone.setLandmarkSide(BodySide::Left);
  EXPECT_TRUE(bone.landmarks().complete());
  EXPECT_EQ(reports, 4);
  bone.setLandmarkSide(BodySide::Left);  // no change, no report
  EXPECT_EQ(reports, 4);
  const ScapulaLandmarks placed = bone.landmarks();
  ScapulaLandmarks moved = placed;
  moved[ScapulaLandmark::GlenoidCentre]->z = 6.5;
  EXPECT_FALSE(moved == placed);
  // An exchange of content (an undoable bone replacement) takes the points with the bone they were placed on.
  BoneContent other;
  other.history = BoneHistory(BoneState::fromMesh(test::box(1, 1, 1)));
  other.landmarks = moved;
  bone.swapContent(other);
  EXPECT_EQ(bone.landmarks(), moved);
  EXPECT_EQ(other.landmarks, placed);
  bone.swapContent(other);
  EXPECT_EQ(bone.landmarks(), placed);
  // The planned axis goes with it too.
  const int beforePlan = reports;
  bone.setPlannedAxis(Pose{{1, 2, 3}, {0, 0, -1}, 0});
  EXPECT_EQ(reports, beforePlan + 1);
  bone.setPlannedAxis(Pose{{1, 2, 3}, {0, 0, -1}, 0});
  EXPECT_EQ(reports, beforePlan + 1);  // the same: no report
  bone.swapContent(other);
  EXPECT_FALSE(bone.plannedAxis());
  ASSERT_TRUE(other.plannedAxis);
  bone.swapContent(other);
  ASSERT_TRUE(bone.plannedAxis());
  EXPECT_EQ(bone.plannedAxis()->tip.z, 3);
  EXPECT_EQ(parseBodySide("RIGHT"), BodySide::Right);
  EXPECT_FALSE(parseBodySide("middle"));
  EXPECT_STREQ(jsonKey(ScapulaLandmark::TrigonumScapulae), "trigonum_scapulae");
}

TEST(Nodes, InteractionHoldsTheLandmarkTheNextClickPlaces) {
  Document doc;
  InteractionNode& i = doc.create<InteractionNode>();
  EXPECT_EQ(i.id().toString(), "Interaction1");
  EXPECT_FALSE(i.placeRequest());
  i.setPlaceRequest(ScapulaLandmark::InferiorAngle);
  EXPECT_EQ(i.placeRequest(), ScapulaLandmark::InferiorAngle);
  i.setPlaceRequest(std::nullopt);
  EXPECT_FALSE(i.placeRequest());
  EXPECT_EQ(i.modifiedCount(), 2u);
}
