// The conservative bounds the first-contact search prunes with: the range of a direction over a BVH
// node's box ∩ slab, and the moving ball that holds a parametric reamer's ideal solid. Each is checked
// against dense sampling: never later (or narrower) than what the samples show, and tight where it is meant
// to be exact.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

#include "ContactEvents.h"
#include "RationalMotion.h"
#include "reamsim/collision/TriangleBvh.h"

namespace reamsim {
namespace {

Vec3 randomUnit(std::mt19937_64& rng) {
  std::normal_distribution<double> g(0, 1);
  for (;;) {
    const Vec3 v{g(rng), g(rng), g(rng)};
    if (norm(v) > 1e-6) return v / norm(v);
  }
}

TEST(collisionSweepBounds, RegionRangeHoldsEveryPointOfBoxAndSlab) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int trial = 0; trial < 200; ++trial) {
    const Vec3 c{50 * u(rng), 50 * u(rng), 50 * u(rng)}, h{1 + u(rng), 1 + u(rng), 1 + u(rng)};
    const Vec3 lo = c - h, hi = c + h;
    BvhSlab slab;
    slab.axis = randomUnit(rng);
    const double mid = dot(slab.axis, c);
    slab.lo = mid - 0.2 + 0.1 * u(rng);
    slab.hi = mid + 0.2 + 0.1 * u(rng);
    const Vec3 dir = trial % 4 == 0 ? normalized(slab.axis + randomUnit(rng) * 0.05) : randomUnit(rng);
    double rlo, rhi;
    regionRange(lo, hi, slab, dir, rlo, rhi);
    // Never wider than the box alone.
    const double boxLo = dot(dir, c) - (std::abs(dir.x) * h.x + std::abs(dir.y) * h.y + std::abs(dir.z) * h.z);
    EXPECT_GE(rlo, boxLo - 1e-9);
    int inside = 0;
    for (int k = 0; k < 20000 && inside < 2000; ++k) {
      const Vec3 p{c.x + h.x * u(rng), c.y + h.y * u(rng), c.z + h.z * u(rng)};
      const double d = dot(slab.axis, p);
      if (d < slab.lo || d > slab.hi) continue;
      ++inside;
      const double v = dot(dir, p);
      ASSERT_GE(v, rlo) << "trial " << trial;
      ASSERT_LE(v, rhi) << "trial " << trial;
    }
  }
}

// Distance from a point to a box.
double boxDistance(const Vec3& p, const Vec3& lo, const Vec3& hi) {
  const Vec3 q{std::clamp(p.x, lo.x, hi.x), std::clamp(p.y, lo.y, hi.y), std::clamp(p.z, lo.z, hi.z)};
  return norm(p - q);
}

TEST(collisionSweepBounds, BallSweepTimeIsTheFirstTimeTheBallMeetsTheBox) {
  std::mt19937_64 rng(6);
  std::uniform_real_distribution<double> u(-1, 1);
  int meets = 0;
  for (int trial = 0; trial < 400; ++trial) {
    detail::BallSweep b;
    b.c0 = {20 * u(rng), 20 * u(rng), 20 * u(rng)};
    b.d = randomUnit(rng) * (30 * (1 + u(rng)));
    b.radius = 2 + 8 * (1 + u(rng));
    const Vec3 c{20 * u(rng), 20 * u(rng), 20 * u(rng)}, h{0.1 + 3 * (1 + u(rng)), 0.1 + 3 * (1 + u(rng)), 0.1 + 3 * (1 + u(rng))};
    const double t = detail::ballSweepTime(b, c - h, c + h, 1.0);
    constexpr int kSamples = 4000;
    double first = std::numeric_limits<double>::infinity();
    for (int k = 0; k <= kSamples; ++k) {
      const double s = double(k) / kSamples;
      if (boxDistance(b.c0 + b.d * s, c - h, c + h) <= b.radius) {
        first = s;
        break;
      }
    }
    if (std::isinf(first)) {
      // No sample meets: either none exists, or the contact is shorter than a sample step.
      if (!std::isinf(t)) {
        EXPECT_LE(boxDistance(b.c0 + b.d * t, c - h, c + h), b.radius * (1 + 1e-6)) << trial;
      }
      continue;
    }
    ++meets;
    EXPECT_LE(t, first) << "trial " << trial;                 // a lower bound
    EXPECT_GE(t, first - 1.0 / kSamples - 1e-6) << "trial " << trial;  // and exact up to the sampling
  }
  EXPECT_GT(meets, 50);
}

TEST(collisionSweepBounds, MovingBallHoldsTheTurningPoints) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int trial = 0; trial < 200; ++trial) {
    RigidTransform a, b;
    const Vec3 axis = randomUnit(rng);
    const double angle = (trial % 10 == 0 ? 80 : 10) * (1 + u(rng)) * 3.14159265358979 / 180;
    const detail::Mat3 rot = detail::rotationAbout(randomUnit(rng), 3 * u(rng)) , turn = detail::rotationAbout(axis, angle);
    const detail::Mat3 r1 = turn * rot;
    for (int i = 0; i < 9; ++i) {
      a.rotation[i] = rot.m[i];
      b.rotation[i] = r1.m[i];
    }
    a.translation = {10 * u(rng), 10 * u(rng), 10 * u(rng)};
    b.translation = a.translation + randomUnit(rng) * (5 * (1 + u(rng)));
    const detail::MotionPlan plan = detail::MotionPlan::between(a, b);
    const detail::SegmentMotion m = plan.segment(0);
    const Vec3 centre{0, 0, -30};
    const double radius = 30;
    const detail::BallSweep ball = detail::ballSweep(m, centre, radius);
    for (int k = 0; k < 200; ++k) {
      const Vec3 q = centre + randomUnit(rng) * (radius * std::abs(u(rng)));
      const double s = (k % 20) / 19.0;
      const Vec3 x = m.tipAt(s) + m.rotationAt(s) * q;
      ASSERT_LE(norm(x - (ball.c0 + ball.d * s)), ball.radius) << "trial " << trial << " s " << s;
    }
  }
}

// A 90-degree turn about z through the tip: the vertex at -45 degrees sweeps to +45 degrees, and its arc
// bulges out to x = r while both its ends (and so its chord's box) stay at x = r cos 45. It meets a bone
// triangle standing at x = 0.9 r in the bulge, at the angle where r cos = 0.9 r. The exact events skip a
// feature whose path box misses the bone's, so this contact is found only if the boxes hold the arc's sag.
detail::SegmentMotion quarterTurnAboutZ() {
  RigidTransform a, b;
  const detail::Mat3 turn = detail::rotationAbout(Vec3{0, 0, 1}, 0.5 * 3.14159265358979323846);
  for (int i = 0; i < 9; ++i) b.rotation[i] = turn.m[i];
  const detail::MotionPlan plan = detail::MotionPlan::between(a, b);
  EXPECT_EQ(plan.segments, 1);
  return plan.segment(0);
}

TEST(collisionSweepBounds, PairContactFollowsTheArcBeyondItsChord) {
  const detail::SegmentMotion m = quarterTurnAboutZ();
  const double r = 10, c45 = std::sqrt(0.5);
  // Reamer-local triangle (R0 = I, so q = p): one far vertex, two near the axis.
  const Vec3 p[3] = {{r * c45, -r * c45, 0}, {0.5, -0.2, 0.3}, {0.4, 0.1, -0.3}};
  const Vec3 q[3] = {p[0], p[1], p[2]};
  const BvhTriangle bone{{0.9 * r, -0.6 * r, -0.2 * r}, {0.9 * r, -0.2 * r, -0.2 * r}, {0.9 * r, -0.4 * r, 0.3 * r}};
  // The far vertex is at angle -45 + phi(s), phi(s) = 2 atan(s tau); it reaches x = 0.9 r at angle -acos(0.9).
  const double phiHit = 0.25 * 3.14159265358979323846 - std::acos(0.9);
  const double sHit = std::tan(0.5 * phiHit) / m.tau;
  for (const double smin : {0.0, 0.5 * sHit}) {
    const detail::PairContact c = detail::pairFirstContact(m, p, q, bone, 1.0, true, smin);
    ASSERT_TRUE(c.hit) << "smin " << smin;
    EXPECT_NEAR(c.s, sHit, 1e-9);
    EXPECT_EQ(c.feature, ContactFeature::ReamerVertexBoneFace);
    EXPECT_NEAR(c.point.x, 0.9 * r, 1e-9);
    EXPECT_NEAR(c.point.y, -r * std::sqrt(1 - 0.81), 1e-9);
  }
}

TEST(collisionSweepBounds, SweptTriangleBoxHoldsTheArcBeyondItsChord) {
  const detail::SegmentMotion m = quarterTurnAboutZ();
  const double r = 10, c45 = std::sqrt(0.5);
  const Vec3 q[3] = {{r * c45, -r * c45, 0}, {0.5, -0.2, 0.3}, {0.4, 0.1, -0.3}};
  Vec3 lo, hi;
  detail::sweptTriangleBox(m, m.turnAt(1.0), q, 1.0, lo, hi);
  for (int k = 0; k <= 200; ++k) {
    const double s = k / 200.0;
    for (const Vec3& v : q) {
      const Vec3 x = m.tipAt(s) + m.turnAt(s) * v;
      ASSERT_TRUE(x.x >= lo.x && x.y >= lo.y && x.z >= lo.z && x.x <= hi.x && x.y <= hi.y && x.z <= hi.z) << "s " << s;
    }
  }
  EXPECT_GE(hi.x, r);  // the bulge: beyond both ends' r cos 45
}

}  // namespace
}  // namespace reamsim
