#pragma once
// Internal: roots of a cubic on [0, smax] in increasing order, to rounding. The interval is cut at the
// critical points into monotone pieces; a sign change is bracketed down to adjacent doubles; a value within the tolerance at a piece
// end (a tangential touch or a root at the end) is a root too.
#include <algorithm>
#include <cmath>

namespace reamsim::detail {

enum class RootScan { Found, None, Degenerate };

// f(s) = c[0] + c[1] s + c[2] s^2 + c[3] s^3. `reference` is the magnitude f would have without
// cancellation (product of the input lengths): when every coefficient is below kDegenerate x reference the
// polynomial is identically zero up to rounding. accept(s) decides whether a root is a real contact; the
// first accepted root is returned in sOut.
template <class Accept>
RootScan earliestRoot(const double (&c)[4], double smax, double reference, Accept&& accept, double& sOut) {
  constexpr double kDegenerate = 1e-11;
  constexpr double kZero = 1e-13;
  const double scale = std::max({std::abs(c[0]), std::abs(c[1]), std::abs(c[2]), std::abs(c[3])});
  if (!(scale > kDegenerate * reference)) return RootScan::Degenerate;
  const double a0 = c[0] / scale, a1 = c[1] / scale, a2 = c[2] / scale, a3 = c[3] / scale;
  auto f = [&](double s) { return ((a3 * s + a2) * s + a1) * s + a0; };
  // Quick reject: |f(0)| exceeds what the other terms can take away on [0, smax].
  if (std::abs(a0) > kZero + (std::abs(a1) + (std::abs(a2) + std::abs(a3) * smax) * smax) * smax * (1 + 1e-12))
    return RootScan::None;
  double pts[4];
  int n = 0;
  pts[n++] = 0;
  {
    // f'(s) = 3 a3 s^2 + 2 a2 s + a1
    const double A = 3 * a3, B = 2 * a2, C = a1;
    double r1 = -1, r2 = -1;
    if (std::abs(A) > 1e-300) {
      const double disc = B * B - 4 * A * C;
      if (disc >= 0) {
        const double q = -0.5 * (B + std::copysign(std::sqrt(disc), B));
        r1 = q / A;
        r2 = q != 0 ? C / q : r1;
      }
    } else if (std::abs(B) > 1e-300) {
      r1 = -C / B;
    }
    if (r1 > r2) std::swap(r1, r2);
    if (r1 > 0 && r1 < smax) pts[n++] = r1;
    if (r2 > 0 && r2 < smax && r2 != r1) pts[n++] = r2;
  }
  pts[n++] = smax;
  double prev = f(pts[0]);
  if (std::abs(prev) <= kZero && accept(pts[0])) { sOut = pts[0]; return RootScan::Found; }
  for (int i = 1; i < n; ++i) {
    double lo = pts[i - 1], hi = pts[i];
    const double fhi = f(hi);
    if (std::abs(prev) > kZero && std::abs(fhi) > kZero && (prev < 0) != (fhi < 0)) {
      // Illinois false position (superlinear), with a bisection every third step so the bracket always at
      // least halves; it ends, like plain bisection, at two adjacent doubles around the sign change.
      double flo = prev, fh = fhi;
      int side = 0;
      for (int it = 0; it < 300; ++it) {
        double mid = it % 3 == 2 ? 0.5 * (lo + hi) : (lo * fh - hi * flo) / (fh - flo);
        if (!(mid > lo && mid < hi)) {
          mid = 0.5 * (lo + hi);
          if (!(mid > lo && mid < hi)) break;
        }
        const double fm = f(mid);
        if (fm == 0) { lo = hi = mid; break; }
        if ((fm < 0) == (flo < 0)) {
          lo = mid;
          flo = fm;
          if (side == -1) fh *= 0.5;
          side = -1;
        } else {
          hi = mid;
          fh = fm;
          if (side == 1) flo *= 0.5;
          side = 1;
        }
      }
      // The contact time is the earliest: take the lower end (the crossing lies in [lo, hi]).
      if (accept(lo)) { sOut = lo; return RootScan::Found; }
      if (hi != lo && accept(hi)) { sOut = hi; return RootScan::Found; }
    }
    if (std::abs(fhi) <= kZero && accept(pts[i])) { sOut = pts[i]; return RootScan::Found; }
    prev = fhi;
  }
  return RootScan::None;
}

}  // namespace reamsim::detail
