#pragma once
// Internal: the reamer path between two poses used by the first-contact query.
//
// The rotation R1 R0^T is split into segments of at most 90 degrees about its fixed axis k. Within a
// segment, for s in [0, 1]: tip(s) = tip0 + s delta and R(s) = Rot(k, phi(s)) R0 with tan(phi/2) = s tau,
// tau = tan(theta/2). With this rational parametrisation D(s) R(s) (D = 1 + tau^2 s^2) is a quadratic
// polynomial in s, so every contact condition between a moving and a fixed feature (vertex-plane,
// edge-edge coplanarity) is a cubic in s: solved to rounding, no time stepping.
#include <algorithm>
#include <cmath>

#include "PoseFrame.h"

namespace reamsim::detail {

inline Mat3 rotationAbout(const Vec3& k, double angle) {
  const double c = std::cos(angle), s = std::sin(angle), v = 1 - c;
  Mat3 r;
  r.m[0] = c + k.x * k.x * v;        r.m[1] = k.x * k.y * v - k.z * s; r.m[2] = k.x * k.z * v + k.y * s;
  r.m[3] = k.y * k.x * v + k.z * s;  r.m[4] = c + k.y * k.y * v;       r.m[5] = k.y * k.z * v - k.x * s;
  r.m[6] = k.z * k.x * v - k.y * s;  r.m[7] = k.z * k.y * v + k.x * s; r.m[8] = c + k.z * k.z * v;
  return r;
}

// Axis and angle (in [0, pi]) of a rotation matrix.
inline void axisAngle(const Mat3& r, Vec3& axis, double& angle) {
  const double* m = r.m;
  const Vec3 v{m[7] - m[5], m[2] - m[6], m[3] - m[1]};  // 2 sin(angle) axis
  const double cosA = std::clamp((m[0] + m[4] + m[8] - 1) * 0.5, -1.0, 1.0);
  const double sin2 = norm(v);
  angle = std::atan2(0.5 * sin2, cosA);
  if (angle < 1e-300) {
    axis = {0, 0, 1};
    angle = 0;
    return;
  }
  if (cosA > -0.5) {
    axis = v / sin2;
    return;
  }
  // Near pi the antisymmetric part vanishes: use the symmetric part (r + r^T)/2 = cos I + (1 - cos) k k^T.
  const double oneMinus = 1 - cosA;
  Vec3 k{std::sqrt(std::max(0.0, (m[0] - cosA) / oneMinus)), std::sqrt(std::max(0.0, (m[4] - cosA) / oneMinus)),
         std::sqrt(std::max(0.0, (m[8] - cosA) / oneMinus))};
  // Fix signs relative to the largest component.
  if (k.x >= k.y && k.x >= k.z) {
    k.y = std::copysign(k.y, m[1] + m[3]);
    k.z = std::copysign(k.z, m[2] + m[6]);
  } else if (k.y >= k.z) {
    k.x = std::copysign(k.x, m[1] + m[3]);
    k.z = std::copysign(k.z, m[5] + m[7]);
  } else {
    k.x = std::copysign(k.x, m[2] + m[6]);
    k.y = std::copysign(k.y, m[5] + m[7]);
  }
  // Orient with the sine part where it is still meaningful.
  if (dot(k, v) < 0) k = -k;
  axis = normalized(k);
}

struct SegmentMotion {
  Mat3 R0;
  Vec3 tip0, delta;
  Vec3 k{0, 0, 1};
  double tau = 0;

  double phi(double s) const { return 2 * std::atan(s * tau); }
  // Rot(k, phi(s)) without trigonometry: sin phi = 2w/(1+w^2), 1 - cos phi = 2w^2/(1+w^2), w = s tau.
  Mat3 turnAt(double s) const {
    const double w = s * tau, inv = 1 / (1 + w * w), sn = 2 * w * inv, v = 2 * w * w * inv, c = 1 - v;
    Mat3 r;
    r.m[0] = c + k.x * k.x * v;        r.m[1] = k.x * k.y * v - k.z * sn; r.m[2] = k.x * k.z * v + k.y * sn;
    r.m[3] = k.y * k.x * v + k.z * sn; r.m[4] = c + k.y * k.y * v;        r.m[5] = k.y * k.z * v - k.x * sn;
    r.m[6] = k.z * k.x * v - k.y * sn; r.m[7] = k.z * k.y * v + k.x * sn; r.m[8] = c + k.z * k.z * v;
    return r;
  }
  Mat3 rotationAt(double s) const { return tau == 0 ? R0 : turnAt(s) * R0; }
  Vec3 tipAt(double s) const { return tip0 + delta * s; }
  // Speed bound of a point at distance r from the tip: |delta| + r dphi/ds, dphi/ds <= 2 tau.
  double speedBound(double r) const { return norm(delta) + 2 * tau * r; }
  // Largest distance of such a point's arc from its chord over [0, s].
  // cos(phi/2) = 1 / sqrt(1 + w^2) since tan(phi/2) = w.
  double sag(double r, double s) const {
    const double w = s * tau;
    return r * (w * w / (1 + w * w + std::sqrt(1 + w * w)));  // = r (1 - 1/sqrt(1+w^2)), no cancellation
  }

  // D(s) Rot(s) v = c0 + c1 s + c2 s^2 for a world vector v (already rotated by R0).
  void vecPoly(const Vec3& v, Vec3 (&c)[3]) const {
    const Vec3 kv = cross(k, v), kkv = cross(k, kv);
    c[0] = v;
    c[1] = kv * (2 * tau);
    c[2] = (v + kkv * 2) * (tau * tau);
  }
  // D(s) (x(s) - a) = c0 + c1 s + c2 s^2 + c3 s^3 for the point q = R0 p (p local), x(s) = tip(s) + Rot(s) q.
  void pointPoly(const Vec3& q, const Vec3& a, Vec3 (&c)[4]) const {
    Vec3 r[3];
    vecPoly(q, r);
    const Vec3 t0 = tip0 - a;
    const double t2 = tau * tau;
    c[0] = t0 + r[0];
    c[1] = delta + r[1];
    c[2] = t0 * t2 + r[2];
    c[3] = delta * t2;
  }
};

}  // namespace reamsim::detail

namespace reamsim::detail {

// The whole path from one pose to another, cut into segments of at most 90 degrees of rotation.
struct MotionPlan {
  Mat3 R0;
  Vec3 tip0, delta, k{0, 0, 1};
  double theta = 0;
  int segments = 1;

  static MotionPlan between(const RigidTransform& a, const RigidTransform& b) {
    MotionPlan p;
    p.R0 = Mat3::from(a);
    p.tip0 = a.translation;
    p.delta = b.translation - a.translation;
    axisAngle(Mat3::from(b) * p.R0.transposed(), p.k, p.theta);
    constexpr double kMaxSegmentAngle = 1.5707963267948966;
    p.segments = std::max(1, static_cast<int>(std::ceil(p.theta / kMaxSegmentAngle - 1e-12)));
    return p;
  }
  SegmentMotion segment(int i) const {
    SegmentMotion m;
    const double f = double(i) / segments;
    m.R0 = theta == 0 ? R0 : rotationAbout(k, theta * f) * R0;
    m.tip0 = tip0 + delta * f;
    m.delta = delta / double(segments);
    m.k = k;
    m.tau = std::tan(0.5 * theta / segments);
    return m;
  }
  RigidTransform at(double t) const {
    t = std::clamp(t, 0.0, 1.0);
    const int i = std::min(segments - 1, static_cast<int>(std::floor(t * segments)));
    const SegmentMotion m = segment(i);
    const double s = t * segments - i;
    const Mat3 r = m.rotationAt(s);
    RigidTransform out;
    for (int j = 0; j < 9; ++j) out.rotation[j] = r.m[j];
    out.translation = m.tipAt(s);
    return out;
  }
};

}  // namespace reamsim::detail
