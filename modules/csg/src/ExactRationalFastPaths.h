#pragma once
// Four of CGAL's exact (mpq_class) computations done over integers, without a gcd after every operation.
// Epeck's exact number type here is mpq_class, and its lazy values are only evaluated exactly where the
// interval filter cannot decide. In the corefinement that happens for nearly every intersection point:
// each split face is triangulated in projection, and points on a face edge, or on the trace of an earlier
// cut's planar facet, are collinear or nearly so. A profile of `bench cut` at 400k faces put most of that
// exact work in GMP's gcd (mpq_class canonicalises after every product and difference):
//   - the sign of a 3×3 determinant (every exact orientation test),
//   - the projected orientation of the face triangulation (the differences of its points unreduced),
//   - the interval kept beside each exact value (GMP's truncation instead of MPFR), and
//   - the intersection point of a face's plane with an edge's line (every intersection point evaluated
//     exactly, about three quarters of the exact fallbacks' time before this fast path).
// Both are specialisations for mpq_class / Simple_cartesian<mpq_class>: include this header first in every
// unit of this module that uses a CGAL kernel, so that all of them see the same definitions. The results
// are the same exact values (tests/csg/ExactRationalFastPathsTest.cpp checks them against CGAL's generic
// code), so a CGAL unit of another module (mesh repair, CT import: Epick only) that instantiates CGAL's own
// version for its exact fallbacks computes the same thing, whichever definition the linker keeps.
#include <CGAL/Kernel/function_objects.h>
#include <algorithm>
#include <cmath>
#include <limits>
#include <CGAL/Interval_nt.h>
#include <CGAL/NT_converter.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/gmpxx.h>
#include <CGAL/predicates/sign_of_determinant.h>
#include <CGAL/Kernel_23/internal/Projection_traits_base_3.h>

namespace CGAL {
namespace reamsim_exact {

// The sign of a 3×3 determinant whose entries are num[i] / den[i] with den[i] > 0, not necessarily in
// lowest terms. Each row is scaled by the product of its distinct denominators (positive: the sign is kept),
// which leaves integers; no gcd is taken.
inline Sign signOfFractionDeterminant(const mpz_srcptr (&num)[9], const mpz_srcptr (&den)[9]) {
  // Reused between calls: mpz values keep their limbs, so a call allocates nothing once warm.
  thread_local struct Scratch {
    mpz_class n[9], m0, m1, m2, det;
  } s;
  for (int row = 0; row < 3; ++row) {
    mpz_srcptr distinct[3];
    int count = 0;
    for (int col = 0; col < 3; ++col) {
      mpz_srcptr d = den[3 * row + col];
      if (mpz_cmp_ui(d, 1) == 0) continue;
      bool seen = false;
      for (int j = 0; j < count && !seen; ++j) seen = mpz_cmp(distinct[j], d) == 0;
      if (!seen) distinct[count++] = d;
    }
    for (int col = 0; col < 3; ++col) {
      // numerator × the row's distinct denominators other than its own
      mpz_ptr out = s.n[3 * row + col].get_mpz_t();
      mpz_set(out, num[3 * row + col]);
      for (int j = 0; j < count; ++j)
        if (mpz_cmp(distinct[j], den[3 * row + col]) != 0) mpz_mul(out, out, distinct[j]);
    }
  }
  mpz_class* n = s.n;
  // Expansion along the first row.
  mpz_mul(s.m0.get_mpz_t(), n[4].get_mpz_t(), n[8].get_mpz_t());
  mpz_submul(s.m0.get_mpz_t(), n[5].get_mpz_t(), n[7].get_mpz_t());
  mpz_mul(s.m1.get_mpz_t(), n[3].get_mpz_t(), n[8].get_mpz_t());
  mpz_submul(s.m1.get_mpz_t(), n[5].get_mpz_t(), n[6].get_mpz_t());
  mpz_mul(s.m2.get_mpz_t(), n[3].get_mpz_t(), n[7].get_mpz_t());
  mpz_submul(s.m2.get_mpz_t(), n[4].get_mpz_t(), n[6].get_mpz_t());
  mpz_mul(s.det.get_mpz_t(), n[0].get_mpz_t(), s.m0.get_mpz_t());
  mpz_submul(s.det.get_mpz_t(), n[1].get_mpz_t(), s.m1.get_mpz_t());
  mpz_addmul(s.det.get_mpz_t(), n[2].get_mpz_t(), s.m2.get_mpz_t());
  const int sign = mpz_sgn(s.det.get_mpz_t());
  return sign > 0 ? POSITIVE : (sign < 0 ? NEGATIVE : ZERO);
}

}  // namespace reamsim_exact

template <>
inline Sgn<mpq_class>::result_type sign_of_determinant<mpq_class>(const mpq_class& a00, const mpq_class& a01,
                                                                  const mpq_class& a02, const mpq_class& a10,
                                                                  const mpq_class& a11, const mpq_class& a12,
                                                                  const mpq_class& a20, const mpq_class& a21,
                                                                  const mpq_class& a22) {
  const mpq_class* a[9] = {&a00, &a01, &a02, &a10, &a11, &a12, &a20, &a21, &a22};
  mpz_srcptr num[9], den[9];
  for (int i = 0; i < 9; ++i) {
    num[i] = a[i]->get_num_mpz_t();
    den[i] = a[i]->get_den_mpz_t();
  }
  return reamsim_exact::signOfFractionDeterminant(num, den);
}

// The interval of an exact value, which Epeck stores beside every lazy value it evaluates exactly. CGAL
// converts through MPFR (an exact division and rounding per coordinate); GMP's mpq_get_d truncates toward
// zero, which with the next double away from zero brackets the value (one ulp wide), and is the value
// itself when the fraction is a double. Values outside [1e-290, 1e290] in magnitude take CGAL's way.
template <>
struct NT_converter<mpq_class, Interval_nt<false>> : public CGAL::cpp98::unary_function<mpq_class, Interval_nt<false>> {
  Interval_nt<false> operator()(const mpq_class& a) const {
    const int sign = mpq_sgn(a.get_mpq_t());
    if (sign == 0) return Interval_nt<false>(0.0);
    const double d = mpq_get_d(a.get_mpq_t());
    const double magnitude = std::abs(d);
    if (!(magnitude >= 1e-290 && magnitude <= 1e290)) return CGAL::to_interval(a);
    mpz_srcptr num = a.get_num_mpz_t(), den = a.get_den_mpz_t();
    const bool denPowerOfTwo = mpz_scan1(den, 0) + 1 == mpz_sizeinbase(den, 2);
    if (denPowerOfTwo && mpz_sizeinbase(num, 2) - mpz_scan1(num, 0) <= 53) return Interval_nt<false>(d);
    const double away = std::nextafter(d, sign > 0 ? std::numeric_limits<double>::infinity()
                                                   : -std::numeric_limits<double>::infinity());
    return sign > 0 ? Interval_nt<false>(d, away) : Interval_nt<false>(away, d);
  }
};

namespace TriangulationProjectionTraitsCartesianFunctors {

// The orientation of p, q, r seen along the face normal: the sign of det(q − p, r − p, n), the test the
// corefinement's face triangulation falls back to most (points on a face edge or on the trace of an
// earlier cut's facet are collinear or nearly so). CGAL forms q − p and r − p as canonical rationals, a gcd
// per coordinate; here each difference stays an unreduced fraction (one subtraction when both
// denominators are equal, as for points of one dyadic scale), then the integer determinant above.
template <>
inline Sign Projected_orientation_with_normal_3<Projection_traits_base_3<Simple_cartesian<mpq_class>>>::operator()(
    const Point& p, const Point& q, const Point& r) const {
  thread_local struct Scratch {
    mpz_class num[6], den[6];
  } s;
  mpz_srcptr num[9], den[9];
  const Point* rows[2] = {&q, &r};
  for (int row = 0; row < 2; ++row)
    for (int i = 0; i < 3; ++i) {
      const int k = 3 * row + i;
      const mpq_class& a = rows[row]->cartesian(i);
      const mpq_class& b = p.cartesian(i);
      mpz_srcptr da = a.get_den_mpz_t();
      mpz_srcptr db = b.get_den_mpz_t();
      mpz_ptr n = s.num[k].get_mpz_t();
      if (mpz_cmp(da, db) == 0) {
        mpz_sub(n, a.get_num_mpz_t(), b.get_num_mpz_t());
        den[k] = da;
      } else {
        mpz_mul(n, a.get_num_mpz_t(), db);
        mpz_submul(n, b.get_num_mpz_t(), da);
        mpz_mul(s.den[k].get_mpz_t(), da, db);
        den[k] = s.den[k].get_mpz_t();
      }
      num[k] = n;
    }
  for (int i = 0; i < 3; ++i) {
    num[6 + i] = normal.cartesian(i).get_num_mpz_t();
    den[6 + i] = normal.cartesian(i).get_den_mpz_t();
  }
  return reamsim_exact::signOfFractionDeterminant(num, den);
}

}  // namespace TriangulationProjectionTraitsCartesianFunctors

namespace CommonKernelFunctors {

// The point where the line l1 l2 meets the plane p1 p2 p3. When every coordinate is a dyadic rational (a
// double, or a sum of doubles' products: the bone's rounded vertices and the tool's), all of them are
// integers over one power of two, 2^E; then with integer vectors P, L and n = (P2 − P1) × (P3 − P1),
//   x = (L1 · den + num · (L2 − L1)) / (den · 2^E),  num = n · (P1 − L1),  den = n · (L2 − L1),
// one canonicalisation per coordinate. Other inputs, and a line parallel to the plane, take CGAL's own way.
template <>
class Construct_plane_line_intersection_point_3<Simple_cartesian<mpq_class>> {
  using K = Simple_cartesian<mpq_class>;
  using Point = K::Point_3;

 public:
  using result_type = Point;

  Point operator()(const Point& p1, const Point& p2, const Point& p3, const Point& l1, const Point& l2) const {
    Point out;
    if (dyadic(p1, p2, p3, l1, l2, out)) return out;
    return generic(K::Construct_plane_3()(p1, p2, p3), l1, l2);
  }

  Point operator()(const K::Plane_3& plane, const Point& l1, const Point& l2) const {
    return generic(plane, l1, l2);
  }

 private:
  static Point generic(const K::Plane_3& plane, const Point& l1, const Point& l2) {
    const auto res = K::Intersect_3()(plane, K::Construct_line_3()(l1, l2));
    CGAL_assertion(res != boost::none);
    const Point* e_pt = boost::get<Point>(&(*res));
    CGAL_assertion(e_pt != nullptr);
    return *e_pt;
  }

  static bool dyadic(const Point& p1, const Point& p2, const Point& p3, const Point& l1, const Point& l2,
                     Point& out) {
    thread_local struct Scratch {
      mpz_class v[15], a[3], b[3], n[3], w[3], num, den, t;
    } s;
    const Point* pts[5] = {&p1, &p2, &p3, &l1, &l2};
    // The largest power of two among the denominators; give up on any other denominator.
    mp_bitcnt_t e = 0;
    for (const Point* p : pts)
      for (int i = 0; i < 3; ++i) {
        mpz_srcptr d = p->cartesian(i).get_den_mpz_t();
        const mp_bitcnt_t low = mpz_scan1(d, 0);
        if (low + 1 != mpz_sizeinbase(d, 2)) return false;  // not a power of two
        e = std::max(e, low);
      }
    for (int k = 0; k < 5; ++k)
      for (int i = 0; i < 3; ++i) {
        const mpq_class& c = pts[k]->cartesian(i);
        mpz_mul_2exp(s.v[3 * k + i].get_mpz_t(), c.get_num_mpz_t(), e - mpz_scan1(c.get_den_mpz_t(), 0));
      }
    const mpz_class *P1 = s.v, *P2 = s.v + 3, *P3 = s.v + 6, *L1 = s.v + 9, *L2 = s.v + 12;
    for (int i = 0; i < 3; ++i) {
      mpz_sub(s.a[i].get_mpz_t(), P2[i].get_mpz_t(), P1[i].get_mpz_t());
      mpz_sub(s.b[i].get_mpz_t(), P3[i].get_mpz_t(), P1[i].get_mpz_t());
    }
    for (int i = 0; i < 3; ++i) {  // n = a × b
      const int j = (i + 1) % 3, k = (i + 2) % 3;
      mpz_mul(s.n[i].get_mpz_t(), s.a[j].get_mpz_t(), s.b[k].get_mpz_t());
      mpz_submul(s.n[i].get_mpz_t(), s.a[k].get_mpz_t(), s.b[j].get_mpz_t());
    }
    mpz_set_ui(s.num.get_mpz_t(), 0);
    mpz_set_ui(s.den.get_mpz_t(), 0);
    for (int i = 0; i < 3; ++i) {
      mpz_sub(s.t.get_mpz_t(), P1[i].get_mpz_t(), L1[i].get_mpz_t());
      mpz_addmul(s.num.get_mpz_t(), s.n[i].get_mpz_t(), s.t.get_mpz_t());
      mpz_sub(s.w[i].get_mpz_t(), L2[i].get_mpz_t(), L1[i].get_mpz_t());
      mpz_addmul(s.den.get_mpz_t(), s.n[i].get_mpz_t(), s.w[i].get_mpz_t());
    }
    if (mpz_sgn(s.den.get_mpz_t()) == 0) return false;
    mpq_class x[3];
    for (int i = 0; i < 3; ++i) {
      mpz_ptr xn = mpq_numref(x[i].get_mpq_t());
      mpz_mul(xn, L1[i].get_mpz_t(), s.den.get_mpz_t());
      mpz_addmul(xn, s.num.get_mpz_t(), s.w[i].get_mpz_t());
      mpz_mul_2exp(mpq_denref(x[i].get_mpq_t()), s.den.get_mpz_t(), e);
      mpq_canonicalize(x[i].get_mpq_t());  // also makes the denominator positive
    }
    out = Point(x[0], x[1], x[2]);
    return true;
  }
};

}  // namespace CommonKernelFunctors
}  // namespace CGAL
