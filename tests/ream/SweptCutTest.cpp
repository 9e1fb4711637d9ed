// Swept cutting: a sideways translation cuts the whole volume the reamer sweeps (the hull of its two
// placements), so a long move leaves no ridge; a turn is cut in sub-steps along it; a short axial feed cuts
// the end pose's solid (it covers the feed).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <map>
#include <memory>
#include <optional>
#include <utility>
#include <vector>
#include <cmath>
#include <cstdio>
#include <string>

#include "ReamFixture.h"
#include "reamsim/ream/CutLogIO.h"
#include "reamsim/ream/LocalCutBackend.h"
#include "reamsim/csg/SweptVolume.h"
#include "reamsim/mesh/TriangleMesh.h"
#include "reamsim/mesh/Validation.h"
#include "reamsim/tools/Primitives.h"
#include "reamsim/ream/DefaultCase.h"
#include "reamsim/tools/ReamerGeometry.h"
#include "reamsim/tools/ReamerPresets.h"
#include <random>

namespace reamsim {
namespace {

TriangleMesh block() { return test::blockBelowZ0(60); }
Pose at(double x, double z) { return Pose{{x, 0, z}, {0, 0, -1}, 0}; }

// Width of the reamer's cross-section across the direction of travel (x): what a sideways sweep removes per
// mm of travel and mm of depth.
double widthAcrossX(const TriangleMesh& solid) {
  double lo = 1e300, hi = -1e300;
  for (const Vec3& p : solid.vertices) {
    lo = std::min(lo, p.y);
    hi = std::max(hi, p.y);
  }
  return hi - lo;
}

class SweptCutEngines : public ::testing::TestWithParam<bool> {};  // local engine, or the CGAL reference

TEST_P(SweptCutEngines, SidewaysMoveRemovesTheSweptSlot) {
  test::ReamScene s(block(), test::flatReamer20(), GetParam() ? localCutBackendFactory() : referenceCutBackendFactory());
  const TriangleMesh solid = *s.reamer->cuttingVolume();
  ASSERT_TRUE(isConvexSolid(solid));
  s.controller->moveTo(at(-15, 1.0));                      // above the top
  const ReamStepOutcome down = s.controller->moveTo(at(-15, -1.0));  // 1 mm in: a disc
  EXPECT_FALSE(down.swept);                                 // axial: the end solid covers it
  const double disc = down.cut.removedMm3;
  EXPECT_GT(disc, 300.0);
  const ReamStepOutcome across = s.controller->moveTo(at(15, -1.0));  // 30 mm sideways in one step
  EXPECT_TRUE(across.swept);
  // The slot between the two discs: travel x width x depth (the end disc overlaps nothing cut before... it
  // does not: 30 mm > the 20 mm diameter, so the slot and the second disc are all new).
  // The local engine's clean-up may move the surface by a quarter of the reamer's facet sag (3 um at its
  // wall): 1.2e-3 mm3 (2e-6) measured; the reference is the exact Boolean.
  EXPECT_NEAR(across.cut.removedMm3, 30.0 * widthAcrossX(solid) * 1.0, (GetParam() ? 1e-5 : 1e-6) * across.cut.removedMm3);
  EXPECT_NEAR(s.log->cumulativeMm3(), disc + across.cut.removedMm3, 1e-6);
  EXPECT_FALSE(s.controller->checkBone().selfIntersectsExact);
}

INSTANTIATE_TEST_SUITE_P(SweptCut, SweptCutEngines, ::testing::Values(true, false),
                         [](const auto& info) { return info.param ? "local" : "reference"; });

TEST(SweptCut, AMovePastTheBoneBuildsNoHullAndCutsNothing) {
  // The flat reamer's face 0.5 mm above the block's top, moved 30 mm sideways: boxes overlap all along, the
  // surfaces never meet. The first-contact query says so exactly, and the step builds no hull.
  test::ReamScene s(block(), test::flatReamer20(), localCutBackendFactory());
  const Pose start = at(-15, 0.5);
  for (bool skip : {true, false}) {
    ReamEngine engine(s.reamer->cuttingVolume(), makeBvhContactBackend(), localCutBackendFactory());
    engine.setSkipMissedSweeps(skip);
    const ReamComputation c = engine.compute(s.bone->current(), s.bone->currentRevision(), at(15, 0.5), 30.0, &start);
    ASSERT_TRUE(c.contact.alongMove.has_value());
    EXPECT_FALSE(c.contact.alongMove->reached);
    EXPECT_TRUE(c.contact.boxesOverlap);
    EXPECT_TRUE(c.sweptPastBone);
    EXPECT_EQ(c.swept, !skip) << "skip " << skip;  // without the skip the hull is built, and misses
    EXPECT_FALSE(c.cut.changed);
  }
  // 0.5 mm lower the face lies on the top all along: the move touches the bone from its start (t = 0),
  // so the hull is built (it removes nothing: the Boolean's coplanar case).
  const Pose onTop = at(-15, 0.0);
  ReamEngine engine(s.reamer->cuttingVolume(), makeBvhContactBackend(), localCutBackendFactory());
  const ReamComputation c = engine.compute(s.bone->current(), s.bone->currentRevision(), at(15, 0.0), 30.0, &onTop);
  ASSERT_TRUE(c.contact.alongMove.has_value());
  EXPECT_TRUE(c.contact.alongMove->reached);
  EXPECT_EQ(c.contact.alongMove->t, 0.0);
  EXPECT_FALSE(c.sweptPastBone);
  EXPECT_TRUE(c.swept);
}

TEST(SweptCut, AMoveOfLengthZeroIsAskedLikeAnyOther) {
  // A step to the pose the reamer is at (a plan's repeated pose, a key released at once): the query's
  // motion has no translation and no turn; clear of the bone it is not reached, lying on it it is at t = 0.
  test::ReamScene s(block(), test::flatReamer20(), localCutBackendFactory());
  for (double z : {0.5, 0.0}) {
    const Pose here = at(3, z);
    ReamEngine engine(s.reamer->cuttingVolume(), makeBvhContactBackend(), localCutBackendFactory());
    const ReamComputation c = engine.compute(s.bone->current(), s.bone->currentRevision(), here, 0.0, &here);
    ASSERT_TRUE(c.contact.alongMove.has_value());
    EXPECT_EQ(c.contact.alongMove->reached, z == 0.0) << z;
    if (z == 0.0) {
      EXPECT_EQ(c.contact.alongMove->t, 0.0);
    }
    EXPECT_FALSE(c.swept);
    EXPECT_FALSE(c.cut.changed);
  }
}

TEST(SweptCut, AFastMoveThroughAThinPlateCutsItAndLogsWhereItFirstMetIt) {
  // A plate 1 mm thick standing across x; the reamer 1 mm deep starts and ends clear of it (20 mm across,
  // tips at x = -15 and +15), so neither pose touches it: only the move does, first at t = 4.5 / 30 (its
  // rim at x = -5 reaching the plate's face at x = -0.5).
  const TriangleMesh plate = buildBox(Bounds{{-0.5, -20, -20}, {0.5, 20, 0}}, 2);
  test::ReamScene s(plate, test::flatReamer20(), localCutBackendFactory());
  s.controller->moveTo(at(-15, 1.0));
  s.controller->moveTo(at(-15, -1.0));
  const ReamStepOutcome across = s.controller->moveTo(at(15, -1.0));
  ASSERT_TRUE(across.contact.alongMove.has_value());
  ASSERT_TRUE(across.contact.alongMove->reached);
  EXPECT_NEAR(across.contact.alongMove->t, 4.5 / 30.0, 1e-3);  // the polygonal rim reaches a little later
  EXPECT_NEAR(across.contact.alongMove->point.x, -0.5, 1e-9);
  EXPECT_FALSE(*across.contact.solidOverlapsBone);  // the end pose alone would cut nothing
  EXPECT_TRUE(across.swept);
  // The slot through the plate: its thickness x the reamer's width x the depth.
  EXPECT_NEAR(across.cut.removedMm3, 1.0 * widthAcrossX(*s.reamer->cuttingVolume()) * 1.0, 1e-5 * across.cut.removedMm3);
  ASSERT_GE(s.log->size(), 1u);
  const CutLogEntry& e = s.log->entries().back();
  ASSERT_TRUE(e.moveContactT.has_value());
  EXPECT_EQ(*e.moveContactT, across.contact.alongMove->t);
  ASSERT_TRUE(e.moveContactPoint.has_value());
  EXPECT_NEAR(e.moveContactPoint->x, -0.5, 1e-9);
  const std::string csv = cutLogCsv(s.log->entries());
  EXPECT_NE(csv.find(",move_contact_t,move_contact_x,move_contact_y,move_contact_z,"), std::string::npos) << csv;
  char t[32];
  std::snprintf(t, sizeof t, ",%.9g,-0.500000,", *e.moveContactT);
  EXPECT_NE(csv.find(t), std::string::npos) << csv;
  EXPECT_NE(cutLogJson(s.log->entries()).find("\"move_contact_t\""), std::string::npos);
  EXPECT_FALSE(s.controller->checkBone().selfIntersectsExact);
}

TEST(SweptCut, WithoutMotionThePlacedSolidIsCut) {
  // The same end pose reached by placing the reamer: only the end disc goes, the ridge between stays.
  test::ReamScene s(block(), test::flatReamer20());
  s.controller->moveTo(at(-15, -1.0));
  ReamEngine engine(s.reamer->cuttingVolume(), makeBvhContactBackend(), referenceCutBackendFactory());
  const ReamComputation c = engine.compute(s.bone->current(), s.bone->currentRevision(), at(15, -1.0), 30.0);
  EXPECT_FALSE(c.swept);
  EXPECT_LT(c.cut.removedMm3, 0.6 * 30.0 * widthAcrossX(*s.reamer->cuttingVolume()));
}

TEST(SweptCut, AxialJumpLongerThanTheSolidIsSwept) {
  // The flat reamer is 10 mm long: a 15 mm plunge in one step would leave 5 mm uncut between the two solids.
  test::ReamScene s(block(), test::flatReamer20());
  s.controller->moveTo(at(0, 1.0));
  const ReamStepOutcome shortFeed = s.controller->moveTo(at(0, -2.0));  // 3 mm: covered, not swept
  EXPECT_FALSE(shortFeed.swept);
  const ReamStepOutcome plunge = s.controller->moveTo(at(0, -17.0));  // 15 mm at once
  EXPECT_TRUE(plunge.swept);
  const double disc = shortFeed.cut.removedMm3 / 2.0;  // per mm of depth
  EXPECT_NEAR(plunge.cut.removedMm3, 15.0 * disc, 1e-6 * plunge.cut.removedMm3);
}

// A move that travels less than 1 µm across the axis (a hand-held device at rest jitters by less) is cut at
// its end pose: what it would sweep lies within that of the end placement, far under the reamer's facet sag.
// From 1 µm on it is swept, in one Boolean. Both remove the same to within the travel times the sweep's face.
TEST(SweptCut, ASidewaysTravelUnderAMicrometreIsCutAtItsEndPose) {
  test::ReamScene s(block(), test::flatReamer20(), localCutBackendFactory());
  s.controller->moveTo(at(0, 1.0));
  s.controller->moveTo(at(0, -1.0));
  ReamEngine engine(s.reamer->cuttingVolume(), makeBvhContactBackend(), localCutBackendFactory());
  const Pose start = at(0, -1.0);
  const ReamComputation jitter =
      engine.compute(s.bone->current(), s.bone->currentRevision(), at(0.0005, -1.1), 0.1, &start);
  EXPECT_FALSE(jitter.swept);
  EXPECT_TRUE(jitter.cut.changed);
  const ReamComputation moved =
      engine.compute(s.bone->current(), s.bone->currentRevision(), at(0.002, -1.1), 0.1, &start);
  EXPECT_TRUE(moved.swept);
  EXPECT_EQ(moved.sweepCuts, 1);
  // The disc's area times 0.1 mm either way, plus what the 2 µm travel sweeps beyond the end placement.
  EXPECT_NEAR(moved.cut.removedMm3, jitter.cut.removedMm3, 0.002 * 1.1 * widthAcrossX(*s.reamer->cuttingVolume()));
}

// The flat reamer 1 mm deep, tilted by `deg` about y, its tip moved `x` mm along x.
Pose tiltedAt(double deg, double x = 0) {
  const double a = deg * 3.14159265358979323846 / 180;
  return Pose{{x, 0, -1.0}, {std::sin(a), 0, -std::cos(a)}, 0};
}

// Bone removed by a move of the flat reamer 1 mm deep that turns it by 10 degrees while its tip travels
// 8 mm along x (a hand swinging the reamer about a point on the shaft), in one step whose turn is cut in
// sub-steps of `hullMm` (0: the reamer is placed at the end pose, nothing said about where it came from).
double removedBySwinging(double hullMm, int* sweepCuts = nullptr) {
  test::ReamScene s(block(), test::flatReamer20(), localCutBackendFactory());
  s.controller->moveTo(at(0, 1.0));
  s.controller->moveTo(at(0, -1.0));
  ReamEngine engine(s.reamer->cuttingVolume(), makeBvhContactBackend(), localCutBackendFactory());
  if (hullMm > 0) engine.setTurnTravel({0.5, hullMm});
  const Pose start = at(0, -1.0);
  const ReamComputation c =
      engine.compute(s.bone->current(), s.bone->currentRevision(), tiltedAt(10.0, 8.0), 8.0, hullMm > 0 ? &start : nullptr);
  EXPECT_EQ(c.swept, hullMm > 0);
  EXPECT_LT(c.volumeBookkeepingError, 1e-6 * c.cut.removedMm3);
  if (sweepCuts) *sweepCuts = c.sweepCuts;
  const BoneInvariants inv = engine.checkBone();
  EXPECT_TRUE(inv.closed);
  EXPECT_FALSE(inv.selfIntersectsExact);
  return c.cut.removedMm3;
}

// The local engine only: the CGAL reference keeps every intersection point exact, and a chain of slightly
// turned placements makes its rationals grow until one cut takes minutes (the reason the local engine
// rounds, docs/CSG.md).
TEST(SweptCut, SwingRemovesWhatTheSwingingReamerSweeps) {
  // The default sub-steps (0.1 mm at the farthest point: 25 hulls and the end pose) against sub-steps 4
  // times finer: the error is of first order in the sub-step, and under 0.5 % at the default. Placing the
  // reamer at the end pose leaves the slot it travelled through.
  int cuts = 0;
  const double swing = removedBySwinging(ReamEngine::TurnTravel{}.hullMm, &cuts);
  const double fine = removedBySwinging(0.025);
  const double placed = removedBySwinging(0);
  EXPECT_EQ(cuts, 26);
  EXPECT_LT(swing, fine);  // hulls at each sub-step's first orientation: the rim's depth lags the turn
  EXPECT_NEAR(swing, fine, 5e-3 * fine);
  EXPECT_GT(fine - placed, 100.0);  // mm³: about 8 mm x 20 mm x 1 mm of slot
}

TEST(SweptCut, TheSameSwingRemovesTheSameVolumeEveryTime) {
  // Fresh engines, the allocator's state disturbed between them: convex_hull_3 splits the planar faces of a
  // sweep (the flat reamer's floor and discs) in an order that follows memory addresses, so before the hull
  // was triangulated canonically (SweptVolume.h) these differed by up to 0.1 % (docs/CSG.md).
  std::vector<std::unique_ptr<int[]>> junk;
  const double first = removedBySwinging(ReamEngine::TurnTravel{}.hullMm);
  for (int run = 1; run < 3; ++run) {
    for (int k = 0; k < 300 * run; ++k) junk.emplace_back(new int[std::size_t(17 + k % 13)]);
    EXPECT_EQ(removedBySwinging(ReamEngine::TurnTravel{}.hullMm), first) << run;
  }
}

TEST(SweptCut, TurnPathFollowsTheGreatCircleAndEndsAtThePose) {
  const RigidTransform from = toTransform(at(0, 0));
  Pose end = tiltedAt(10.0);
  end.tip = {3, 1, -2};
  end.rollDeg = 37;  // a roll comes with the end pose; the path before it keeps the swing's
  const RigidTransform to = toTransform(end);
  const TurnPath path(from, to);
  ASSERT_TRUE(path.isTurn());
  const Vec3 a0 = from.applyToDirection({0, 0, 1}), a1 = to.applyToDirection({0, 0, 1});
  const double angle = 10.0 * 3.14159265358979323846 / 180;
  EXPECT_NEAR(path.angle(), angle, 1e-12);
  const double radius = 14, travel = 0.25;
  const Vec3 move = to.translation - from.translation;
  const Vec3 sideways = move - a1 * dot(move, a1);
  const int n = turnSubSteps(path, radius, travel, true);
  ASSERT_EQ(n, static_cast<int>(std::ceil((norm(sideways) + angle * radius) / travel)));
  EXPECT_EQ(turnSubSteps(path, radius, travel, false), static_cast<int>(std::ceil(angle * radius / travel)));
  const Vec3 k = normalized(cross(a0, a1));
  RigidTransform previous = from;
  for (int i = 1; i <= n; ++i) {
    const double s = double(i) / n;
    const RigidTransform t = path.at(s);
    EXPECT_LT(norm(t.translation - (from.translation + move * s)), 1e-12);  // the tip on its line
    const Vec3 axis = t.applyToDirection({0, 0, 1});
    EXPECT_NEAR(dot(axis, k), 0.0, 1e-12);                                   // on the great circle
    EXPECT_NEAR(std::acos(std::min(1.0, dot(axis, a0))), s * angle, 1e-9);  // evenly along it
    // Every point within the radius moves at most `travel` besides the feed (the last sub-step adds the roll).
    if (i < n) {
      for (const Vec3& q : {Vec3{radius, 0, 0}, Vec3{0, radius, 0}, Vec3{0, 0, radius}, Vec3{0, 0, -radius},
                            normalized(Vec3{1, 1, 1}) * radius}) {
        EXPECT_LE(norm(t.apply(q) - previous.apply(q) - a1 * (dot(move, a1) / n)), travel * (1 + 1e-9));
      }
    }
    previous = t;
  }
  EXPECT_EQ(path.at(1).rotation, to.rotation);
  EXPECT_EQ(path.at(1).translation, to.translation);
  // Not a turn: the same axis (a translation or a roll), or opposite axes.
  EXPECT_FALSE(TurnPath(from, toTransform(Pose{{5, 0, 0}, {0, 0, -1}, 30})).isTurn());
  EXPECT_FALSE(TurnPath(from, toTransform(Pose{{0, 0, 0}, {0, 0, 1}, 0})).isTurn());
  // A huge move is capped.
  EXPECT_EQ(turnSubSteps(TurnPath(from, toTransform(Pose{{0, 0, 0}, {1, 0, 0}, 0})), 100.0, 0.25, true, 96), 96);
}

// The real local engine, raising the stop flag after its n-th Boolean (a user pressing Stop while a swing
// is cut), and noting at each Boolean how far the step said it had got.
class StopAfterCuts : public CutBackend {
 public:
  StopAfterCuts(std::unique_ptr<CutBackend> inner, StepControl& control, int n, std::vector<std::pair<int, int>>& seen)
      : inner_(std::move(inner)), control_(control), n_(n), seen_(seen) {}
  ReferenceCut subtract(const TriangleMesh& tool) override {
    seen_.emplace_back(control_.booleansDone.load(), control_.booleansTotal.load());
    ReferenceCut c = inner_->subtract(tool);
    if (++cuts_ == n_) control_.stop = true;
    return c;
  }
  void setCuttingSolid(const TriangleMesh& solid) override { inner_->setCuttingSolid(solid); }
  TriangleMesh mesh() const override { return inner_->mesh(); }
  const BoneState* state() const override { return inner_->state(); }
  BoneInvariants checkInvariants() const override { return inner_->checkInvariants(); }

 private:
  std::unique_ptr<CutBackend> inner_;
  StepControl& control_;
  int n_, cuts_ = 0;
  std::vector<std::pair<int, int>>& seen_;
};

TEST(SweptCut, StoppedSwingLeavesTheBoneWholeAndTheNextStepCutsItAll) {
  // A 10 degree swing is 26 Booleans. Stopped after the third, the step throws ReamCancelled and returns
  // nothing; the same step asked again (the engine resyncs from the bone it is given) removes what an
  // engine that was never stopped removes. Along the way the step says how many Booleans it has done.
  test::ReamScene s(block(), test::flatReamer20(), localCutBackendFactory());
  s.controller->moveTo(at(0, 1.0));
  s.controller->moveTo(at(0, -1.0));
  const BoneState before = s.bone->current();
  const std::uint64_t revision = s.bone->currentRevision();
  const Pose start = at(0, -1.0);
  StepControl control;
  std::vector<std::pair<int, int>> seen;
  const CutBackendFactory local = localCutBackendFactory();
  ReamEngine engine(s.reamer->cuttingVolume(), makeBvhContactBackend(),
                    [&](const BoneState& b) { return std::make_unique<StopAfterCuts>(local(b), control, 3, seen); });
  EXPECT_THROW(engine.compute(before, revision, tiltedAt(10.0, 8.0), 8.0, &start, &control), ReamCancelled);
  EXPECT_TRUE(control.stop.load());
  EXPECT_EQ(control.booleansDone.load(), 3);
  ASSERT_EQ(seen.size(), 3u);
  for (int k = 0; k < 3; ++k) EXPECT_EQ(seen[std::size_t(k)], std::make_pair(k, 26)) << k;
  EXPECT_EQ(s.bone->currentRevision(), revision);  // the document never saw the partial swing

  StepControl again;
  const ReamComputation resumed = engine.compute(before, revision, tiltedAt(10.0, 8.0), 8.0, &start, &again);
  EXPECT_EQ(again.booleansDone.load(), 26);
  ReamEngine fresh(s.reamer->cuttingVolume(), makeBvhContactBackend(), localCutBackendFactory());
  const ReamComputation whole = fresh.compute(before, revision, tiltedAt(10.0, 8.0), 8.0, &start);
  EXPECT_EQ(resumed.sweepCuts, 26);
  EXPECT_GT(whole.cut.removedMm3, 100.0);
  // Bit for bit: the same 26 Booleans on the same bone, with hulls listed and split the same way every time
  // (docs/CSG.md, "Reproducibility").
  EXPECT_EQ(resumed.cut.removedMm3, whole.cut.removedMm3);
  EXPECT_LT(resumed.volumeBookkeepingError, 1e-6 * resumed.cut.removedMm3);
  ASSERT_TRUE(resumed.next && whole.next);
  EXPECT_EQ(resumed.next->liveTriangleCount(), whole.next->liveTriangleCount());
  const BoneInvariants inv = engine.checkBone();
  EXPECT_TRUE(inv.closed);
  EXPECT_FALSE(inv.selfIntersectsExact);

  // Raised before the step, nothing is cut at all (the cutter is still in step with the bone).
  StepControl early;
  early.stop = true;
  EXPECT_THROW(fresh.compute(before, revision, tiltedAt(10.0, 8.0), 8.0, &start, &early), ReamCancelled);
  EXPECT_EQ(early.booleansDone.load(), 0);
}

TEST(SweptCut, TurnInPlaceIsAChainOfPlacements) {
  // Tilting about the tip sweeps little beyond the end pose for a flat reamer (its body leans over the
  // bone its face passed), but what it sweeps is cut, the chain costs a few Booleans, and the bone stays
  // closed and free of self-intersections.
  test::ReamScene s(block(), test::flatReamer20(), localCutBackendFactory());
  s.controller->moveTo(at(0, 1.0));
  s.controller->moveTo(at(0, -1.0));
  const ReamStepOutcome turn = s.controller->moveTo(tiltedAt(4.0));
  EXPECT_TRUE(turn.swept);
  const double arc = 4.0 * 3.14159265358979323846 / 180 * norm(Vec3{10, 0, 10});
  EXPECT_GE(turn.sweepCuts, static_cast<int>(std::ceil(arc / 0.5)));
  EXPECT_GE(turn.sweepCuts, 2);
  EXPECT_GT(turn.cut.removedMm3, 1.0);
  EXPECT_LT(turn.volumeBookkeepingError, 1e-6 * turn.cut.removedMm3);
  const BoneInvariants inv = s.controller->checkBone();
  EXPECT_TRUE(inv.closed);
  EXPECT_FALSE(inv.selfIntersectsExact);
  EXPECT_FALSE(inv.selfIntersectsRounded);
}

TEST(SweptCut, HullOfTwoPlacementsIsClosedAndHasTheExpectedVolume) {
  const TriangleMesh solid = buildCuttingSolid(test::flatReamer20());
  const RigidTransform a = toTransform(at(0, 0)), b = toTransform(at(7, 0));
  const TriangleMesh hull = sweptByTranslation(solid, a, b);
  EXPECT_TRUE(isConvexSolid(hull));
  EXPECT_NEAR(signedVolume(hull), signedVolume(solid) + 7.0 * widthAcrossX(solid) * 10.0, 1e-6);
  RigidTransform turned = b;
  turned.rotation[0] = 0.5;
  EXPECT_THROW(sweptByTranslation(solid, a, turned), std::invalid_argument);
}

// The glenoid reamer (a spherical cap on a cylinder) at tilted poses moved across, along and obliquely to its
// axis: the hull has the volume of the Minkowski sum of the solid and the move, and every placed vertex of
// both placements lies on or behind every hull face (a corner lost would lie outside it).
TEST(SweptCut, HullOfTheGlenoidReamerHoldsEveryPlacedVertex) {
  const TriangleMesh solid = buildCuttingSolid(loadPreset("glenoid-36-R30", reamerPresetsPath()));
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  const Vec3 moves[] = {{0.5, 0, 0}, {0, 0, -0.8}, {0.3, -0.2, -0.4}, {4, 1, 0}, {0, 1e-3, 0}};
  for (int pose = 0; pose < 4; ++pose) {
    const Vec3 axis = normalized(Vec3{0.3 * u(rng), 0.3 * u(rng), -1});
    const RigidTransform from = toTransform(Pose{{u(rng), u(rng), u(rng)}, axis, 40.0 * u(rng)});
    for (const Vec3& move : moves) {
      SCOPED_TRACE("pose " + std::to_string(pose) + ", move " + std::to_string(move.x) + " " +
                   std::to_string(move.y) + " " + std::to_string(move.z));
      RigidTransform to = from;
      const Vec3 d = from.applyToDirection(move);
      to.translation = from.translation + d;
      const TriangleMesh hull = sweptByTranslation(solid, from, to);
      ASSERT_FALSE(hull.triangles.empty());
      // Its volume: the solid's plus its shadow across the move times the move's length (a Minkowski sum).
      double shadow = 0;
      for (const Triangle& t : solid.triangles) {
        const Vec3 a = from.apply(solid.vertices[t[0]]);
        shadow += 0.25 * std::abs(dot(cross(from.apply(solid.vertices[t[1]]) - a, from.apply(solid.vertices[t[2]]) - a), d));
      }
      const double expected = signedVolume(solid) + shadow;
      EXPECT_NEAR(signedVolume(hull), expected, 1e-9 * expected);
      // Every placed vertex on or behind every face's plane (to 1e-9 mm). Faces whose corners lie all but on
      // one line (a feed along the axis makes needles of the strips between the cylinder's edges) have no
      // plane to speak of in doubles; their neighbours bound the same points. A thin face's plane (a 1 µm move
      // makes parallelograms 1 µm by 1 mm) is known to its squared size over its area times the rounding,
      // which the bound grows by.
      for (const Triangle& f : hull.triangles) {
        const Vec3 a = hull.vertices[f[0]], e1 = hull.vertices[f[1]] - a, e2 = hull.vertices[f[2]] - a;
        const Vec3 n = cross(e1, e2);
        if (!(norm(n) > 1e-3 * norm(e1) * norm(e2))) continue;
        const double bound = 1e-9 * std::max(1.0, std::max(squaredNorm(e1), squaredNorm(e2)) / norm(n));
        const Vec3 un = normalized(n);
        for (const RigidTransform* t : {&from, static_cast<const RigidTransform*>(&to)})
          for (const Vec3& v : solid.vertices) ASSERT_LE(dot(un, t->apply(v) - a), bound);
      }
    }
  }
}

// hullOfPlacements (sweptByTranslation's fallback): the hull of a tilted flat reamer moved across its axis is
// listed the same way after the allocator's state changed. Moved along x at its axis-aligned pose (its discs then lie exactly in planes z = const), the
// discs' interior points are left out and each disc face is split by its Delaunay triangulation (no vertex
// inside the circumcircle of the triangle across an edge); convex_hull_3's own split is neither.
TEST(SweptCut, HullIsTheSameEveryTimeWithCornersOnlyAndDelaunayFaces) {
  const TriangleMesh solid = buildCuttingSolid(test::flatReamer20());
  const RigidTransform tilted = toTransform(tiltedAt(10.0));
  RigidTransform across = tilted;
  across.translation = across.translation + Vec3{3.0, 1.5, 0.25};
  const TriangleMesh first = hullOfPlacements(solid, tilted, across);
  std::vector<std::unique_ptr<int[]>> junk;
  for (int run = 0; run < 4; ++run) {
    for (int k = 0; k < 500; ++k) junk.emplace_back(new int[std::size_t(5 + (k * 7) % 31)]);
    const TriangleMesh again = hullOfPlacements(solid, tilted, across);
    ASSERT_EQ(again.triangles, first.triangles) << run;
    ASSERT_EQ(again.vertices.size(), first.vertices.size());
    for (std::size_t i = 0; i < first.vertices.size(); ++i) EXPECT_EQ(again.vertices[i], first.vertices[i]);
  }

  const TriangleMesh hull = hullOfPlacements(solid, toTransform(at(0, 0)), toTransform(at(7, 0)));
  EXPECT_TRUE(isConvexSolid(hull));
  auto flat = [&](const Triangle& t) {
    return hull.vertices[t[0]].z == hull.vertices[t[1]].z && hull.vertices[t[0]].z == hull.vertices[t[2]].z;
  };
  std::vector<int> offDisc(hull.vertices.size(), 0);  // faces around each vertex not in a disc's plane
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::size_t> faceOfEdge;
  for (std::size_t f = 0; f < hull.triangles.size(); ++f) {
    const Triangle& t = hull.triangles[f];
    for (int k = 0; k < 3; ++k) {
      offDisc[t[k]] += flat(t) ? 0 : 1;
      EXPECT_TRUE(faceOfEdge.emplace(std::make_pair(t[k], t[(k + 1) % 3]), f).second);  // each directed edge once
    }
  }
  for (std::size_t v = 0; v < offDisc.size(); ++v) EXPECT_GT(offDisc[v], 0) << "vertex " << v << " inside a disc";
  int discPairs = 0;
  for (const auto& [edge, f] : faceOfEdge) {
    const auto twin = faceOfEdge.find({edge.second, edge.first});
    ASSERT_NE(twin, faceOfEdge.end());  // closed
    const Triangle &t = hull.triangles[f], &u = hull.triangles[twin->second];
    if (!flat(t) || !flat(u) || hull.vertices[t[0]].z != hull.vertices[u[0]].z) continue;
    ++discPairs;
    std::uint32_t x = u[0];
    for (std::uint32_t w : u)
      if (w != edge.first && w != edge.second) x = w;
    // In-circle determinant in the plane, oriented by the face's normal (+z or -z): > 0 when x is inside.
    const Vec3 &p = hull.vertices[t[0]], &q = hull.vertices[t[1]], &r = hull.vertices[t[2]], &c = hull.vertices[x];
    const double sz = cross(q - p, r - p).z > 0 ? 1.0 : -1.0;
    const double ax = p.x - c.x, ay = p.y - c.y, bx = q.x - c.x, by = q.y - c.y, cx = r.x - c.x, cy = r.y - c.y;
    const double det = (ax * ax + ay * ay) * (bx * cy - by * cx) - (bx * bx + by * by) * (ax * cy - ay * cx) +
                       (cx * cx + cy * cy) * (ax * by - ay * bx);
    EXPECT_LE(sz * det, 1e-9) << "edge " << edge.first << "-" << edge.second;
  }
  EXPECT_GT(discPairs, 50);  // the stadium-shaped floor and back
}

// hullOfPlacements: a solid with integer corners moved by an integer vector with a part along its axis: every
// coordinate is exact, so coplanarity is decided exactly here too. The hull's planar faces (the floor, the top and the
// slanted parallelograms between the two placements' edges) are split with the Delaunay condition (the two
// angles facing a shared edge sum to at most 180 degrees), and every vertex is a corner (three or more
// planes around it: the midpoints on the prism's edges are left out).
TEST(SweptCut, HullOfAnExactPrismSplitsItsPlanarFacesByDelaunay) {
  // A prism over the triangle (0,0) (8,0) (0,6), 10 high, with the midpoints of its vertical edges and of its
  // bottom edges as extra vertices (on edges of the solid, so never corners of the hull).
  TriangleMesh prism;
  prism.vertices = {{0, 0, 0}, {8, 0, 0}, {0, 6, 0}, {0, 0, 10}, {8, 0, 10}, {0, 6, 10},
                    {0, 0, 5}, {8, 0, 5}, {0, 6, 5}, {4, 0, 0}, {4, 3, 0}, {0, 3, 0}};
  prism.triangles = {{0, 11, 9}, {9, 10, 1}, {11, 2, 10}, {9, 11, 10},           // bottom (-z)
                     {3, 4, 5},                                                  // top (+z)
                     {0, 9, 6}, {9, 1, 7}, {9, 7, 6}, {6, 7, 4}, {6, 4, 3},      // y = 0
                     {0, 6, 11}, {11, 8, 2}, {11, 6, 8}, {6, 5, 8}, {6, 3, 5},   // x = 0
                     {1, 10, 7}, {10, 2, 8}, {10, 8, 7}, {7, 8, 5}, {7, 5, 4}};  // the slanted side
  ASSERT_NEAR(signedVolume(prism), 240.0, 1e-9);
  RigidTransform from, to;
  to.translation = Vec3{5, 3, 4};
  const TriangleMesh hull = hullOfPlacements(prism, from, to);
  EXPECT_TRUE(isConvexSolid(hull));
  // The hull of two placements of a convex solid is its Minkowski sum with the move: its volume plus the
  // area of its shadow across the move times the move's length, i.e. half the sum of |area vector . move|.
  double shadow = 0;
  for (const Triangle& t : prism.triangles)
    shadow += 0.5 * std::abs(dot(cross(prism.vertices[t[1]] - prism.vertices[t[0]], prism.vertices[t[2]] - prism.vertices[t[0]]) * 0.5,
                                 to.translation));
  EXPECT_NEAR(signedVolume(hull), 240.0 + shadow, 1e-9);
  auto normal = [&](const Triangle& t) {
    return cross(hull.vertices[t[1]] - hull.vertices[t[0]], hull.vertices[t[2]] - hull.vertices[t[0]]);
  };
  auto sameDirection = [](const Vec3& a, const Vec3& b) { return norm(cross(a, b)) == 0 && dot(a, b) > 0; };  // exact: integers
  std::vector<std::vector<Vec3>> planes(hull.vertices.size());
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::size_t> faceOfEdge;
  for (std::size_t f = 0; f < hull.triangles.size(); ++f) {
    const Triangle& t = hull.triangles[f];
    for (int k = 0; k < 3; ++k) {
      auto& ps = planes[t[k]];
      if (std::none_of(ps.begin(), ps.end(), [&](const Vec3& m) { return sameDirection(m, normal(t)); })) ps.push_back(normal(t));
      faceOfEdge[{t[k], t[(k + 1) % 3]}] = f;
    }
  }
  for (std::size_t v = 0; v < planes.size(); ++v) EXPECT_GE(planes[v].size(), 3u) << "vertex " << v;
  auto angleAt = [&](std::uint32_t apex, std::uint32_t a, std::uint32_t b) {
    const Vec3 u = hull.vertices[a] - hull.vertices[apex], w = hull.vertices[b] - hull.vertices[apex];
    return std::atan2(norm(cross(u, w)), dot(u, w));
  };
  int split = 0;
  for (const auto& [edge, f] : faceOfEdge) {
    if (edge.first > edge.second) continue;
    const Triangle &t = hull.triangles[f], &u = hull.triangles[faceOfEdge.at({edge.second, edge.first})];
    if (!sameDirection(normal(t), normal(u))) continue;
    ++split;
    auto opposite = [&](const Triangle& x) {
      for (std::uint32_t w : x)
        if (w != edge.first && w != edge.second) return w;
      return x[0];
    };
    const double facing = angleAt(opposite(t), edge.first, edge.second) + angleAt(opposite(u), edge.first, edge.second);
    EXPECT_LE(facing, M_PI + 1e-12) << "edge " << edge.first << "-" << edge.second;
  }
  EXPECT_GE(split, 4);  // at least the floor, the top and two parallelograms are split faces
}


// The silhouette sweep (what sweptByTranslation builds first) against the hull of the two placements, for the
// glenoid and the flat reamer at tilted, rolled poses and moves across, along and oblique to the axis: where it
// is built, a closed, consistently oriented surface without self-intersections (CGAL, exact predicates) whose
// volume is the hull's, each one's vertices on or behind the other's faces; and it is built
// for every move with a part across the axis (the key moves of the reaming loop), which is where its speed
// matters. Mutation-checked: without the tolerance that keeps the two halves of a planar strip parallel to
// the move together, the fold check refuses seven of these moves (the hull is built instead), and without
// that check too the strip folds over itself and this fails (self-intersections, a vertex 28 mm in front of
// a face).
TEST(SweptCut, SilhouetteSweepIsTheHullOfThePlacements) {
  const std::vector<TriangleMesh> solids = {buildCuttingSolid(loadPreset("glenoid-36-R30", reamerPresetsPath())),
                                            buildCuttingSolid(test::flatReamer20())};
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  const Vec3 moves[] = {{0.5, 0, 0}, {0, -0.5, 0}, {0.3, -0.2, -0.4}, {4, 1, 0}, {0, 1e-3, 0}, {0, 0, -0.8}};
  int built = 0;
  for (std::size_t k = 0; k < solids.size(); ++k) {
    const TriangleMesh& solid = solids[k];
    for (int pose = 0; pose < 6; ++pose) {
      // The first pose axis-aligned and unrolled (faces exactly parallel to the move), the others tilted.
      const Vec3 axis = pose == 0 ? Vec3{0, 0, -1} : normalized(Vec3{0.3 * u(rng), 0.3 * u(rng), -1});
      const RigidTransform from =
          toTransform(Pose{{u(rng), u(rng), u(rng)}, axis, pose == 0 ? 0.0 : 40.0 * u(rng)});
      for (const Vec3& move : moves) {
        SCOPED_TRACE("solid " + std::to_string(k) + ", pose " + std::to_string(pose) + ", move " +
                     std::to_string(move.x) + " " + std::to_string(move.y) + " " + std::to_string(move.z));
        RigidTransform to = from;
        to.translation = from.translation + from.applyToDirection(move);
        const std::optional<TriangleMesh> swept = sweptBySilhouette(solid, from, to);
        const bool across = std::hypot(move.x, move.y) >= 1e-3;
        if (across) {
          EXPECT_TRUE(swept.has_value());
        }
        if (!swept) continue;
        ++built;
        const EdgeTopology topology = analyzeEdges(*swept);
        EXPECT_EQ(topology.boundaryEdges, 0u);
        EXPECT_EQ(topology.nonManifoldEdges, 0u);
        EXPECT_TRUE(topology.consistentlyOriented());
        EXPECT_EQ(countSelfIntersections(*swept), 0u);
        const TriangleMesh hull = hullOfPlacements(solid, from, to);
        EXPECT_NEAR(signedVolume(*swept), signedVolume(hull), 1e-9 * signedVolume(hull));
        EXPECT_TRUE(isConvexSolid(*swept));
        // The same convex body: each one's vertices on or behind every face of the other (to 1e-9 mm).
        auto behindEveryFace = [](const TriangleMesh& faces, const std::vector<Vec3>& points) {
          double worst = -1;
          for (const Triangle& f : faces.triangles) {
            // A needle (the hull makes them of strips parallel to the move) has no plane to speak of; a thin
            // face's plane is known in doubles to its squared size over its area times the rounding.
            const Vec3 a = faces.vertices[f[0]], e1 = faces.vertices[f[1]] - a, e2 = faces.vertices[f[2]] - a;
            const double area2 = norm(cross(e1, e2));
            if (!(area2 > 1e-3 * norm(e1) * norm(e2))) continue;
            const double slack = 1e-9 * std::max(1.0, std::max(squaredNorm(e1), squaredNorm(e2)) / area2);
            const Vec3 n = normalized(cross(e1, e2));
            for (const Vec3& p : points) worst = std::max(worst, dot(n, p - a) - slack + 1e-9);
          }
          return worst;
        };
        EXPECT_LE(behindEveryFace(*swept, hull.vertices), 1e-9);
        EXPECT_LE(behindEveryFace(hull, swept->vertices), 1e-9);
      }
    }
  }
  EXPECT_GE(built, 2 * 6 * 4);
}

}  // namespace
}  // namespace reamsim
