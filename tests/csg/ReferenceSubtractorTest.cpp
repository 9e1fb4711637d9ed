#include <gtest/gtest.h>

#include <cmath>

#include "reamsim/csg/ReferenceSubtractor.h"
#include "reamsim/mesh/Validation.h"
#include "reamsim/tools/Primitives.h"
#include "reamsim/tools/ReamerGeometry.h"

namespace reamsim {
namespace {

TriangleMesh block() { return buildBox(Bounds{{-30, -30, -20}, {30, 30, 0}}, 4); }

// A flat reamer, tip at (0, 0, zTip), feeding along -Z (local +Z maps to -Z: flip y and z).
TriangleMesh flatToolAt(double zTip, int segments = 64) {
  ReamerSpec spec;
  spec.diameterMm = 20;
  spec.bodyLengthMm = 10;
  spec.segments = segments;
  spec.rings = 4;
  TriangleMesh m = buildCuttingSolid(spec);
  for (Vec3& p : m.vertices) p = {p.x, -p.y, zTip - p.z};
  return m;
}

double polygonArea(double radius, int segments) { return 0.5 * segments * radius * radius * std::sin(2 * M_PI / segments); }

TEST(ReferenceSubtractor, RemovesExactlyThePrismOfTheFacetedTool) {
  ReferenceSubtractor engine(block());
  const double depth = 1.5;
  const ReferenceCut cut = engine.subtract(flatToolAt(-depth));
  ASSERT_TRUE(cut.changed);
  const double expected = polygonArea(10, 64) * depth;
  EXPECT_NEAR(cut.removedMm3, expected, expected * 1e-9);
  EXPECT_NEAR(cut.volumeBeforeMm3 - cut.volumeAfterMm3, cut.removedMm3, 1e-6 * cut.removedMm3);
  EXPECT_EQ(cut.facesAfter, engine.faceCount());
  const BoneInvariants inv = engine.checkInvariants();
  EXPECT_TRUE(inv.closed);
  EXPECT_TRUE(inv.outwardOriented);
  EXPECT_FALSE(inv.selfIntersectsExact);
  EXPECT_FALSE(inv.selfIntersectsRounded);
  EXPECT_TRUE(validateMesh(engine.mesh()).isCleanSolid());
}

TEST(ReferenceSubtractor, ToolOutsideLeavesBoneUntouched) {
  ReferenceSubtractor engine(block());
  const double before = engine.volumeMm3();
  const std::size_t faces = engine.faceCount();
  const ReferenceCut cut = engine.subtract(flatToolAt(+5));
  EXPECT_FALSE(cut.changed);
  EXPECT_EQ(cut.removedMm3, 0.0);
  EXPECT_EQ(engine.volumeMm3(), before);
  EXPECT_EQ(engine.faceCount(), faces);
}

TEST(ReferenceSubtractor, ConsecutiveCutsKeepInvariants) {
  ReferenceSubtractor engine(block());
  double total = 0;
  for (int i = 1; i <= 12; ++i) {
    // Tilted, offset cuts so that new edges cross old ones.
    TriangleMesh tool = flatToolAt(-0.37 * i, 48);
    const double a = 0.05 * i;
    for (Vec3& p : tool.vertices) p = {p.x * std::cos(a) - p.z * std::sin(a) + 0.7 * i, p.y + 0.3 * i, p.x * std::sin(a) + p.z * std::cos(a)};
    const ReferenceCut cut = engine.subtract(tool);
    total += cut.removedMm3;
    EXPECT_NEAR(cut.volumeBeforeMm3 - cut.volumeAfterMm3, cut.removedMm3, 1e-6 * std::max(1.0, cut.removedMm3));
    const BoneInvariants inv = engine.checkInvariants();
    ASSERT_TRUE(inv.closed && inv.outwardOriented && !inv.selfIntersectsExact) << "cut " << i;
  }
  EXPECT_NEAR(60.0 * 60 * 20 - engine.volumeMm3(), total, 1e-6 * total);
}

TEST(ReferenceSubtractor, RejectsOpenBone) {
  TriangleMesh open = block();
  open.triangles.pop_back();
  EXPECT_THROW(ReferenceSubtractor{open}, std::invalid_argument);
}

}  // namespace
}  // namespace reamsim
