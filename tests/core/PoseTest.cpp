#include <gtest/gtest.h>

#include <limits>
#include <stdexcept>

#include "reamsim/core/Pose.h"

using namespace reamsim;

namespace {
void expectNear(const Vec3& a, const Vec3& b, double tol = 1e-12) {
  EXPECT_NEAR(a.x, b.x, tol);
  EXPECT_NEAR(a.y, b.y, tol);
  EXPECT_NEAR(a.z, b.z, tol);
}
void expectOrthonormal(const RigidTransform& t) {
  const auto& r = t.rotation;
  const Vec3 c0{r[0], r[3], r[6]}, c1{r[1], r[4], r[7]}, c2{r[2], r[5], r[8]};
  EXPECT_NEAR(dot(c0, c0), 1, 1e-12);
  EXPECT_NEAR(dot(c1, c1), 1, 1e-12);
  EXPECT_NEAR(dot(c2, c2), 1, 1e-12);
  EXPECT_NEAR(dot(c0, c1), 0, 1e-12);
  EXPECT_NEAR(dot(c0, c2), 0, 1e-12);
  EXPECT_NEAR(dot(c1, c2), 0, 1e-12);
  expectNear(cross(c0, c1), c2);  // right-handed: a rotation, not a reflection
}
}  // namespace

TEST(Pose, DefaultIsIdentity) {
  const RigidTransform t = toTransform(Pose{});
  for (int i = 0; i < 9; ++i) EXPECT_NEAR(t.rotation[i], (i % 4 == 0) ? 1.0 : 0.0, 1e-15);
}

TEST(Pose, MapsLocalZToAxisAndOriginToTip) {
  for (const Vec3 axis : {Vec3{0, 0, 1}, Vec3{0, 0, -1}, Vec3{1, 0, 0}, Vec3{0, -3, 0}, Vec3{1, 2, 3},
                          Vec3{-0.3, 0.01, -5}, Vec3{1e-3, 1e-3, 1e-9}}) {
    for (double roll : {0.0, 30.0, -170.0}) {
      const Pose pose{{10, -4, 2.5}, axis, roll};
      const RigidTransform t = toTransform(pose);
      expectOrthonormal(t);
      expectNear(t.apply({0, 0, 0}), pose.tip);
      expectNear(t.applyToDirection({0, 0, 1}), normalized(axis));
      expectNear(t.apply({0, 0, 5}), pose.tip + normalized(axis) * 5, 1e-11);
    }
  }
}

TEST(Pose, RollRotatesAboutTheAxis) {
  const Pose a{{0, 0, 0}, {1, 1, 0}, 0}, b{{0, 0, 0}, {1, 1, 0}, 90};
  const Vec3 xa = toTransform(a).applyToDirection({1, 0, 0});
  const Vec3 xb = toTransform(b).applyToDirection({1, 0, 0});
  EXPECT_NEAR(dot(xa, xb), 0, 1e-12);
  expectNear(cross(xa, xb), normalized(a.axis));  // +90 deg is counter-clockwise about the axis
}

TEST(Pose, AdvancedAlongAxis) {
  const Pose p{{1, 2, 3}, {0, 0, 2}, 15};
  const Pose q = advancedAlongAxis(p, 1.5);
  expectNear(q.tip, {1, 2, 4.5});
  EXPECT_EQ(q.axis, p.axis);
  EXPECT_EQ(q.rollDeg, p.rollDeg);
  expectNear(advancedAlongAxis(p, -1).tip, {1, 2, 2});
}

TEST(Pose, ZeroAxisIsRejected) {
  EXPECT_THROW(toTransform(Pose{{0, 0, 0}, {0, 0, 0}, 0}), std::invalid_argument);
  EXPECT_THROW(advancedAlongAxis(Pose{{0, 0, 0}, {0, 0, 0}, 0}, 1), std::invalid_argument);
}

// A NaN or an infinity in the tip or the roll has no transform (it would reach every query as "no contact").
TEST(Pose, NonFiniteTipOrRollIsRejected) {
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  EXPECT_THROW(toTransform(Pose{{0, nan, 0}, {0, 0, -1}, 0}), std::invalid_argument);
  EXPECT_THROW(toTransform(Pose{{inf, 0, 0}, {0, 0, -1}, 0}), std::invalid_argument);
  EXPECT_THROW(toTransform(Pose{{0, 0, 0}, {0, 0, -1}, nan}), std::invalid_argument);
  EXPECT_THROW(toTransform(Pose{{0, 0, 0}, {nan, 0, -1}, 0}), std::invalid_argument);
  EXPECT_NO_THROW(toTransform(Pose{{1e6, -1e6, 0}, {0, 0, -1}, 720}));
}
