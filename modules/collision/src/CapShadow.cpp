#include "CapShadow.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace reamsim::detail {

namespace {

struct Point2 {
  double x, y;
};

// Twice the signed area of (a, b, p): > 0 when p lies left of a -> b.
double leftOf(const Point2& a, const Point2& b, const Point2& p) {
  return (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x);
}

// Sutherland-Hodgman against the closed half-plane left of a -> b. A vertex rounded to just outside an edge
// it lies on is lost only where the neighbouring face triangle, whose height agrees there, keeps it.
int clipLeftOf(const Point2* in, int n, Point2 a, Point2 b, Point2* out) {
  int m = 0;
  for (int i = 0; i < n; ++i) {
    const Point2& p = in[i];
    const Point2& q = in[(i + 1) % n];
    const double sp = leftOf(a, b, p);
    const double sq = leftOf(a, b, q);
    if (sp >= 0) out[m++] = p;
    if ((sp >= 0) != (sq >= 0)) {
      const double t = sp / (sp - sq);
      out[m++] = {p.x + t * (q.x - p.x), p.y + t * (q.y - p.y)};
    }
  }
  return m;
}

}  // namespace

std::shared_ptr<const CapShadow> CapShadow::build(const TriangleMesh& solid, const std::vector<std::uint32_t>& face) {
  auto cap = std::make_shared<CapShadow>();
  double xlo = std::numeric_limits<double>::infinity(), xhi = -xlo, ylo = xlo, yhi = -xlo;
  cap->top_ = -xlo;
  cap->bottom_ = xlo;
  for (std::uint32_t f : face) {
    const Triangle& t = solid.triangles[f];
    const Vec3 P[3] = {solid.vertices[t[0]], solid.vertices[t[1]], solid.vertices[t[2]]};
    const Vec3 n = cross(P[1] - P[0], P[2] - P[0]);
    const double len = norm(n);
    if (!(len > 0) || !(n.z >= kMinForward * len)) return nullptr;  // not a height field: no shadow
    Face s;
    for (int k = 0; k < 3; ++k) {
      s.x[k] = P[k].x;
      s.y[k] = P[k].y;
      cap->rimRadius_ = std::max(cap->rimRadius_, std::hypot(P[k].x, P[k].y));
      cap->top_ = std::max(cap->top_, P[k].z);
      cap->bottom_ = std::min(cap->bottom_, P[k].z);
    }
    // n . (p - P0) = 0  =>  z = P0.z - (n.x (x - P0.x) + n.y (y - P0.y)) / n.z
    s.a = -n.x / n.z;
    s.b = -n.y / n.z;
    s.c = P[0].z - s.a * P[0].x - s.b * P[0].y;
    s.xlo = std::min({s.x[0], s.x[1], s.x[2]});
    s.xhi = std::max({s.x[0], s.x[1], s.x[2]});
    s.ylo = std::min({s.y[0], s.y[1], s.y[2]});
    s.yhi = std::max({s.y[0], s.y[1], s.y[2]});
    s.solidTriangle = f;
    xlo = std::min(xlo, s.xlo);
    xhi = std::max(xhi, s.xhi);
    ylo = std::min(ylo, s.ylo);
    yhi = std::max(yhi, s.yhi);
    cap->faces_.push_back(s);
  }
  if (cap->faces_.empty()) return nullptr;
  // About one face per cell on average (the apex's slivers crowd a few cells).
  const int n = std::max(1, static_cast<int>(std::sqrt(static_cast<double>(cap->faces_.size()))));
  cap->cell_ = std::max(xhi - xlo, yhi - ylo) / n * (1 + 1e-12) + 1e-300;
  cap->x0_ = xlo;
  cap->y0_ = ylo;
  cap->nx_ = std::max(1, static_cast<int>(std::ceil((xhi - xlo) / cap->cell_)));
  cap->ny_ = std::max(1, static_cast<int>(std::ceil((yhi - ylo) / cap->cell_)));
  const std::size_t cells = static_cast<std::size_t>(cap->nx_) * static_cast<std::size_t>(cap->ny_);
  auto cellRange = [&](const Face& s, int& i0, int& i1, int& j0, int& j1) {
    i0 = cap->cellOf(s.xlo, cap->x0_, cap->nx_);
    i1 = cap->cellOf(s.xhi, cap->x0_, cap->nx_);
    j0 = cap->cellOf(s.ylo, cap->y0_, cap->ny_);
    j1 = cap->cellOf(s.yhi, cap->y0_, cap->ny_);
  };
  std::vector<std::uint32_t> count(cells + 1, 0);
  for (Face& s : cap->faces_) {
    int i0, i1, j0, j1;
    cellRange(s, i0, i1, j0, j1);
    s.firstCellX = i0;
    s.firstCellY = j0;
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i) ++count[static_cast<std::size_t>(j) * cap->nx_ + i + 1];
  }
  for (std::size_t c = 0; c < cells; ++c) count[c + 1] += count[c];
  cap->cellStart_ = count;
  cap->cellFaces_.resize(count[cells]);
  for (std::uint32_t f = 0; f < cap->faces_.size(); ++f) {
    int i0, i1, j0, j1;
    cellRange(cap->faces_[f], i0, i1, j0, j1);
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i) cap->cellFaces_[count[static_cast<std::size_t>(j) * cap->nx_ + i]++] = f;
  }
  return cap;
}

CapShadow::ShadowBox CapShadow::shadowBox(const Vec3 (&q)[3]) {
  return {std::min({q[0].x, q[1].x, q[2].x}), std::max({q[0].x, q[1].x, q[2].x}), std::min({q[0].y, q[1].y, q[2].y}),
          std::max({q[0].y, q[1].y, q[2].y})};
}

int CapShadow::cellOf(double v, double v0, int n) const {
  return std::clamp(static_cast<int>(std::floor((v - v0) / cell_)), 0, n - 1);
}

template <class Visit>
void CapShadow::forFacesUnder(const ShadowBox& box, Visit&& visit) const {
  const auto [xlo, xhi, ylo, yhi] = box;
  if (!(xhi >= x0_ && ylo <= y0_ + ny_ * cell_ && yhi >= y0_ && xlo <= x0_ + nx_ * cell_)) return;
  const int i0 = cellOf(xlo, x0_, nx_), i1 = cellOf(xhi, x0_, nx_);
  const int j0 = cellOf(ylo, y0_, ny_), j1 = cellOf(yhi, y0_, ny_);
  for (int j = j0; j <= j1; ++j)
    for (int i = i0; i <= i1; ++i) {
      const std::size_t c = static_cast<std::size_t>(j) * nx_ + i;
      for (std::uint32_t k = cellStart_[c]; k < cellStart_[c + 1]; ++k) {
        const Face& s = faces_[cellFaces_[k]];
        if (s.xlo > xhi || s.xhi < xlo || s.ylo > yhi || s.yhi < ylo) continue;
        // A face listed in several of the cells visited is taken in the first of them only.
        if (i != std::max(i0, s.firstCellX) || j != std::max(j0, s.firstCellY)) continue;
        if (!visit(s)) return;
      }
    }
}

void CapShadow::facesUnder(const Vec3 (&q)[3], std::vector<std::uint32_t>& out) const {
  out.clear();
  forFacesUnder(shadowBox(q), [&](const Face& s) {
    out.push_back(s.solidTriangle);
    return true;
  });
}

bool CapShadow::steep(const Vec3 (&q)[3]) {
  const Vec3 n = cross(q[1] - q[0], q[2] - q[0]);
  return std::abs(n.z) >= kMinSteepness * norm(n);
}

bool CapShadow::interval(const Vec3 (&q)[3], double& lo, double& hi, Vec3& hiPoint) const {
  const Vec3 n = cross(q[1] - q[0], q[2] - q[0]);
  // The bone triangle's height over its shadow: z(x, y) = q0.z + gx (x - q0.x) + gy (y - q0.y).
  const double gx = -n.x / n.z, gy = -n.y / n.z;
  Point2 tri[3] = {{q[0].x, q[0].y}, {q[1].x, q[1].y}, {q[2].x, q[2].y}};
  if (n.z < 0) std::swap(tri[1], tri[2]);  // counter-clockwise, as the face triangles' shadows are
  lo = std::numeric_limits<double>::infinity();
  hi = -lo;
  Point2 best{0, 0};
  // The back-out distance at a point of the shadow: the face's height less the bone triangle's.
  auto take = [&](const Face& s, const Point2* p, int m) {
    for (int k = 0; k < m; ++k) {
      const double d = (s.a * p[k].x + s.b * p[k].y + s.c) - (q[0].z + gx * (p[k].x - q[0].x) + gy * (p[k].y - q[0].y));
      lo = std::min(lo, d);
      if (d > hi) {
        hi = d;
        best = p[k];
      }
    }
  };
  forFacesUnder(shadowBox(q), [&](const Face& s) {
    // Within one face triangle's shadow (the usual case for a bone finer than the reamer), the interval is
    // that face's alone: any other face meets the shadow at most on a shared edge, with the same heights.
    const Point2 corner[3] = {{s.x[0], s.y[0]}, {s.x[1], s.y[1]}, {s.x[2], s.y[2]}};
    bool inside = true;
    for (int e = 0; e < 3 && inside; ++e)
      for (const Point2& p : tri) inside = inside && leftOf(corner[e], corner[(e + 1) % 3], p) > 0;
    if (inside) {
      lo = std::numeric_limits<double>::infinity();
      hi = -lo;
      take(s, tri, 3);
      return false;
    }
    Point2 a[9], b[9];
    int m = clipLeftOf(tri, 3, corner[0], corner[1], a);
    if (m == 0) return true;
    m = clipLeftOf(a, m, corner[1], corner[2], b);
    if (m == 0) return true;
    m = clipLeftOf(b, m, corner[2], corner[0], a);
    take(s, a, m);
    return true;
  });
  if (!(lo <= hi)) return false;
  hiPoint = {best.x, best.y, q[0].z + gx * (best.x - q[0].x) + gy * (best.y - q[0].y)};
  return true;
}

}  // namespace reamsim::detail
