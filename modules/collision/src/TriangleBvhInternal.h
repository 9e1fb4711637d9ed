#pragma once
// Internal to the BVH's translation units (TriangleBvh*.cpp): box arithmetic and the build's triangle
// reference.
#include <limits>

#include "reamsim/collision/TriangleBvh.h"

namespace reamsim::bvh_detail {

inline double area(const Vec3& lo, const Vec3& hi) {
  const Vec3 d = hi - lo;
  if (d.x < 0 || d.y < 0 || d.z < 0) return 0;
  return 2 * (d.x * d.y + d.y * d.z + d.z * d.x);
}
// Written as plain selects so the compiler emits branch-free min/max (the binning loop mispredicted).
inline double mn(double a, double b) { return b < a ? b : a; }
inline double mx(double a, double b) { return a < b ? b : a; }
inline void grow(Vec3& lo, Vec3& hi, const Vec3& plo, const Vec3& phi) {
  lo.x = mn(lo.x, plo.x);
  lo.y = mn(lo.y, plo.y);
  lo.z = mn(lo.z, plo.z);
  hi.x = mx(hi.x, phi.x);
  hi.y = mx(hi.y, phi.y);
  hi.z = mx(hi.z, phi.z);
}
inline constexpr double kInf = std::numeric_limits<double>::infinity();
inline const Vec3 kEmptyLo{kInf, kInf, kInf};
inline const Vec3 kEmptyHi{-kInf, -kInf, -kInf};

}  // namespace reamsim::bvh_detail

namespace reamsim {
struct TriangleBvh::BuildRef {
  Vec3 lo, hi, centroid;
  std::uint32_t slot;
};
}  // namespace reamsim
