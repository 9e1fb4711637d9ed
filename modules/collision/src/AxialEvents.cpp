#include "AxialEvents.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "reamsim/collision/TriangleGeometry.h"

namespace reamsim::detail {

namespace {

constexpr double kBaryEps = 1e-9;

bool insideTriangle(const Vec3& x, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 v0 = b - a, v1 = c - a, v2 = x - a;
  const double d00 = dot(v0, v0), d01 = dot(v0, v1), d11 = dot(v1, v1), d20 = dot(v2, v0), d21 = dot(v2, v1);
  const double den = d00 * d11 - d01 * d01;
  if (!(den > 1e-24 * d00 * d11)) return false;
  const double v = (d11 * d20 - d01 * d21) / den, w = (d00 * d21 - d01 * d20) / den;
  if (!(v >= -kBaryEps && w >= -kBaryEps && v + w <= 1 + kBaryEps)) return false;
  // A sliver's computed normal can be far off, and a point far outside it then projects inside: the
  // point must also lie in the triangle's (slightly grown) box.
  const double tol = 1e-7 * std::max({1.0, std::abs(a.x), std::abs(a.y), std::abs(a.z)});
  return x.x >= std::min({a.x, b.x, c.x}) - tol && x.x <= std::max({a.x, b.x, c.x}) + tol &&
         x.y >= std::min({a.y, b.y, c.y}) - tol && x.y <= std::max({a.y, b.y, c.y}) + tol &&
         x.z >= std::min({a.z, b.z, c.z}) - tol && x.z <= std::max({a.z, b.z, c.z}) + tol;
}

}  // namespace

AxialInterval axialInterval(const Vec3 (&x)[3], const BvhTriangle& bone, const Vec3& u) {
  AxialInterval out;
  const Vec3 B[3] = {bone.a, bone.b, bone.c};
  auto add = [&](double d, const Vec3& point) {
    if (!out.valid) {
      out = {true, d, d, point};
      return;
    }
    out.lo = std::min(out.lo, d);
    if (d > out.hi) {
      out.hi = d;
      out.hiPoint = point;
    }
  };
  // (a) reamer vertex x_i - d u on the bone face.
  const Vec3 n = cross(B[1] - B[0], B[2] - B[0]);
  const double nu = dot(n, u);
  if (std::abs(nu) > 1e-12 * norm(n)) {
    for (const Vec3& xi : x) {
      const double d = dot(n, xi - B[0]) / nu;
      const Vec3 at = xi - u * d;
      if (insideTriangle(at, B[0], B[1], B[2])) add(d, at);
    }
  }
  // (b) bone vertex on the reamer face moved by -d u.
  const Vec3 m = cross(x[1] - x[0], x[2] - x[0]);
  const double mu = dot(m, u);
  if (std::abs(mu) > 1e-12 * norm(m)) {
    for (const Vec3& bj : B) {
      const double d = dot(m, x[0] - bj) / mu;
      const Vec3 shift = u * d;
      if (insideTriangle(bj, x[0] - shift, x[1] - shift, x[2] - shift)) add(d, bj);
    }
  }
  // (c) edge against edge: the translated lines meet; both crossing parameters within the segments.
  for (int i = 0; i < 3; ++i) {
    const Vec3 E = x[(i + 1) % 3] - x[i];
    for (int j = 0; j < 3; ++j) {
      const Vec3 eb = B[(j + 1) % 3] - B[j];
      const Vec3 w = cross(eb, E);
      const double ww = dot(w, w);
      const double wu = dot(w, u);
      if (!(ww > 1e-28 * dot(eb, eb) * dot(E, E)) || !(std::abs(wu) > 1e-12 * std::sqrt(ww))) continue;
      const double d = dot(w, x[i] - B[j]) / wu;
      const Vec3 r = B[j] - (x[i] - u * d);  // from the moved reamer edge start to the bone edge start
      // Coplanar lines X + s E and B - t eb... solved in the plane with normal w.
      const double s = -dot(cross(r, eb), w) / ww;
      const double t = -dot(cross(r, E), w) / ww;
      if (s < -kBaryEps || s > 1 + kBaryEps || t < -kBaryEps || t > 1 + kBaryEps) continue;
      add(d, B[j] + eb * t);
    }
  }
  // Touching at d = 0 (a configuration the events may only reach within rounding): include 0.
  if (trianglesIntersect(x[0], x[1], x[2], B[0], B[1], B[2])) {
    const ClosestPair cp = closestTriangleTriangle(x[0], x[1], x[2], B[0], B[1], B[2]);
    add(0.0, cp.onB);
  }
  return out;
}

bool shadowsOverlap(const Vec3 (&x)[3], const BvhTriangle& bone, const Vec3& u) {
  // 2D coordinates in the plane across u, relative to the first reamer vertex.
  const Vec3 e1 = anyPerpendicular(u);
  const Vec3 e2 = cross(u, e1);
  double ax[3], ay[3], bx[3], by[3];
  const Vec3 B[3] = {bone.a, bone.b, bone.c};
  double mag = 0;
  for (int i = 0; i < 3; ++i) {
    const Vec3 p = x[i] - x[0], q = B[i] - x[0];
    ax[i] = dot(p, e1); ay[i] = dot(p, e2);
    bx[i] = dot(q, e1); by[i] = dot(q, e2);
    mag = std::max({mag, std::abs(ax[i]), std::abs(ay[i]), std::abs(bx[i]), std::abs(by[i])});
  }
  const double tol = 1e-9 * (mag + 1e-300);
  // Separating axes: the edge normals of both shadows.
  auto separated = [&](const double* px, const double* py, int i) {
    const int j = (i + 1) % 3;
    const double nx = py[j] - py[i], ny = px[i] - px[j];
    const double len = std::abs(nx) + std::abs(ny);
    if (len == 0) return false;
    double amin = 1e300, amax = -1e300, bmin = 1e300, bmax = -1e300;
    for (int k = 0; k < 3; ++k) {
      const double pa = nx * ax[k] + ny * ay[k], pb = nx * bx[k] + ny * by[k];
      amin = std::min(amin, pa); amax = std::max(amax, pa);
      bmin = std::min(bmin, pb); bmax = std::max(bmax, pb);
    }
    return amax < bmin - tol * len || bmax < amin - tol * len;
  };
  for (int i = 0; i < 3; ++i)
    if (separated(ax, ay, i) || separated(bx, by, i)) return false;
  return true;
}

bool axialBoxInterval(const Vec3& lo, const Vec3& hi, const Vec3& blo, const Vec3& bhi, const Vec3& u, double& dlo,
                      double& dhi) {
  dlo = -std::numeric_limits<double>::infinity();
  dhi = std::numeric_limits<double>::infinity();
  for (int i = 0; i < 3; ++i) {
    // Need lo_i - d u_i <= bhi_i and blo_i <= hi_i - d u_i.
    if (u[i] == 0) {
      if (lo[i] > bhi[i] || blo[i] > hi[i]) return false;
      continue;
    }
    double a = (lo[i] - bhi[i]) / u[i], b = (hi[i] - blo[i]) / u[i];
    if (a > b) std::swap(a, b);
    // Widen for rounding of the division.
    const double slack = 1e-12 * (std::abs(a) + std::abs(b)) + 1e-300;
    dlo = std::max(dlo, a - slack);
    dhi = std::min(dhi, b + slack);
    if (dlo > dhi) return false;
  }
  return true;
}

double chainFrom(double start, std::vector<AxialInterval>& intervals, double tol, Vec3& reachedPoint) {
  std::sort(intervals.begin(), intervals.end(), [](const AxialInterval& a, const AxialInterval& b) {
    return a.lo < b.lo || (a.lo == b.lo && a.hi < b.hi);
  });
  double end = start;
  bool any = false;
  for (const AxialInterval& iv : intervals) {
    if (iv.lo > end + tol) break;
    if (iv.hi < start - tol) continue;
    if (!any || iv.hi > end) reachedPoint = iv.hiPoint;
    any = true;
    end = std::max(end, iv.hi);
  }
  return end;
}

}  // namespace reamsim::detail
