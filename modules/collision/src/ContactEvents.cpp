#include "ContactEvents.h"

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <limits>

#include "Cubic.h"
#include "reamsim/collision/TriangleGeometry.h"

namespace reamsim::detail {

namespace {

constexpr double kBaryEps = 1e-9;  // as in Moeller-Trumbore (RayTriangle.h)

// Point x (assumed in the plane of abc up to rounding) inside the closed triangle, with slack.
bool insideTriangle(const Vec3& x, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 v0 = b - a, v1 = c - a, v2 = x - a;
  const double d00 = dot(v0, v0), d01 = dot(v0, v1), d11 = dot(v1, v1), d20 = dot(v2, v0), d21 = dot(v2, v1);
  const double den = d00 * d11 - d01 * d01;
  if (!(den > 1e-24 * d00 * d11)) return false;  // degenerate triangle: its edges carry the contact
  const double v = (d11 * d20 - d01 * d21) / den, w = (d00 * d21 - d01 * d20) / den;
  return v >= -kBaryEps && w >= -kBaryEps && v + w <= 1 + kBaryEps;
}

// L1 magnitudes: only used to scale the "identically zero" threshold, so no square roots are needed.
double l1(const Vec3& v) { return std::abs(v.x) + std::abs(v.y) + std::abs(v.z); }
double sum3(const Vec3 (&c)[3]) { return l1(c[0]) + l1(c[1]) + l1(c[2]); }
double sum4(const Vec3 (&c)[4]) { return l1(c[0]) + l1(c[1]) + l1(c[2]) + l1(c[3]); }

Vec3 unitOr(const Vec3& v, const Vec3& fallback) {
  const double n = norm(v);
  return n > 0 ? v / n : fallback;
}

}  // namespace

void sweptTriangleBox(const SegmentMotion& m, const Mat3& rotAtSmax, const Vec3 (&q)[3], double smax, Vec3& lo,
                      Vec3& hi) {
  constexpr double inf = std::numeric_limits<double>::infinity();
  lo = {inf, inf, inf};
  hi = {-inf, -inf, -inf};
  double r = 0;
  for (const Vec3& v : q) {
    const Vec3 e = rotAtSmax * v;
    for (const Vec3& p : {v, e}) {
      lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
      hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
    }
    r = std::max(r, norm(v));
  }
  const Vec3 t1 = m.tipAt(smax);
  const double sag = m.sag(r, smax) * (1 + 1e-12) + 1e-12 * r;
  const Vec3 tlo{std::min(m.tip0.x, t1.x), std::min(m.tip0.y, t1.y), std::min(m.tip0.z, t1.z)};
  const Vec3 thi{std::max(m.tip0.x, t1.x), std::max(m.tip0.y, t1.y), std::max(m.tip0.z, t1.z)};
  lo = lo + tlo - Vec3{sag, sag, sag};
  hi = hi + thi + Vec3{sag, sag, sag};
  // Rounding of the mapped points: pad like the BVH boxes.
  const Vec3 d = hi - lo;
  const double pad = 1e-9 * (d.x + d.y + d.z) + 1e-12 * (1 + std::max({std::abs(lo.x), std::abs(lo.y), std::abs(lo.z),
                                                                      std::abs(hi.x), std::abs(hi.y), std::abs(hi.z)}));
  lo -= Vec3{pad, pad, pad};
  hi += Vec3{pad, pad, pad};
}

// Rot(phi) q = q + phi (k x q) + e with |e| <= (phi^2/2 + phi^3/6)|q|, and phi <= 2 tau s <= 2 tau for s <= 1.
static double secondOrder(const SegmentMotion& m, double r) {
  const double t = m.tau;
  return r * (2 * t * t + 1.34 * t * t * t) * (1 + 1e-9) + 1e-15 * r;
}

void boxRates(const SegmentMotion& m, const Vec3& qlo, const Vec3& qhi, double r, Vec3& rateLo, Vec3& rateHi) {
  const Vec3 c = (qlo + qhi) * 0.5, h = (qhi - qlo) * 0.5;
  const Vec3& k = m.k;
  // v = k x q is linear in q: its range over the box is centre +- |K| h.
  const Vec3 vc = cross(k, c);
  const Vec3 vh{std::abs(k.z) * h.y + std::abs(k.y) * h.z, std::abs(k.z) * h.x + std::abs(k.x) * h.z,
                std::abs(k.y) * h.x + std::abs(k.x) * h.y};
  const double w = 2 * m.tau, g = secondOrder(m, r);
  for (int i = 0; i < 3; ++i) {
    rateLo[i] = m.delta[i] + w * std::min(0.0, vc[i] - vh[i]) - g;
    rateHi[i] = m.delta[i] + w * std::max(0.0, vc[i] + vh[i]) + g;
  }
}

AxisSweep axisSweep(const SegmentMotion& m, const Vec3& nLocal, double dlo, double dhi, const Vec3& plo,
                    const Vec3& phi, double r) {
  AxisSweep a;
  a.axis = m.R0 * nLocal;
  const double base = dot(a.axis, m.tip0);
  // First-order turn: d/ds L.(Rot q) ~ phi' L.(k x q) = phi' (R0^T (L x k)).p, ranged over the local box.
  const Vec3 w = m.R0.transposed() * cross(a.axis, m.k);
  const Vec3 c = (plo + phi) * 0.5, h = (phi - plo) * 0.5;
  const double wc = dot(w, c), wh = std::abs(w.x) * h.x + std::abs(w.y) * h.y + std::abs(w.z) * h.z;
  const double lin = dot(a.axis, m.delta), g = secondOrder(m, r);
  a.rateLo = lin + 2 * m.tau * std::min(0.0, wc - wh) - g;
  a.rateHi = lin + 2 * m.tau * std::max(0.0, wc + wh) + g;
  // Rounding of the rotated axis, the dot products and the rates: far below these pads.
  const double pad = 1e-12 * (std::abs(base) + r + std::abs(dlo) + std::abs(dhi)) + 1e-300;
  const double ratePad = 1e-12 * (std::abs(lin) + 2 * m.tau * r + g) + 1e-300;
  a.lo0 = dlo + base - pad;
  a.hi0 = dhi + base + pad;
  a.rateLo -= ratePad;
  a.rateHi += ratePad;
  return a;
}

void projectBox(const Vec3& axis, const Vec3& lo, const Vec3& hi, double& plo, double& phi) {
  const Vec3 c = (lo + hi) * 0.5, h = (hi - lo) * 0.5;
  const double pc = dot(axis, c);
  const double ph = std::abs(axis.x) * h.x + std::abs(axis.y) * h.y + std::abs(axis.z) * h.z;
  const double pad = 1e-12 * (std::abs(pc) + ph) + 1e-300;
  plo = pc - ph - pad;
  phi = pc + ph + pad;
}

BallSweep ballSweep(const SegmentMotion& m, const Vec3& centreLocal, double radius) {
  BallSweep b;
  b.c0 = m.tip0 + m.R0 * centreLocal;
  b.d = m.tipAt(1) + m.rotationAt(1) * centreLocal - b.c0;
  // The centre R(s) q + tip(s) strays from the chord c0 + s d by at most |q| (tau^2/2 + 0.77 tau^3): the
  // rational turn's sine and versine terms differ from their linear interpolants by those amounts.
  const double t = m.tau, q = norm(centreLocal);
  const double stray = q * (0.5 * t * t + 0.78 * t * t * t) * (1 + 1e-9);
  const double scale = std::max({std::abs(b.c0.x), std::abs(b.c0.y), std::abs(b.c0.z)}) + norm(b.d) + radius + q;
  b.radius = radius + stray + 1e-9 * scale;
  return b;
}

double ballSweepTime(const BallSweep& b, const Vec3& lo, const Vec3& hi, double smax) {
  const double rho = b.radius;
  // First the box grown by the radius (a slab per axis), then the rounded corners and edges: the squared
  // distance from the centre to the box is a convex piecewise quadratic in s, with breaks where a
  // coordinate of the centre crosses a face plane of the box.
  TimeWindow w(smax);
  for (int i = 0; i < 3; ++i) {
    w.clip(lo[i] - rho - b.c0[i], -b.d[i]);
    w.clip(b.c0[i] - hi[i] - rho, b.d[i]);
  }
  if (!(w.lo <= w.hi)) return std::numeric_limits<double>::infinity();
  double breaks[8];
  int nb = 0;
  breaks[nb++] = w.lo;
  for (int i = 0; i < 3; ++i) {
    if (b.d[i] == 0) continue;
    for (const double plane : {lo[i], hi[i]}) {
      const double s = (plane - b.c0[i]) / b.d[i];
      if (!(s > w.lo && s < w.hi)) continue;
      int j = nb++;  // insertion sort: at most six breaks
      for (; j > 1 && breaks[j - 1] > s; --j) breaks[j] = breaks[j - 1];
      breaks[j] = s;
    }
  }
  breaks[nb++] = w.hi;
  const double rho2 = rho * rho;
  for (int k = 0; k + 1 < nb; ++k) {
    const double s0 = breaks[k], s1 = breaks[k + 1], mid = 0.5 * (s0 + s1);
    double A = 0, B = 0, C = 0;
    for (int i = 0; i < 3; ++i) {
      const double x = b.c0[i] + mid * b.d[i];
      const double face = x < lo[i] ? lo[i] : (x > hi[i] ? hi[i] : x);
      if (face == x) continue;
      const double e = b.c0[i] - face;
      A += b.d[i] * b.d[i];
      B += 2 * b.d[i] * e;
      C += e * e;
    }
    C -= rho2;
    if ((A * s0 + B) * s0 + C <= 0) return s0 * (1 - 1e-12);
    if (A <= 0) continue;
    const double disc = B * B - 4 * A * C;
    if (disc < 0) continue;
    // The smaller root, without cancellation.
    const double qq = -0.5 * (B + std::copysign(std::sqrt(disc), B));
    const double r1 = qq / A, r2 = qq != 0 ? C / qq : r1;
    const double first = std::min(r1, r2), last = std::max(r1, r2);
    if (first <= s1 && last >= s0) return std::max(s0, first - 1e-9) * (1 - 1e-12);
  }
  return std::numeric_limits<double>::infinity();
}

double approachRate(const SegmentMotion& m, const Vec3& n, const Vec3& q, double side) {
  // d/ds of side * n.x <= side * n.delta + 2 tau max(0, side * n.(k x q)) + |n| g, negated as a decrease.
  const double lin = side * dot(n, m.delta);
  const double rot = side * dot(n, cross(m.k, q));
  return -(lin + std::min(0.0, rot) * 2 * m.tau) + norm(n) * secondOrder(m, norm(q));
}

PairContact pairFirstContact(const SegmentMotion& m, const Vec3 (&p)[3], const Vec3 (&q)[3], const BvhTriangle& bone,
                             double smax, bool checkStart, double smin) {
  PairContact out;
  const Vec3 B[3] = {bone.a, bone.b, bone.c};
  // Already touching at the start of the segment.
  const Vec3 X0[3] = {m.tip0 + q[0], m.tip0 + q[1], m.tip0 + q[2]};
  if (checkStart && trianglesIntersect(X0[0], X0[1], X0[2], B[0], B[1], B[2])) {
    const ClosestPair cp = closestTriangleTriangle(X0[0], X0[1], X0[2], B[0], B[1], B[2]);
    out = {true, 0.0, ContactFeature::Initial, cp.onB,
           unitOr(cross(B[1] - B[0], B[2] - B[0]), Vec3{0, 0, 1})};
    return out;
  }
  double best = smax;
  auto record = [&](double s, ContactFeature f, const Vec3& point, const Vec3& normal) {
    if (!out.hit || s < best) {
      out = {true, s, f, point, normal};
      best = s;
    }
  };
  const double t2 = m.tau * m.tau;
  bool degenerateVertexFace = false;

  // Boxes of each reamer vertex's path over [smin, smax] and of the bone triangle and its edges: a feature
  // pair whose boxes are apart cannot meet there, and not before smin either, so its cubic is not solved.
  // Most pairs that reach this function are of this kind where the surfaces nearly conform (a vertex
  // crosses the plane of a bone triangle it never gets near). A path is the tip's travel plus the offset's
  // arc, which lies within its chord's box grown by the arc's sag; the arc over [smin, smax] turns by at
  // most phi(smax - smin) (phi is concave from 0), so its sag is at most sag(r, smax - smin).
  Vec3 plo[3], phi[3];
  {
    if (!(smin > 0 && smin < smax)) smin = 0;
    const Mat3 turn0 = m.tau == 0 || smin == 0 ? Mat3{} : m.turnAt(smin);
    const Mat3 turn = m.tau == 0 ? Mat3{} : m.turnAt(smax);
    const Vec3 t0 = m.tipAt(smin), t1 = m.tipAt(smax);
    const Vec3 tlo{std::min(t0.x, t1.x), std::min(t0.y, t1.y), std::min(t0.z, t1.z)};
    const Vec3 thi{std::max(t0.x, t1.x), std::max(t0.y, t1.y), std::max(t0.z, t1.z)};
    for (int i = 0; i < 3; ++i) {
      const Vec3 a = turn0 * q[i], e = turn * q[i];
      const double r = norm(q[i]);
      const double pad = m.sag(r, smax - smin) * (1 + 1e-9) + 1e-9 * (r + norm(m.delta)) +
                         1e-12 * (1 + std::abs(tlo.x) + std::abs(tlo.y) + std::abs(tlo.z));
      plo[i] = Vec3{std::min(a.x, e.x), std::min(a.y, e.y), std::min(a.z, e.z)} + tlo - Vec3{pad, pad, pad};
      phi[i] = Vec3{std::max(a.x, e.x), std::max(a.y, e.y), std::max(a.z, e.z)} + thi + Vec3{pad, pad, pad};
    }
  }
  // The features' own tolerances (barycentric and segment slack, 1e-9 of their sizes) fit well inside this.
  const double slack = 1e-8 * (norm(B[1] - B[0]) + norm(B[2] - B[1]) + norm(B[0] - B[2]) + norm(q[1] - q[0]) +
                               norm(q[2] - q[1]) + norm(q[0] - q[2]));
  auto pointsBox = [&](std::initializer_list<Vec3> pts, Vec3& lo, Vec3& hi) {
    lo = hi = *pts.begin();
    for (const Vec3& v : pts) {
      lo = {std::min(lo.x, v.x), std::min(lo.y, v.y), std::min(lo.z, v.z)};
      hi = {std::max(hi.x, v.x), std::max(hi.y, v.y), std::max(hi.z, v.z)};
    }
    lo -= Vec3{slack, slack, slack};
    hi += Vec3{slack, slack, slack};
  };
  auto join = [](const Vec3& alo, const Vec3& ahi, const Vec3& blo, const Vec3& bhi, Vec3& lo, Vec3& hi) {
    lo = {std::min(alo.x, blo.x), std::min(alo.y, blo.y), std::min(alo.z, blo.z)};
    hi = {std::max(ahi.x, bhi.x), std::max(ahi.y, bhi.y), std::max(ahi.z, bhi.z)};
  };
  Vec3 boneLo, boneHi, reamerLo, reamerHi;
  pointsBox({B[0], B[1], B[2]}, boneLo, boneHi);
  join(plo[0], phi[0], plo[1], phi[1], reamerLo, reamerHi);
  join(reamerLo, reamerHi, plo[2], phi[2], reamerLo, reamerHi);

  // (a) reamer vertex reaches the bone face: n . D(s)(x(s) - B0) = 0.
  const Vec3 n = cross(B[1] - B[0], B[2] - B[0]);
  for (int i = 0; i < 3; ++i) {
    if (!boxesOverlap(plo[i], phi[i], boneLo, boneHi)) continue;
    Vec3 c[4];
    m.pointPoly(q[i], B[0], c);
    const double f[4] = {dot(n, c[0]), dot(n, c[1]), dot(n, c[2]), dot(n, c[3])};
    double s;
    const RootScan r = earliestRoot(f, best, l1(n) * sum4(c), [&](double t) {
      const Vec3 x = m.tipAt(t) + m.rotationAt(t) * p[i];
      return insideTriangle(x, B[0], B[1], B[2]);
    }, s);
    if (r == RootScan::Found) {
      const Vec3 un = unitOr(n, Vec3{0, 0, 1});
      record(s, ContactFeature::ReamerVertexBoneFace, m.tipAt(s) + m.rotationAt(s) * p[i], f[0] >= 0 ? un : -un);
    } else if (r == RootScan::Degenerate) {
      degenerateVertexFace = true;
    }
  }

  // (b) bone vertex reaches the reamer face: (D Rot m0) . (v - tip(s)) - D (m0 . q0) = 0.
  const Vec3 m0 = cross(q[1] - q[0], q[2] - q[0]);
  Vec3 M[3];
  m.vecPoly(m0, M);
  const double mq = dot(m0, q[0]);
  for (int j = 0; j < 3; ++j) {
    if (!boxesOverlap(B[j], B[j], reamerLo, reamerHi)) continue;
    const Vec3 V0 = B[j] - m.tip0, V1 = -m.delta;
    const double f[4] = {dot(M[0], V0) - mq, dot(M[0], V1) + dot(M[1], V0), dot(M[1], V1) + dot(M[2], V0) - t2 * mq,
                         dot(M[2], V1)};
    double s;
    const double reference = sum3(M) * (l1(V0) + l1(V1) + l1(q[0]));
    const RootScan r = earliestRoot(f, best, reference, [&](double t) {
      const Mat3 R = m.rotationAt(t);
      const Vec3 tip = m.tipAt(t);
      return insideTriangle(B[j], tip + R * p[0], tip + R * p[1], tip + R * p[2]);
    }, s);
    if (r == RootScan::Found) {
      const Vec3 um = unitOr(m.rotationAt(s) * cross(p[1] - p[0], p[2] - p[0]), Vec3{0, 0, 1});
      record(s, ContactFeature::BoneVertexReamerFace, B[j], f[0] >= 0 ? -um : um);
    } else if (r == RootScan::Degenerate) {
      degenerateVertexFace = true;
    }
  }

  // (c) edge reaches edge: (e_b x D Rot E) . (tip(s) - B_j) + e_b . D Rot (E x q_i) = 0. Parallel edges
  // (e_b x Rot E identically zero) are skipped: their first contact is an endpoint reaching a face, (a)/(b).
  for (int i = 0; i < 3; ++i) {
    const Vec3 E = q[(i + 1) % 3] - q[i];
    Vec3 G[3], H[3];
    m.vecPoly(E, G);
    m.vecPoly(cross(E, q[i]), H);
    Vec3 elo, ehi;
    join(plo[i], phi[i], plo[(i + 1) % 3], phi[(i + 1) % 3], elo, ehi);
    for (int j = 0; j < 3; ++j) {
      Vec3 blo, bhi;
      pointsBox({B[j], B[(j + 1) % 3]}, blo, bhi);
      if (!boxesOverlap(elo, ehi, blo, bhi)) continue;
      const Vec3 eb = B[(j + 1) % 3] - B[j];
      const Vec3 g[3] = {cross(eb, G[0]), cross(eb, G[1]), cross(eb, G[2])};
      if (!(sum3(g) > 1e-11 * l1(eb) * sum3(G))) continue;
      const Vec3 T0 = m.tip0 - B[j], T1 = m.delta;
      const double f[4] = {dot(g[0], T0) + dot(eb, H[0]), dot(g[0], T1) + dot(g[1], T0) + dot(eb, H[1]),
                           dot(g[1], T1) + dot(g[2], T0) + dot(eb, H[2]), dot(g[2], T1)};
      const double reference = sum3(g) * (l1(T0) + l1(T1)) + l1(eb) * sum3(H);
      double s;
      Vec3 c1, c2;
      const RootScan r = earliestRoot(f, best, reference, [&](double t) {
        const Mat3 R = m.rotationAt(t);
        const Vec3 tip = m.tipAt(t);
        const double tol = 1e-9 * (norm(eb) + norm(E));
        double u, v;
        const double d2 = closestSegmentSegment(tip + R * p[i], tip + R * p[(i + 1) % 3], B[j], B[(j + 1) % 3], u, v,
                                                c1, c2);
        return d2 <= tol * tol;
      }, s);
      if (r == RootScan::Found) {
        const Vec3 dir = unitOr(cross(eb, m.rotationAt(s) * (m.R0.transposed() * E)), Vec3{0, 0, 1});
        record(s, ContactFeature::EdgeEdge, (c1 + c2) * 0.5, f[0] >= 0 ? dir : -dir);
      }
    }
  }

  // Degenerate configurations (a vertex sliding in the other triangle's plane): conservative advancement.
  if (degenerateVertexFace) {
    const double rmax = std::max({norm(q[0]), norm(q[1]), norm(q[2])});
    const double speed = m.speedBound(rmax);
    double s = 0;
    for (int it = 0; it < 10000 && speed > 0 && s <= best; ++it) {
      const Mat3 R = m.rotationAt(s);
      const Vec3 tip = m.tipAt(s);
      const Vec3 X[3] = {tip + R * p[0], tip + R * p[1], tip + R * p[2]};
      const ClosestPair cp = closestTriangleTriangle(X[0], X[1], X[2], B[0], B[1], B[2]);
      const double d = std::sqrt(cp.squaredDistance);
      if (d <= kFallbackToleranceMm) {
        if (!out.hit || s < best) record(s, ContactFeature::Fallback, cp.onB, unitOr(cp.onA - cp.onB, unitOr(n, {0, 0, 1})));
        break;
      }
      s += d / speed;
    }
  }
  return out;
}

}  // namespace reamsim::detail
