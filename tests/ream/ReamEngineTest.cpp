// The two halves of the reaming loop used by the GUI: the engine computes on a worker thread, the
// document commits on the main thread. Same results as the synchronous controller; a computation made
// against a bone that changed meanwhile (undo) is refused and the engine resyncs.
#include <gtest/gtest.h>

#include <future>
#include <optional>
#include <stdexcept>

#include "ReamFixture.h"
#include "reamsim/ream/CutLogIO.h"
#include "reamsim/ream/Approach.h"
#include "reamsim/ream/ReamStep.h"
#include "reamsim/ream/DefaultCase.h"
#include "reamsim/ream/LocalCutBackend.h"
#include "reamsim/ream/Plan.h"
#include "reamsim/tools/ReamerGeometry.h"
#include "reamsim/tools/ReamerPresets.h"
#include "reamsim/tools/Primitives.h"

namespace reamsim {
namespace {

TriangleMesh block() { return test::blockBelowZ0(); }

Pose at(double z) { return Pose{{0, 0, z}, {0, 0, -1}, 0}; }

// The controller's engines (ReamScene): BVH collision, CGAL reference cutting.
ReamEngine referenceEngine(const ReamerNode& reamer) {
  return ReamEngine(reamer.cuttingVolume(), makeBvhContactBackend(), referenceCutBackendFactory());
}

TEST(ReamEngine, WorkerThreadStepsMatchTheController) {
  test::ReamScene sync(block(), test::flatReamer20());
  test::ReamScene split(block(), test::flatReamer20());
  ReamEngine engine = referenceEngine(*split.reamer);
  const double zs[] = {1.0, 0.2, -0.3, -0.8, -1.3};
  for (std::size_t i = 0; i < std::size(zs); ++i) {
    const ReamStepOutcome expected = sync.controller->moveTo(at(zs[i]));
    const BoneState bone = split.bone->current();  // immutable value: safe to hand to the worker
    const std::uint64_t revision = split.bone->currentRevision();
    const double stepMm = i == 0 ? 0.0 : std::abs(zs[i] - zs[i - 1]);
    ReamComputation c =
        std::async(std::launch::async, [&] { return engine.compute(bone, revision, at(zs[i]), stepMm); }).get();
    const CutLogEntry e = commitReamStep(split.doc, *split.bone, *split.reamer, *split.log, split.alerts, c, i);
    if (e.boneStateId) engine.adopt(e.boneStateId);
    EXPECT_EQ(e.contact, expected.entry.contact) << "step " << i;
    EXPECT_EQ(e.boxesOverlap, expected.entry.boxesOverlap) << "step " << i;
    EXPECT_NEAR(e.removedMm3, expected.entry.removedMm3, 1e-9 * std::max(1.0, e.removedMm3)) << "step " << i;
    EXPECT_EQ(e.faces, expected.entry.faces) << "step " << i;
    EXPECT_EQ(split.alerts->alerts().size(), sync.alerts->alerts().size());
  }
  EXPECT_GT(split.log->cumulativeMm3(), 100.0);  // 1.3 mm of a 20 mm flat reamer: ~400 mm3
  EXPECT_NEAR(split.bone->current().volume(), sync.bone->current().volume(), 1e-6);
  EXPECT_FALSE(engine.checkBone().selfIntersectsExact);
}

// The log names the reamer each step was computed with: a step still running when the user picks another
// reamer is committed as made, by the first one.
TEST(ReamEngine, LogNamesTheReamerTheStepWasComputedWith) {
  test::ReamScene s(block(), test::flatReamer20());
  ReamEngine engine(s.reamer->cuttingVolume(), makeBvhContactBackend(), referenceCutBackendFactory(), s.reamer->spec());
  ReamComputation c = engine.compute(s.bone->current(), s.bone->currentRevision(), at(-0.5), 0);
  ReamerSpec other;
  other.name = "glenoid-40-R35";
  other.diameterMm = 40;
  other.sphereRadiusMm = 35;
  s.reamer->setSpec(other);  // changed while the step ran
  const CutLogEntry e = commitReamStep(s.doc, *s.bone, *s.reamer, *s.log, s.alerts, c, 0);
  ASSERT_TRUE(e.contact);
  EXPECT_EQ(e.reamer, "flat-20");
  EXPECT_EQ(e.reamerDiameterMm, 20);
  EXPECT_FALSE(e.reamerSphereRadiusMm);  // flat
  const std::string csv = cutLogCsv(s.log->entries());
  EXPECT_NE(csv.find(",reamer,reamer_diameter_mm,reamer_sphere_radius_mm,undone,note\n"), std::string::npos) << csv;
  EXPECT_NE(csv.find(",flat-20,20,,0,\n"), std::string::npos) << csv;
  // An engine that does not know its reamer's spec logs the node's: the curved one, with its radius.
  s.reamer->setCuttingVolume(std::make_shared<const TriangleMesh>(buildCuttingSolid(other)));
  ReamEngine anonymous = referenceEngine(*s.reamer);
  anonymous.adopt(e.boneStateId);
  ReamComputation d = anonymous.compute(s.bone->current(), s.bone->currentRevision(), at(-1.0), 0.5);
  const CutLogEntry f = commitReamStep(s.doc, *s.bone, *s.reamer, *s.log, s.alerts, d, 1);
  EXPECT_EQ(f.reamer, "glenoid-40-R35");
  ASSERT_TRUE(f.reamerSphereRadiusMm);
  EXPECT_EQ(*f.reamerSphereRadiusMm, 35);
  EXPECT_NE(cutLogJson(s.log->entries()).find("\"name\": \"glenoid-40-R35\""), std::string::npos);
}

TEST(ReamEngine, StaleComputationIsRefusedAndEngineResyncs) {
  test::ReamScene s(block(), test::flatReamer20());
  ReamEngine engine = referenceEngine(*s.reamer);
  ReamComputation first = engine.compute(s.bone->current(), s.bone->currentRevision(), at(-0.5), 0);
  const CutLogEntry cut = commitReamStep(s.doc, *s.bone, *s.reamer, *s.log, s.alerts, first, 0);
  ASSERT_TRUE(cut.contact);
  engine.adopt(cut.boneStateId);
  const double afterFirst = s.bone->current().volume();

  ReamComputation second = engine.compute(s.bone->current(), s.bone->currentRevision(), at(-1.0), 0.5);
  ASSERT_TRUE(second.cut.changed);
  ASSERT_TRUE(s.bone->undo());  // the user undid while the second step was computed
  EXPECT_THROW(commitReamStep(s.doc, *s.bone, *s.reamer, *s.log, s.alerts, second, 1), std::logic_error);
  EXPECT_EQ(s.log->size(), 1u);

  // Without adopt the engine must rebuild from the undone state: a cut to -1.0 removes ~2x the first.
  ReamComputation again = engine.compute(s.bone->current(), s.bone->currentRevision(), at(-1.0), 0.5);
  ASSERT_TRUE(again.cut.changed);
  EXPECT_NEAR(again.cut.removedMm3, 2 * cut.removedMm3, 0.01 * cut.removedMm3);
  EXPECT_GT(s.bone->current().volume(), afterFirst);
}

TEST(ReamEngine, CollisionOnlyEngineNeverCutsAndCutLogSkipsNonCuts) {
  test::ReamScene s(block(), test::flatReamer20());
  ReamEngine engine(s.reamer->cuttingVolume(), makeThesisContactBackend(), CutBackendFactory{});
  EXPECT_FALSE(engine.canCut());
  const double volume = s.bone->current().volume();
  ReamComputation c = engine.compute(s.bone->current(), s.bone->currentRevision(), at(-0.5), 0);
  EXPECT_TRUE(c.contactChecked);
  EXPECT_TRUE(c.contact.penetrating);
  EXPECT_FALSE(c.cut.changed);
  const CutLogEntry e = commitReamStep(s.doc, *s.bone, *s.reamer, *s.log, s.alerts, c, 0, CommitOptions{false, std::nullopt, {}});
  EXPECT_FALSE(e.contact);
  EXPECT_EQ(s.log->size(), 0u);  // the GUI's log lists cuts only
  EXPECT_TRUE(s.alerts->has(AlertKind::BoundsOverlap));
  EXPECT_EQ(s.bone->current().volume(), volume);
  EXPECT_EQ(s.reamer->pose().tip, at(-0.5).tip);
}

TEST(ReamEngine, CumulativeFromInitialVolumeIgnoresUndoneCuts) {
  test::ReamScene s(block(), test::flatReamer20());
  ReamEngine engine = referenceEngine(*s.reamer);
  CommitOptions options{false, s.bone->current().volume(), {}};
  auto step = [&](double z, std::size_t i) {
    ReamComputation c = engine.compute(s.bone->current(), s.bone->currentRevision(), at(z), 0.5);
    const CutLogEntry e = commitReamStep(s.doc, *s.bone, *s.reamer, *s.log, s.alerts, c, i, options);
    if (e.boneStateId) engine.adopt(e.boneStateId);
    return e;
  };
  const CutLogEntry first = step(-0.5, 0);
  ASSERT_TRUE(s.bone->undo());
  const CutLogEntry again = step(-0.5, 1);  // the same cut again: cumulative is one cut, not two
  EXPECT_NEAR(again.cumulativeMm3, first.removedMm3, 1e-6 * first.removedMm3);
  EXPECT_EQ(s.log->size(), 2u);
}

// "Ream to depth"'s search on the engine's own collision structure, which follows the bone from revision to
// revision, gives what a tree built afresh for the bone gives: before and after another engine's cuts (the
// searching reamer, 10 mm across, fits in their 20 mm hole and meets its floor), from the side, pointing
// away, after an undo; the thesis's rays (no exact motion query) get the same answers through a tree built
// for the call.
TEST(ReamEngine, ContactSearchAlongTheAxisFollowsTheBone) {
  test::ReamScene s(block(), test::flatReamer20());
  ReamEngine cutter = referenceEngine(*s.reamer);
  ReamerSpec narrow = test::flatReamer20();
  narrow.diameterMm = 10;
  const auto narrowSolid = std::make_shared<const TriangleMesh>(buildCuttingSolid(narrow));
  ReamEngine bvh(narrowSolid, makeBvhContactBackend(), CutBackendFactory{}, narrow);
  ReamEngine rays(narrowSolid, makeThesisContactBackend(), CutBackendFactory{}, narrow);
  auto search = [&](const Pose& from, const char* what) -> std::optional<double> {
    const auto expected = advanceToContactMm(s.bone->current(), *narrowSolid, from, 50, &narrow);
    for (ReamEngine* e : {&bvh, &rays}) {
      const auto got = e->advanceToContactMm(s.bone->current(), s.bone->currentRevision(), from, 50);
      EXPECT_EQ(got.has_value(), expected.has_value()) << what;
      if (got && expected) {
        EXPECT_NEAR(*got, *expected, 1e-9) << what;
      }
    }
    return expected;
  };
  const Pose tilted{{7.5, -3, 4}, normalized(Vec3{0.3, -0.2, -1}), 0};
  EXPECT_NEAR(search(at(3.0), "before any cut").value_or(-1), 3.0, 1e-9);
  EXPECT_FALSE(search(Pose{{0, 0, 15}, {0, 0, 1}, 0}, "pointing away").has_value());
  const double tiltedBefore = search(tilted, "tilted, before the cuts").value_or(-1);
  std::size_t i = 0;
  for (double z : {-0.5, -1.2}) {
    ReamComputation c = cutter.compute(s.bone->current(), s.bone->currentRevision(), at(z), 0.5);
    const CutLogEntry e = commitReamStep(s.doc, *s.bone, *s.reamer, *s.log, s.alerts, c, i++);
    ASSERT_TRUE(e.boneStateId);
    cutter.adopt(e.boneStateId);
  }
  EXPECT_NEAR(search(at(3.0), "into the hole").value_or(-1), 4.2, 1e-6);  // its floor is at -1.2
  EXPECT_EQ(search(at(-1.2), "on the floor").value_or(-1), 0.0);
  EXPECT_GT(search(tilted, "tilted, into the hole's side").value_or(-1), tiltedBefore);
  ASSERT_TRUE(s.bone->undo());
  EXPECT_NEAR(search(at(3.0), "after an undo").value_or(-1), 3.5, 1e-6);
}

// Another reamer on the same engine (sequential reaming with growing sizes, ReamEngine::setReamer): the next cut is
// the new reamer's, as a fresh engine computes it on the same bone; the engine's tree and cutter are kept.
TEST(ReamEngine, AnotherReamerOnTheSameEngineCutsAsAFreshEngine) {
  const ReamerSpec small = loadPreset("glenoid-36-R30", reamerPresetsPath());
  const ReamerSpec large = loadPreset("glenoid-40-R32", reamerPresetsPath());
  auto smallVolume = std::make_shared<const TriangleMesh>(buildCuttingSolid(small));
  auto largeVolume = std::make_shared<const TriangleMesh>(buildCuttingSolid(large));
  const Pose start = loadPlan(defaultPlanPath()).feed->start;
  const BoneState bone = BoneState::fromMesh(loadDefaultBone().mesh);
  ReamEngine engine(smallVolume, makeBvhContactBackend(), localCutBackendFactory(), small);
  const double approach = *engine.advanceToContactMm(bone, 1, start, 100);
  const Pose first = advancedAlongAxis(start, approach + 0.5);
  const ReamComputation c1 = engine.compute(bone, 1, first, 0);
  ASSERT_TRUE(c1.cut.changed && c1.next);
  const BoneState seated = *c1.next;
  engine.adopt(2);

  engine.setReamer(largeVolume, large);
  const Pose second = advancedAlongAxis(start, approach + 0.8);
  const ReamComputation c2 = engine.compute(seated, 2, second, 0.3, &first);
  ReamEngine fresh(largeVolume, makeBvhContactBackend(), localCutBackendFactory(), large);
  const ReamComputation f2 = fresh.compute(seated, 2, second, 0.3, &first);
  ASSERT_TRUE(c2.cut.changed && f2.cut.changed);
  EXPECT_NEAR(c2.cut.removedMm3, f2.cut.removedMm3, 1e-6 * f2.cut.removedMm3);
  EXPECT_EQ(c2.next->liveTriangleCount(), f2.next->liveTriangleCount());
  ASSERT_TRUE(c2.reamer);
  EXPECT_EQ(c2.reamer->name, "glenoid-40-R32");
  // The larger reamer's cut, not the smaller one's (which would take less of the rim).
  ReamEngine smallFresh(smallVolume, makeBvhContactBackend(), localCutBackendFactory(), small);
  const ReamComputation s2 = smallFresh.compute(seated, 2, second, 0.3, &first);
  EXPECT_GT(c2.cut.removedMm3, s2.cut.removedMm3 * 1.05);
  EXPECT_THROW(engine.setReamer(nullptr, large), std::invalid_argument);
}

}  // namespace
}  // namespace reamsim
