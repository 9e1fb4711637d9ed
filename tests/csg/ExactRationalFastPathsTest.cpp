// The integer fast paths of the engine's exact arithmetic (src/ExactRationalFastPaths.h) against CGAL's own
// computations over mpq_class: the sign of a 3×3 determinant (random entries with random denominators,
// singular matrices: a row a rational combination of the others, as for the collinear points of the
// corefinement's face triangulation; exact orientation tests on constructed Epeck points), the projected
// orientation of that triangulation (against the determinant expanded over canonical rationals), the
// interval kept beside an exact value (against MPFR's), and the
// intersection of a plane and a line (doubles of any magnitude, coplanar and axis-aligned inputs, rational
// inputs that take CGAL's own way, and Epeck's lazy construction).
#include "ExactRationalFastPaths.h"

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace reamsim {
namespace {

mpq_class randomRational(std::mt19937_64& rng) {
  std::uniform_int_distribution<long> num(-1000000007L, 1000000007L);
  std::uniform_int_distribution<long> den(1, 4);
  mpq_class q(num(rng), den(rng) == 1 ? 1 : std::uniform_int_distribution<long>(1, 99991)(rng));
  q.canonicalize();
  if (rng() % 3 == 0) q /= mpq_class(1L << (rng() % 40));  // power-of-two denominators, as from doubles
  return q;
}

CGAL::Sign genericSign(const mpq_class (&m)[9]) {
  return CGAL::sign(CGAL::determinant(m[0], m[1], m[2], m[3], m[4], m[5], m[6], m[7], m[8]));
}
CGAL::Sign integerSign(const mpq_class (&m)[9]) {
  return CGAL::sign_of_determinant(m[0], m[1], m[2], m[3], m[4], m[5], m[6], m[7], m[8]);
}

TEST(ExactRationalFastPaths, AgreesWithTheRationalDeterminant) {
  std::mt19937_64 rng(5);
  int zeros = 0;
  for (int i = 0; i < 20000; ++i) {
    mpq_class m[9];
    for (mpq_class& x : m) x = rng() % 7 == 0 ? mpq_class(0) : randomRational(rng);
    if (i % 2 == 1) {  // singular: the last row is a rational combination of the first two
      const mpq_class a = randomRational(rng), b = randomRational(rng);
      for (int c = 0; c < 3; ++c) m[6 + c] = a * m[c] + b * m[3 + c];
    }
    const CGAL::Sign expected = genericSign(m);
    zeros += expected == CGAL::ZERO;
    ASSERT_EQ(integerSign(m), expected) << "matrix " << i;
  }
  EXPECT_GE(zeros, 10000);  // every singular one, and they are seen as such
}

// Points on the segment pq (constructed exactly) are collinear with p and q: orientation 0 against any
// fourth point, and a point off the plane gives the sign of the side it is on.
TEST(ExactRationalFastPaths, ExactOrientationOfConstructedPoints) {
  using K = CGAL::Exact_predicates_exact_constructions_kernel;
  std::mt19937_64 rng(6);
  std::uniform_real_distribution<double> u(-50, 50);
  for (int i = 0; i < 2000; ++i) {
    const K::Point_3 p(u(rng), u(rng), u(rng)), q(u(rng), u(rng), u(rng)), r(u(rng), u(rng), u(rng));
    const K::Point_3 onPq = p + (q - p) * K::FT(1.0 / 3.0) + (q - p) * K::FT(0.1);
    const K::Point_3 inPlane = CGAL::midpoint(onPq, r);
    EXPECT_EQ(CGAL::orientation(p, q, r, inPlane), CGAL::COPLANAR);
    EXPECT_EQ(CGAL::orientation(p, q, onPq, r), CGAL::COPLANAR);
    const K::Vector_3 n = CGAL::cross_product(q - p, r - p);
    EXPECT_EQ(CGAL::orientation(p, q, r, inPlane + n), CGAL::orientation(p, q, r, p + n));
    EXPECT_EQ(CGAL::orientation(q - p, onPq - p, n), CGAL::ZERO);
  }
}

// The face triangulation's projected orientation (unreduced differences) against the determinant expanded
// over canonical rationals: random rational points, points of one dyadic scale (equal denominators), and
// collinear triples (a point on the segment of the other two, exactly).
TEST(ExactRationalFastPaths, ProjectedOrientationAgreesWithTheRationalDeterminant) {
  using SK3 = CGAL::Simple_cartesian<mpq_class>;
  using Traits = CGAL::Projection_traits_base_3<SK3>;
  std::mt19937_64 rng(9);
  int zeros = 0;
  for (int i = 0; i < 20000; ++i) {
    SK3::Point_3 pt[3];
    for (SK3::Point_3& q : pt) {
      if (i % 3 == 0) {  // one dyadic scale: doubles
        std::uniform_real_distribution<double> u(-50, 50);
        q = SK3::Point_3(mpq_class(u(rng)), mpq_class(u(rng)), mpq_class(u(rng)));
      } else {
        q = SK3::Point_3(randomRational(rng), randomRational(rng), randomRational(rng));
      }
    }
    if (i % 4 == 1) {  // r on the segment pq
      const mpq_class t = randomRational(rng) / mpq_class(2000000000);
      pt[2] = pt[0] + (pt[1] - pt[0]) * t;
    }
    const SK3::Vector_3 n(randomRational(rng), randomRational(rng), randomRational(rng));
    const SK3::Vector_3 u = pt[1] - pt[0], v = pt[2] - pt[0];
    const mpq_class det = u.x() * (v.y() * n.z() - v.z() * n.y()) - u.y() * (v.x() * n.z() - v.z() * n.x()) +
                          u.z() * (v.x() * n.y() - v.y() * n.x());
    const CGAL::Sign expected = CGAL::sign(det);
    zeros += expected == CGAL::ZERO;
    const CGAL::TriangulationProjectionTraitsCartesianFunctors::Projected_orientation_with_normal_3<Traits> orient(n);
    ASSERT_EQ(orient(pt[0], pt[1], pt[2]), expected) << "case " << i;
  }
  EXPECT_GE(zeros, 5000);  // every collinear triple
}

// The interval kept beside an exact value holds it, is at most one ulp wide, and is the value itself when
// the value is a double (the interval CGAL's MPFR conversion gives then).
TEST(ExactRationalFastPaths, IntervalOfAnExactValueHoldsItWithinAnUlp) {
  std::mt19937_64 rng(10);
  std::uniform_real_distribution<double> u(-50, 50);
  const CGAL::NT_converter<mpq_class, CGAL::Interval_nt<false>> toInterval;
  int points = 0;
  for (int i = 0; i < 20000; ++i) {
    mpq_class a;
    switch (i % 4) {
      case 0: a = randomRational(rng); break;
      case 1: a = mpq_class(u(rng)); break;                             // a double
      case 2: a = mpq_class(u(rng)) / mpq_class(3 + long(rng() % 97)); break;  // near a double, not one
      default: a = mpq_class(std::ldexp(u(rng), int(rng() % 600) - 300)) + mpq_class(1, 1L << 62); break;
    }
    const CGAL::Interval_nt<false> got = toInterval(a);
    ASSERT_LE(mpq_class(got.inf()), a) << a;
    ASSERT_GE(mpq_class(got.sup()), a) << a;
    ASSERT_LE(got.sup(), std::nextafter(got.inf(), std::numeric_limits<double>::infinity())) << a;
    const CGAL::Interval_nt<false> cgal = CGAL::to_interval(a);
    if (cgal.is_point()) {
      ASSERT_TRUE(got.is_point()) << a;
      ASSERT_EQ(got.inf(), cgal.inf());
      ++points;
    }
  }
  EXPECT_GE(points, 5000);  // the doubles
}

// CGAL's own plane–line intersection, not through the specialised functor.
using SK = CGAL::Simple_cartesian<mpq_class>;
SK::Point_3 referenceIntersection(const SK::Point_3& p1, const SK::Point_3& p2, const SK::Point_3& p3,
                                  const SK::Point_3& l1, const SK::Point_3& l2) {
  const auto res = CGAL::intersection(SK::Plane_3(p1, p2, p3), SK::Line_3(l1, l2));
  const SK::Point_3* p = res ? boost::get<SK::Point_3>(&*res) : nullptr;
  EXPECT_NE(p, nullptr);
  return p ? *p : SK::Point_3();
}

SK::Point_3 fromDoubles(double x, double y, double z) { return {mpq_class(x), mpq_class(y), mpq_class(z)}; }

TEST(ExactRationalFastPaths, PlaneLineIntersectionEqualsCgalsOwn) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-60, 60);
  std::uniform_int_distribution<int> scale(-30, 30);
  const SK::Construct_plane_line_intersection_point_3 fast;
  int dyadicCases = 0, rationalCases = 0;
  for (int i = 0; i < 20000; ++i) {
    SK::Point_3 p[5];
    const int kind = i % 5;
    for (SK::Point_3& q : p) {
      if (kind == 1) {  // magnitudes from 1e-9 to 1e9 in one call
        q = fromDoubles(std::ldexp(u(rng), scale(rng)), std::ldexp(u(rng), scale(rng)), std::ldexp(u(rng), scale(rng)));
      } else if (kind == 2) {  // axis-aligned: repeated coordinates, integers
        q = fromDoubles(std::round(u(rng) / 20), std::round(u(rng) / 20), std::round(u(rng) / 20));
      } else {
        q = fromDoubles(u(rng), u(rng), u(rng));
      }
    }
    if (kind == 3) p[4] = SK::Point_3(p[0].x() + (p[1].x() - p[0].x()) / 3, p[0].y() + (p[1].y() - p[0].y()) / 3,
                                      p[0].z() + (p[1].z() - p[0].z()) / 3);  // l2 a rational point in the plane
    if (kind == 4) p[3] = CGAL::midpoint(p[1], p[2]);  // l1 in the plane, on an edge: dyadic
    const SK::Vector_3 n = CGAL::cross_product(p[1] - p[0], p[2] - p[0]);
    if (n == CGAL::NULL_VECTOR || n * (p[4] - p[3]) == 0) continue;  // no single point: never asked
    const SK::Point_3 expected = referenceIntersection(p[0], p[1], p[2], p[3], p[4]);
    ASSERT_EQ(fast(p[0], p[1], p[2], p[3], p[4]), expected) << "case " << i;
    (kind == 3 ? rationalCases : dyadicCases)++;
  }
  EXPECT_GT(dyadicCases, 15000);
  EXPECT_GT(rationalCases, 3000);
}

// Through Epeck: a lazy intersection point, forced to its exact value, is CGAL's exact point; and a point
// built on an earlier exact point (not dyadic) agrees too.
TEST(ExactRationalFastPaths, LazyIntersectionPointsAreExact) {
  using K = CGAL::Exact_predicates_exact_constructions_kernel;
  std::mt19937_64 rng(8);
  std::uniform_real_distribution<double> u(-50, 50);
  const K::Construct_plane_line_intersection_point_3 construct;
  for (int i = 0; i < 2000; ++i) {
    K::Point_3 p[5];
    for (K::Point_3& q : p) q = K::Point_3(u(rng), u(rng), u(rng));
    if (CGAL::collinear(p[0], p[1], p[2]) ||
        CGAL::orientation(p[0], p[1], p[2], p[3]) == CGAL::orientation(p[0], p[1], p[2], p[4]))
      continue;  // the segment must cross the plane
    const K::Point_3 x = construct(p[0], p[1], p[2], p[3], p[4]);
    const auto e = [](const K::Point_3& q) { return CGAL::exact(q); };
    EXPECT_EQ(CGAL::exact(x), referenceIntersection(e(p[0]), e(p[1]), e(p[2]), e(p[3]), e(p[4])));
    EXPECT_EQ(CGAL::orientation(p[0], p[1], p[2], x), CGAL::COPLANAR);
    // a second plane through the exact (rational) point
    const K::Point_3 q = p[1] + (p[2] - p[0]);
    if (CGAL::collinear(x, p[3], q) || CGAL::orientation(x, p[3], q, p[0]) == CGAL::orientation(x, p[3], q, p[4]))
      continue;
    const K::Point_3 y = construct(x, p[3], q, p[0], p[4]);
    EXPECT_EQ(CGAL::exact(y), referenceIntersection(e(x), e(p[3]), e(q), e(p[0]), e(p[4])));
  }
}

}  // namespace
}  // namespace reamsim
