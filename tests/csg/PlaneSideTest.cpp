// The double-precision plane filter of the engine's triangle tests (src/PlaneSide.h) against CGAL's exact
// orientation: it may leave a point undecided but never names the wrong side, for points at every distance
// from the plane down to one ulp, on it, on degenerate (collinear) triangles and at large coordinates; and
// the triangle-pair test it filters (src/TrianglePair.h) gives the unfiltered answer on pairs that touch,
// cross, share corners and lie in one plane.
#include "PlaneSide.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "TrianglePair.h"

namespace reamsim {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
K::Point_3 kp(const Vec3& v) { return {v.x, v.y, v.z}; }
int exactSide(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& p) {
  return int(CGAL::orientation(kp(a), kp(b), kp(c), kp(p)));
}

Vec3 randomPoint(std::mt19937_64& rng, double centre, double spread) {
  std::uniform_real_distribution<double> u(-spread, spread);
  return {centre + u(rng), centre + u(rng), centre + u(rng)};
}

TEST(PlaneSide, NeverNamesTheWrongSideAndDecidesClearCases) {
  std::mt19937_64 rng(43);
  std::uniform_real_distribution<double> unit(0, 1);
  int decided = 0, clear = 0, wrong = 0, checked = 0;
  for (int i = 0; i < 200000; ++i) {
    // Bone-like coordinates (a millimetre triangle ~100 mm from the origin), sometimes far larger ones.
    const double centre = (i % 7 == 0) ? 1e6 : 100.0 * (unit(rng) - 0.5);
    const double size = (i % 5 == 0) ? 1e-4 : 1.0;
    const Vec3 a = randomPoint(rng, centre, size), b = randomPoint(rng, centre, size);
    Vec3 c = randomPoint(rng, centre, size);
    if (i % 11 == 0) c = a + (b - a) * unit(rng);  // collinear corners (rounded: nearly so, or exactly)
    const csg::PlaneSide plane(a, b, c);
    // A point on the plane (rounded), then moved off it by 0 to 10^-1 of the triangle's size.
    const double s = unit(rng), t = unit(rng) * (1 - s);
    const Vec3 n = normalized(cross(b - a, c - a));
    const double off = (i % 3 == 0) ? 0.0 : size * std::pow(10.0, -16.0 * unit(rng)) * (unit(rng) < 0.5 ? -1 : 1);
    const Vec3 p = a + (b - a) * s + (c - a) * t + n * off;
    const int got = plane.side(p), truth = exactSide(a, b, c, p);
    ++checked;
    if (got != 0) {
      ++decided;
      if (got != truth) ++wrong;
    }
    // Clearly off the plane (a thousandth of the triangle's size, a non-degenerate triangle): decided.
    if (std::abs(off) > 1e-3 * size && norm(cross(b - a, c - a)) > 1e-3 * size * size && centre < 1e3) {
      ++clear;
      EXPECT_EQ(got, truth) << "i = " << i;
    }
  }
  EXPECT_EQ(wrong, 0);
  EXPECT_GT(clear, 10000);
  EXPECT_GT(decided, checked / 2);
}

TEST(PlaneSide, ProperOnlyForTrianglesWhoseCornersAreNotCollinear) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> unit(0, 1);
  int proper = 0;
  for (int i = 0; i < 100000; ++i) {
    const double size = (i % 5 == 0) ? 1e-5 : 1.0;
    const Vec3 a = randomPoint(rng, 100.0 * (unit(rng) - 0.5), size);
    Vec3 b = randomPoint(rng, 0.0, size) + a, c = randomPoint(rng, 0.0, size) + a;
    // Collinear to rounding, exactly collinear (on a line along x), nearly collinear, or a random triangle.
    if (i % 4 == 0) c = a + (b - a) * (3 * unit(rng) - 1);
    if (i % 4 == 1) b = Vec3{a.x - size * unit(rng), a.y, a.z}, c = Vec3{a.x + size * unit(rng), a.y, a.z};
    if (i % 4 == 2) c = a + (b - a) * unit(rng) + Vec3{1e-12, -1e-12, 1e-12} * size * unit(rng);
    const bool got = csg::PlaneSide(a, b, c).proper();
    if (got) {
      ++proper;
      EXPECT_FALSE(CGAL::collinear(kp(a), kp(b), kp(c))) << "i = " << i;
    }
    if (i % 4 == 3) {
      EXPECT_TRUE(got) << "a random triangle is proven proper, i = " << i;
    }
  }
  EXPECT_GT(proper, 25000);
}

TEST(PlaneSide, SeparatesNeedsEveryPointStrictlyOnOneSide) {
  const Vec3 a{0, 0, 0}, b{1, 0, 0}, c{0, 1, 0};
  const csg::PlaneSide plane(a, b, c);
  EXPECT_TRUE(plane.separates(Vec3{0, 0, 1}, Vec3{5, 5, 2}, Vec3{-3, 1, 1e-9}));
  EXPECT_TRUE(plane.separates(Vec3{0, 0, -1}, Vec3{5, 5, -2}));
  EXPECT_FALSE(plane.separates(Vec3{0, 0, 1}, Vec3{5, 5, -2}));
  EXPECT_FALSE(plane.separates(Vec3{0, 0, 1}, Vec3{5, 5, 0}));  // one on the plane
  EXPECT_EQ(plane.side(Vec3{0.3, 0.3, 0}), 0);
  const double nan = std::nan("");
  EXPECT_EQ(plane.side(Vec3{nan, 0, 1}), 0);
  EXPECT_EQ(csg::PlaneSide(a, b, Vec3{2, 0, 0}).side(Vec3{0, 0, 1}), 0);  // a degenerate triangle decides nothing
}

TEST(PlaneSide, FilteredPairTestAgreesWithCgalAlone) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> unit(0, 1);
  int meeting = 0, apart = 0;
  for (int i = 0; i < 60000; ++i) {
    // Six points: triangle s = (0, 1, 2); t reuses 0, 1 or 2 of s's corners.
    std::vector<Vec3> v(6);
    for (int k = 0; k < 3; ++k) v[k] = randomPoint(rng, 50.0, 1.0);
    const Vec3 n = normalized(cross(v[1] - v[0], v[2] - v[0]));
    for (int k = 3; k < 6; ++k) {
      // Near s: in its plane, a rounding off it, micrometres off it, or anywhere near.
      const double s = unit(rng), t = unit(rng);
      const Vec3 inPlane = v[0] + (v[1] - v[0]) * (1.5 * s - 0.25) + (v[2] - v[0]) * (1.5 * t - 0.25);
      switch (i % 4) {
        case 0: v[k] = inPlane; break;
        case 1: v[k] = inPlane + n * (1e-15 * (unit(rng) - 0.5)); break;
        case 2: v[k] = inPlane + n * (1e-3 * (unit(rng) - 0.5)); break;
        default: v[k] = randomPoint(rng, 50.0, 1.0);
      }
    }
    if (i % 13 == 0) v[4] = v[0] + (v[1] - v[0]) * 0.5;  // a corner on s's edge
    const std::array<std::uint32_t, 3> s{0, 1, 2};
    const int share = i % 3;  // t shares 0, 1 or 2 corners with s
    std::array<std::uint32_t, 3> t = share == 0 ? std::array<std::uint32_t, 3>{3, 4, 5}
                                     : share == 1 ? std::array<std::uint32_t, 3>{0, 4, 5}
                                                  : std::array<std::uint32_t, 3>{1, 0, 5};
    // CGAL's predicates alone (the test without the plane filter) against the filtered test.
    const auto at = [&](std::uint32_t k) { return kp(v[k]); };
    const bool want = csg::trianglesIntersectBeyondShared<K, false>(s, t, at);
    const bool got = csg::trianglesIntersectBeyondShared<K>(s, t, at);
    ASSERT_EQ(got, want) << "pair " << i;
    (want ? meeting : apart)++;
  }
  EXPECT_GT(meeting, 5000);
  EXPECT_GT(apart, 5000);
}

}  // namespace
}  // namespace reamsim
