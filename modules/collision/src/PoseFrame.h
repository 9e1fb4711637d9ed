#pragma once
// Internal: a rigid transform with its inverse, and conservative box mapping between the reamer-local and
// the bone (world) frame. A box maps to the axis-aligned box of its rotated image (centre + |R| x half
// extents): never smaller than the image, so box tests stay conservative.
#include <cmath>

#include "reamsim/core/Pose.h"
#include "reamsim/mesh/Vec3.h"

namespace reamsim::detail {

struct Mat3 {
  double m[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};  // row-major
  Vec3 operator*(const Vec3& v) const {
    return {m[0] * v.x + m[1] * v.y + m[2] * v.z, m[3] * v.x + m[4] * v.y + m[5] * v.z,
            m[6] * v.x + m[7] * v.y + m[8] * v.z};
  }
  Mat3 operator*(const Mat3& o) const {
    Mat3 r;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        r.m[3 * i + j] = m[3 * i] * o.m[j] + m[3 * i + 1] * o.m[3 + j] + m[3 * i + 2] * o.m[6 + j];
    return r;
  }
  Mat3 transposed() const { return {{m[0], m[3], m[6], m[1], m[4], m[7], m[2], m[5], m[8]}}; }
  static Mat3 from(const RigidTransform& t) {
    Mat3 r;
    for (int i = 0; i < 9; ++i) r.m[i] = t.rotation[i];
    return r;
  }
};

// Image of the box [lo, hi] under x -> R x + t, as an enclosing axis-aligned box.
inline void mapBox(const Mat3& R, const Vec3& t, const Vec3& lo, const Vec3& hi, Vec3& outLo, Vec3& outHi) {
  const Vec3 c = (lo + hi) * 0.5, h = (hi - lo) * 0.5;
  const Vec3 cw = R * c + t;
  const double* m = R.m;
  const Vec3 hw{std::abs(m[0]) * h.x + std::abs(m[1]) * h.y + std::abs(m[2]) * h.z,
                std::abs(m[3]) * h.x + std::abs(m[4]) * h.y + std::abs(m[5]) * h.z,
                std::abs(m[6]) * h.x + std::abs(m[7]) * h.y + std::abs(m[8]) * h.z};
  // Rounding of the centre is far below the BVH box padding, but keep the result strictly enclosing.
  const Vec3 slack = hw * 1e-15 + Vec3{1e-300, 1e-300, 1e-300};
  outLo = cw - hw - slack;
  outHi = cw + hw + slack;
}

struct PoseFrame {
  Mat3 R, Rt;  // local -> world rotation and its inverse
  Vec3 t;      // world position of the local origin (the tip)
  explicit PoseFrame(const RigidTransform& x) : R(Mat3::from(x)), Rt(R.transposed()), t(x.translation) {}
  Vec3 toWorld(const Vec3& p) const { return R * p + t; }
  Vec3 toLocal(const Vec3& p) const { return Rt * (p - t); }
  void localBoxToWorld(const Vec3& lo, const Vec3& hi, Vec3& wlo, Vec3& whi) const { mapBox(R, t, lo, hi, wlo, whi); }
  void worldBoxToLocal(const Vec3& lo, const Vec3& hi, Vec3& llo, Vec3& lhi) const {
    mapBox(Rt, Rt * (-t), lo, hi, llo, lhi);
  }
};

}  // namespace reamsim::detail
