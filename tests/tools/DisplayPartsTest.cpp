#include <gtest/gtest.h>

#include "MeshChecks.h"
#include "reamsim/tools/ReamerGeometry.h"

using namespace reamsim;

TEST(toolsDisplayParts, PinAheadOfTipShaftBehindBody) {
  ReamerSpec s;
  s.diameterMm = 40;
  s.sphereRadiusMm = 32;
  s.bodyLengthMm = 12;
  s.guidePinDiameterMm = 3.2;
  s.guidePinLengthMm = 20;
  s.shaftDiameterMm = 8;
  s.shaftLengthMm = 80;
  const ReamerDisplayParts parts = buildDisplayParts(s);
  ASSERT_FALSE(parts.guidePin.empty());
  ASSERT_FALSE(parts.shaft.empty());
  EXPECT_TRUE(test::isClosedOriented(parts.guidePin));
  EXPECT_TRUE(test::isClosedOriented(parts.shaft));
  EXPECT_GT(signedVolume(parts.guidePin), 0);
  const Bounds pin = computeBounds(parts.guidePin), shaft = computeBounds(parts.shaft);
  EXPECT_EQ(pin.min.z, 0.0);
  EXPECT_EQ(pin.max.z, 20.0);
  EXPECT_NEAR(pin.max.x, 1.6, 1e-12);
  const double back = -capHeight(s) - 12;
  EXPECT_NEAR(shaft.max.z, back, 1e-12);
  EXPECT_NEAR(shaft.min.z, back - 80, 1e-12);
}

TEST(toolsDisplayParts, MissingPartsAreEmpty) {
  ReamerSpec s;  // default: no guide pin
  s.shaftLengthMm = 0;
  const ReamerDisplayParts parts = buildDisplayParts(s);
  EXPECT_TRUE(parts.guidePin.empty());
  EXPECT_TRUE(parts.shaft.empty());
}
