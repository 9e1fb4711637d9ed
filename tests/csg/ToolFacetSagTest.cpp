// The tool's facet sag as its mesh shows it, and the clean-up's deviation bound that follows from it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>

#include "LocalTestMeshes.h"
#include "reamsim/csg/LocalSubtractor.h"
#include "reamsim/csg/ToolFacetSag.h"
#include "reamsim/ream/DefaultCase.h"
#include "reamsim/tools/ReamedSurface.h"
#include "reamsim/tools/ReamerPresets.h"

namespace reamsim {
namespace {

using test::capSpec;
using test::flatSpec;
using test::toolAt;

// The measured sag (the deepest point of a cap facet below the sphere, measureReamedSurface) against the
// estimate from the mesh alone, for caps of several sizes and resolutions, placed anywhere.
TEST(ToolFacetSag, FollowsTheCapFacetsDeepestPoint) {
  const Pose pose{{3, -7, 40}, normalized(Vec3{0.2, -0.1, -1}), 17};
  for (const ReamerSpec& spec : {capSpec(36, 30), capSpec(28, 25), capSpec(56, 40), capSpec(36, 30, 192, 24),
                                 capSpec(36, 30, 384, 48), capSpec(36, 30, 128, 36)}) {
    const double measured = measureReamedSurface(toolAt(spec, pose), spec, pose).facetSagMm;
    const double estimate = toolFacetSagMm(toolAt(spec, pose));
    std::printf("%g x %g, %d x %d: facet sag %.4f mm, estimated %.4f\n", spec.diameterMm, spec.sphereRadiusMm,
                spec.segments, spec.rings, measured, estimate);
    EXPECT_NEAR(estimate, measured, 0.25 * measured) << spec.diameterMm << " R" << spec.sphereRadiusMm << " "
                                                     << spec.segments << " x " << spec.rings;
  }
}

TEST(ToolFacetSag, FinerMeshesSagLessAndPlanesNotAtAll) {
  const Pose pose{{0, 0, 0}, {0, 0, -1}, 0};
  const double coarse = toolFacetSagMm(toolAt(capSpec(36, 30, 96, 12), pose));
  const double fine = toolFacetSagMm(toolAt(capSpec(36, 30, 192, 24), pose));
  EXPECT_NEAR(fine / coarse, 0.25, 0.05);  // sag ~ L^2
  TriangleMesh box = toolAt(flatSpec(20, 4), pose);  // a square prism: planes meeting at sharp edges
  EXPECT_LT(toolFacetSagMm(box), 1e-6);  // coplanar neighbours: an acos of 1 to rounding
}

// By default the clean-up moves the surface by at most half the tool's sag; a set bound wins. The
// same triangles with another shape (a reamer scaled up) get their own sag, not the first's.
TEST(ToolFacetSag, SetsTheCleanupsDefaultDeviation) {
  const DefaultBone bone = loadDefaultBone();
  const Pose pose{bone.glenoid.centre - bone.glenoid.outwardAxis * 0.5, -bone.glenoid.outwardAxis, 0};
  for (const ReamerSpec& spec : {capSpec(36, 30), capSpec(36, 30, 192, 24)}) {
    LocalSubtractor engine(bone.mesh);
    const TriangleMesh tool = toolAt(spec, pose);
    const LocalCut c = engine.subtract(tool);
    ASSERT_TRUE(c.changed);
    EXPECT_DOUBLE_EQ(c.cleanupDeviationMm, std::clamp(0.5 * toolFacetSagMm(tool), BandCleanup::kMinAutoDeviationMm,
                                                      BandCleanup::kMaxAutoDeviationMm));
    EXPECT_GT(c.cleanupDeviationMm, BandCleanup::kMinAutoDeviationMm);
  }
  {
    LocalSubtractor engine(bone.mesh);
    const TriangleMesh small = toolAt(capSpec(36, 30), pose);
    TriangleMesh large = small;  // the same triangles, 1.1 times the size about the tip (under the 10 um cap)
    for (Vec3& p : large.vertices) p = pose.tip + (p - pose.tip) * 1.1;
    engine.subtract(small);
    EXPECT_DOUBLE_EQ(engine.subtract(large).cleanupDeviationMm, 0.5 * toolFacetSagMm(large));
  }
  LocalSubtractor engine(bone.mesh);
  BandCleanup set;
  set.maxDeviationMm = 0.002;
  engine.setBandCleanup(set);
  EXPECT_EQ(engine.subtract(toolAt(capSpec(36, 30), pose)).cleanupDeviationMm, 0.002);
}

}  // namespace
}  // namespace reamsim
