#pragma once
// Internal: first contact of one moving reamer triangle with one fixed bone triangle along a segment
// motion (the leaf test of queryFirstContact and of its brute-force reference).
#include <algorithm>
#include <cmath>
#include <limits>

#include "RationalMotion.h"
#include "reamsim/collision/FirstContact.h"
#include "reamsim/collision/TriangleBvh.h"

namespace reamsim::detail {

// The times s in [0, smax] satisfying linear constraints c0 + c1 s <= 0.
struct TimeWindow {
  double lo = 0, hi;
  explicit TimeWindow(double smax) : hi(smax) {}
  void clip(double c0, double c1) {
    if (c1 == 0) {
      if (c0 > 0) hi = -1;
    } else if (c1 > 0) {
      hi = std::min(hi, -c0 / c1);
    } else {
      lo = std::max(lo, -c0 / c1);
    }
  }
  // The first time of the window (shaded down for rounding), +inf when it is empty.
  double earliest() const {
    return lo <= hi * (1 + 1e-12) + 1e-300 ? lo * (1 - 1e-12) : std::numeric_limits<double>::infinity();
  }
};

struct PairContact {
  bool hit = false;
  double s = 0;  // segment time
  ContactFeature feature = ContactFeature::None;
  Vec3 point, normal;
};

// p: the reamer triangle in local coordinates; q: the same rotated by m.R0 (offsets from the tip at s = 0).
// Only contacts with s <= smax are reported. checkStart: test for touching at s = 0 first (callers that know
// the surfaces are apart at the start skip it). smin: a lower bound the caller knows for the pair's first
// contact (0 when none): features whose paths over [smin, smax] stay apart are not solved.
PairContact pairFirstContact(const SegmentMotion& m, const Vec3 (&p)[3], const Vec3 (&q)[3], const BvhTriangle& bone,
                             double smax, bool checkStart = true, double smin = 0);

// Earliest s in [0, smax] at which a box whose faces move linearly (lower faces at rateLo, upper faces at
// rateHi per axis, from [lo0, hi0] at s = 0) can overlap [blo, bhi]; +inf when it cannot.
// Inline, as the two below: the searches call them for every node and triangle they bound.
inline double sweptBoxTime(const Vec3& lo0, const Vec3& hi0, const Vec3& rateLo, const Vec3& rateHi, const Vec3& blo,
                           const Vec3& bhi, double smax) {
  TimeWindow w(smax);
  for (int i = 0; i < 3; ++i) {
    w.clip(lo0[i] - bhi[i], rateLo[i]);   // lower face reaches the other box's upper face
    w.clip(blo[i] - hi0[i], -rateHi[i]);  // upper face reaches the other box's lower face
  }
  return w.earliest();
}

// Conservative face rates of the moving box holding points q (offsets from the tip at s = 0) within
// [qlo, qhi] (a box of radius r about the tip): translation, first-order rotation k x q over the box (its
// direction is known, which keeps the bound tight) and a second-order remainder.
void boxRates(const SegmentMotion& m, const Vec3& qlo, const Vec3& qhi, double r, Vec3& rateLo, Vec3& rateHi);

// A moving reamer feature seen along one fixed world axis L: at segment time s its projection on L lies
// within [lo0 + s rateLo, hi0 + s rateHi]. With L the feature's own (rotated) normal direction this is a
// slab as thin as the feature is flat, which boxes are not once the reamer is tilted.
struct AxisSweep {
  Vec3 axis;  // L, world, unit
  double lo0 = 0, hi0 = 0, rateLo = 0, rateHi = 0;
};
// Points p (reamer-local) with nLocal.p in [dlo, dhi], inside the local box [plo, phi], at most r from the
// tip; L = R0 nLocal. Exact for translations; the turn adds its directional first-order reach and the
// second-order remainder, as in boxRates.
AxisSweep axisSweep(const SegmentMotion& m, const Vec3& nLocal, double dlo, double dhi, const Vec3& plo,
                    const Vec3& phi, double r);
// Earliest s in [0, smax] at which the sweep can overlap the fixed interval [blo, bhi] of the same axis;
// +inf when it cannot.
inline double axisSweepTime(const AxisSweep& a, double blo, double bhi, double smax) {
  TimeWindow w(smax);
  w.clip(a.lo0 - bhi, a.rateLo);   // the sweep's low end reaches the interval's high end
  w.clip(blo - a.hi0, -a.rateHi);  // the sweep's high end reaches the interval's low end
  return w.earliest();
}
// The projection of a fixed box on the sweep's axis, padded for rounding.
void projectBox(const Vec3& axis, const Vec3& lo, const Vec3& hi, double& plo, double& phi);

// A ball of fixed radius whose centre moves linearly from c0 by d over the segment: it holds the convex
// ideal solid of a parametric reamer at every s (the turn's deviation of the centre from that line is
// folded into the radius). Tight where boxes are loose: in front of a curved cutting face.
struct BallSweep {
  Vec3 c0, d;
  double radius = 0;
};
// The ball of `radius` about the reamer-local point `centreLocal`, moving with the reamer.
BallSweep ballSweep(const SegmentMotion& m, const Vec3& centreLocal, double radius);
// The ball seen along a fixed world axis (unit): an AxisSweep for axisSweepTime against a slab.
inline AxisSweep ballAlong(const BallSweep& b, const Vec3& axis) {
  AxisSweep a;
  a.axis = axis;
  const double c = dot(axis, b.c0), rate = dot(axis, b.d);
  const double pad = 1e-12 * (std::abs(c) + b.radius + std::abs(rate)) + 1e-300;
  a.lo0 = c - b.radius - pad;
  a.hi0 = c + b.radius + pad;
  a.rateLo = rate - pad;
  a.rateHi = rate + pad;
  return a;
}
// Earliest s in [0, smax] at which the ball can meet the fixed box [lo, hi]; +inf when it cannot.
double ballSweepTime(const BallSweep& b, const Vec3& lo, const Vec3& hi, double smax);

// Fastest rate at which the signed height n.(x - a) of the point with offset q can move towards zero, given
// its current side (sign of the height).
double approachRate(const SegmentMotion& m, const Vec3& n, const Vec3& q, double side);

// Axis-aligned box enclosing the triangle's path over [0, smax] (rotated offsets at both ends, the arc's
// sag, plus the tip's travel).
void sweptTriangleBox(const SegmentMotion& m, const Mat3& rotAtSmax, const Vec3 (&q)[3], double smax, Vec3& lo,
                      Vec3& hi);

}  // namespace reamsim::detail
