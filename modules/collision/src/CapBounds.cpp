#include "CapBounds.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "CapShadow.h"

namespace reamsim::detail {

CapBounds::CapBounds(const ReamerModel& reamer, const PoseFrame& frame)
    : frame_(frame), u_(normalized(frame.R * Vec3{0, 0, 1})) {
  const CapShadow& cap = *reamer.capShadow();
  faceTop_ = cap.top();
  faceBottom_ = cap.bottom();
  rim_ = cap.rimRadius() * (1 + 1e-12) + 1e-300;
  const ReamerModel::IdealSolid& id = reamer.idealSolid();
  // The sphere's bounds need its slope finite over the disc.
  sphere_ = id.valid && !id.flat && id.radius < 0.99 * id.sphereRadius;
  if (!sphere_) return;
  sphereRadius_ = id.sphereRadius;
  sphereCentreZ_ = id.sphereCentreZ;
  idealRadius_ = id.radius;
  // maxSag and vertexSlack are distances from the sphere along its radius; along the axis they grow by at
  // most Rs / h, h the rim's height above the sphere's centre (a point dr inside the sphere at height z
  // above the centre lies below it by sqrt(z^2 + Rs^2 - rho^2) - z <= dr Rs / z, and no face point is lower
  // than the rim).
  const double steepening = sphereRadius_ / std::sqrt(sphereRadius_ * sphereRadius_ - idealRadius_ * idealRadius_);
  belowSphere_ = id.maxSag * steepening * (1 + 1e-9);
  aboveSphere_ = id.vertexSlack * steepening * (1 + 1e-9);
}

// The ideal sphere's tangent plane above the shadow point (px, py), moved onto the face's disc: top(p) <=
// gx p.x + gy p.y + k over the whole disc.
void CapBounds::tangentPlane(double px, double py, double& gx, double& gy, double& k) const {
  const double r = std::hypot(px, py);
  if (r > rim_) {
    px *= rim_ / r;
    py *= rim_ / r;
  }
  const double root = std::sqrt(sphereRadius_ * sphereRadius_ - (px * px + py * py));
  gx = -px / root;
  gy = -py / root;
  k = sphereCentreZ_ + root - (gx * px + gy * py);
}

// The ideal sphere's height at r from the axis (clamped to the disc) less the facets' sag along the axis: the
// face's top is at least this; concave across the axis, falling away from it.
double CapBounds::sphereTopLessSag(double r) const {
  const double c = std::min(r, idealRadius_);
  return sphereCentreZ_ + std::sqrt(std::max(0.0, sphereRadius_ * sphereRadius_ - c * c)) - belowSphere_;
}

bool CapBounds::node(const Vec3& lo, const Vec3& hi, const BvhSlab& slab, double& dlo, double& dhi) const {
  const Vec3 cl = frame_.toLocal((lo + hi) * 0.5);
  const double halfDiagonal = 0.5 * norm(hi - lo);
  const double rc = std::hypot(cl.x, cl.y);
  if (rc - halfDiagonal * (1 + 1e-12) > rim_) return false;  // wholly outside the face's shadow
  const BoxSlabRegion region(lo, hi, slab);
  double zlo, zhi;
  region.range(u_, zlo, zhi);
  const double ut = dot(u_, frame_.t);
  zlo -= ut;
  zhi -= ut;
  dhi = faceTop_ - zlo;
  dlo = faceBottom_ - zhi;
  double pad = 1e-12 * (std::abs(faceTop_) + std::abs(faceBottom_) + std::abs(zlo) + std::abs(zhi) + std::abs(ut));
  if (sphere_) {
    // The shadow lies within halfDiagonal of the middle's, where the sphere is no lower than farther out.
    dlo = std::max(dlo, sphereTopLessSag(rc + halfDiagonal) - zhi);
    double gx, gy, k;
    tangentPlane(cl.x, cl.y, gx, gy, k);
    // top(p) <= g . p + k, so d <= g.x qx + g.y qy - qz + k: a world linear function over the region.
    const Vec3 w = frame_.R * Vec3{gx, gy, -1};
    double wlo, whi;
    region.range(w, wlo, whi);
    const double wt = dot(w, frame_.t);
    dhi = std::min(dhi, whi - wt + k + aboveSphere_);
    // The tangent point is the middle's shadow moved onto the disc: the region's shadow lies within rho of
    // it, where the sphere's curvature is at most its radial one at rMax.
    const double rho = halfDiagonal + std::max(0.0, rc - rim_);
    const double rMax = std::min(idealRadius_, std::min(rim_, rc) + rho);
    const double across = sphereRadius_ * sphereRadius_ - rMax * rMax;
    const double curvature = sphereRadius_ * sphereRadius_ / (across * std::sqrt(across));
    dlo = std::max(dlo, wlo - wt + k - 0.5 * curvature * rho * rho - belowSphere_);
    pad += 1e-12 * (std::abs(wlo) + std::abs(whi) + std::abs(k) + std::abs(wt));
  }
  dlo -= pad + 1e-300;
  dhi += pad + 1e-300;
  return true;
}

void CapBounds::triangle(const Vec3 (&q)[3], double& dlo, double& dhi) const {
  const double qzlo = std::min({q[0].z, q[1].z, q[2].z}), qzhi = std::max({q[0].z, q[1].z, q[2].z});
  dhi = faceTop_ - qzlo;
  dlo = faceBottom_ - qzhi;
  double scale = std::abs(faceTop_) + std::abs(faceBottom_) + std::abs(qzlo) + std::abs(qzhi);
  if (sphere_) {
    double gx, gy, k;
    tangentPlane((q[0].x + q[1].x + q[2].x) / 3, (q[0].y + q[1].y + q[2].y) / 3, gx, gy, k);
    double tangent = -std::numeric_limits<double>::infinity();
    for (const Vec3& v : q) tangent = std::max(tangent, gx * v.x + gy * v.y - v.z + k);
    dhi = std::min(dhi, tangent + aboveSphere_);
    scale += std::abs(tangent) + std::abs(k);
    // The sphere's height less the sag, less the triangle's, is concave over the triangle's part above the
    // disc: least at a corner inside the disc or on the disc's edge (no lower than the rim there).
    double concave = std::numeric_limits<double>::infinity();
    bool outside = false;
    for (const Vec3& v : q) {
      const double r = std::hypot(v.x, v.y);
      outside = outside || r > idealRadius_;
      concave = std::min(concave, sphereTopLessSag(r) - v.z);
    }
    if (outside) concave = std::min(concave, sphereTopLessSag(idealRadius_) - qzhi);
    dlo = std::max(dlo, concave);
    scale += std::abs(concave);
  }
  dlo -= 1e-12 * scale + 1e-300;
  dhi += 1e-12 * scale + 1e-300;
}

}  // namespace reamsim::detail
