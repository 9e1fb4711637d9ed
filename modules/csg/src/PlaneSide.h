#pragma once
// Internal: which side of a triangle's plane a point lies on, proven in plain doubles where the answer is
// clear, so that the exact triangle tests (TrianglePair.h, the cut's near test) can skip the pairs a plane
// separates without building CGAL objects. Most pairs those tests see are separated by a wide margin: faces
// of one surface side by side, or a bone face a few micrometres beside a reamer facet.
//
// The side of p is the sign of det(b − a, c − a, p − a). Computed as n · (p − a) with n = (b − a) × (c − a)
// in doubles, it differs from the exact determinant by less than 48 ε U W D (ε = 2⁻⁵³; U, W, D the largest
// absolute coordinates of b − a, c − a and p − a): each difference is off by ε relatively, each component
// of n by 4 ε U W, the dot product by 18 ε U W D, and the exact determinant of the rounded differences
// by 18 ε U W D from the true one. A side is reported only beyond 1e-13 U W D (18 times that bound);
// 0 means "not proven here", and the exact predicate decides.
#include <algorithm>
#include <cmath>

#include "reamsim/mesh/Vec3.h"

namespace reamsim::csg {

class PlaneSide {
 public:
  PlaneSide() = default;
  PlaneSide(const Vec3& a, const Vec3& b, const Vec3& c) : a_(a) {
    const Vec3 u = b - a, w = c - a;
    n_ = cross(u, w);
    scale_ = kRelativeBound * largest(u) * largest(w);
  }
  // +1 or −1 when p lies strictly on that side (the sign of det(b − a, c − a, p − a)), else 0.
  int side(const Vec3& p) const {
    const Vec3 d = p - a_;
    const double bound = scale_ * largest(d);
    // Tiny or subnormal magnitudes lose the relative error bound above; NaN fails every comparison.
    if (!(bound > kSmallest)) return 0;
    const double s = dot(n_, d);
    return s > bound ? 1 : s < -bound ? -1 : 0;
  }
  const Vec3& normal() const { return n_; }  // (b − a) × (c − a), in doubles
  // Whether the corners are proven not collinear: a component of the computed normal beyond the bound (the
  // exact normal of the rounded differences is within 8 ε U W of it, the true one as close again).
  bool proper() const { return largest(n_) > scale_; }
  // Whether every point lies strictly on one and the same side.
  template <class... P>
  bool separates(const P&... p) const {
    const int s[] = {side(p)...};
    for (int x : s)
      if (x == 0 || x != s[0]) return false;
    return true;
  }

 private:
  static double largest(const Vec3& v) { return std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)}); }
  static constexpr double kRelativeBound = 1e-13;
  static constexpr double kSmallest = 1e-200;
  Vec3 a_{}, n_{};
  double scale_ = 0;
};

}  // namespace reamsim::csg
