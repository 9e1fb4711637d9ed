// The glenoid frame kept in resources/ is what findGlenoid derives from the bundled bone.
#include <gtest/gtest.h>

#include <cmath>

#include "reamsim/mesh/MeshIO.h"
#include "reamsim/ream/DefaultCase.h"
#include "reamsim/ream/Glenoid.h"

namespace reamsim {
namespace {

TEST(Glenoid, ResourceMatchesDerivationFromTheMesh) {
  const DefaultBone bone = loadDefaultBone();
  const GlenoidFrame derived = findGlenoid(bone.mesh);
  EXPECT_LT(norm(derived.centre - bone.glenoid.centre), 1e-6);
  EXPECT_GT(dot(derived.outwardAxis, bone.glenoid.outwardAxis), std::cos(1e-6));
  EXPECT_NEAR(derived.sphereRadiusMm, bone.glenoid.sphereRadiusMm, 1e-6);
}

TEST(Glenoid, IsAnatomicallyPlausible) {
  const DefaultBone bone = loadDefaultBone();
  const GlenoidFrame& g = bone.glenoid;
  // Faces laterally (+Z in the OpenSim frame), radius within the published 35.4 ± 7.8 mm (2 SD).
  EXPECT_GT(g.outwardAxis.z, 0.5);
  EXPECT_GT(g.sphereRadiusMm, 35.4 - 2 * 7.8);
  EXPECT_LT(g.sphereRadiusMm, 35.4 + 2 * 7.8);
  EXPECT_LT(g.rmsResidualMm, 0.5);
  // The centre lies on the bone surface: some vertex within 2 mm.
  double nearest = INFINITY;
  for (const Vec3& p : bone.mesh.vertices) nearest = std::min(nearest, norm(p - g.centre));
  EXPECT_LT(nearest, 2.0);
}

TEST(Glenoid, NoConcaveLateralPatchIsAClearError) {
  TriangleMesh tetra;
  tetra.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  tetra.triangles = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
  EXPECT_THROW(findGlenoid(tetra), std::runtime_error);
}

}  // namespace
}  // namespace reamsim
