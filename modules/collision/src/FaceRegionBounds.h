#pragma once
// Internal: bounds between bone geometry (world) and the region holding the reamer's cutting face
// (ReamerModel::FaceRegion) under a pose. Squared lower bounds on the distance to the face; zero means the
// geometry may meet the face region (and so may cross the face).
#include <algorithm>
#include <cmath>

#include "PoseFrame.h"
#include "reamsim/collision/ReamerModel.h"
#include "reamsim/collision/TriangleBvh.h"
#include "reamsim/collision/TriangleGeometry.h"

namespace reamsim::detail {

class FaceRegionBounds {
 public:
  FaceRegionBounds(const ReamerModel& reamer, const PoseFrame& frame) : r_(reamer.faceRegion()) {
    centre_ = frame.toWorld(r_.centre);
    axis_ = frame.R * Vec3{0, 0, 1};
    z0_ = dot(axis_, frame.t);  // local z = axis . x - z0
  }

  // Squared lower bound for a bone node over its box ∩ slab (TriangleBvh.h). A patch of surface is thin
  // along its own normal however it is tilted, where its box is as thick as it is wide: where the bone runs
  // parallel to the face (a reamer seated in the glenoid, a flat reamer on a plateau) the box's corners reach
  // far nearer the face than the patch does, and a search bounded by boxes alone opens every node down to
  // the size of the gap. Only the terms that pay for themselves in the searches are kept (measured with
  // callgrind on the hand-held path and random poses, session 20).
  double node(const Vec3& lo, const Vec3& hi, const BvhSlab& slab) const {
    double out[2];
    nodes(lo, hi, slab, lo, hi, slab, out);
    return out[0];
  }

  // node() for two nodes at once (the children of a node a search opens). For a shell the terms run in
  // lockstep, without branches, so the compiler keeps the two nodes in the two lanes of a vector register:
  // the bound is a chain of dependent operations with a square root and a division in it (-11 % on the
  // hand-held path's distance queries at 405k against one node at a time).
  void nodes(const Vec3& lo0, const Vec3& hi0, const BvhSlab& s0, const Vec3& lo1, const Vec3& hi1, const BvhSlab& s1,
             double out[2]) const {
    if (!r_.shell) {  // a plane: along the axis over box ∩ slab (never looser than the box's own z range)
      out[0] = flatGap2(lo0, hi0, s0);
      out[1] = flatGap2(lo1, hi1, s1);
      return;
    }
    const Vec3* lop[2] = {&lo0, &lo1};
    const Vec3* hip[2] = {&hi0, &hi1};
    const BvhSlab* sl[2] = {&s0, &s1};
    double c[3][2], h[3][2], lo[3][2], hi[3][2], ax[3][2], slo[2], shi[2];
    for (int k = 0; k < 2; ++k) {
      for (int i = 0; i < 3; ++i) {
        lo[i][k] = (*lop[k])[i];
        hi[i][k] = (*hip[k])[i];
        ax[i][k] = sl[k]->axis[i];
        c[i][k] = (lo[i][k] + hi[i][k]) * 0.5;
        h[i][k] = (hi[i][k] - lo[i][k]) * 0.5;
      }
      slo[k] = sl[k]->lo;
      shi[k] = sl[k]->hi;
    }
    double gap[2], d[3][2], len[2], u[3][2];
    for (int k = 0; k < 2; ++k) {
      // Along the axis by the box alone: the shell term decides nodes over the cap, where the slab would
      // narrow this range for nothing (a ~20 % dearer bound, measured on the hand-held path).
      const double zc = axis_.x * c[0][k] + axis_.y * c[1][k] + axis_.z * c[2][k] - z0_;
      const double zh = std::abs(axis_.x) * h[0][k] + std::abs(axis_.y) * h[1][k] + std::abs(axis_.z) * h[2][k];
      gap[k] = std::max(0.0, std::max(zc - zh - r_.zMax, r_.zMin - (zc + zh)));
      for (int i = 0; i < 3; ++i) d[i][k] = c[i][k] - centre_[i];
      len[k] = std::sqrt(d[0][k] * d[0][k] + d[1][k] * d[1][k] + d[2][k] * d[2][k]);
      const double l = len[k] > 0 ? len[k] : 1.0;
      for (int i = 0; i < 3; ++i) u[i][k] = d[i][k] / l;
    }
    for (int k = 0; k < 2; ++k) {
      // Along the direction u from the centre to the box's middle (|x - c| >= u . (x - c)), over box ∩ slab
      // as BoxSlabRegion::range: the box's own range, and the slab's range plus the box's range across it.
      const double uc = u[0][k] * c[0][k] + u[1][k] * c[1][k] + u[2][k] * c[2][k];
      const double uh = std::abs(u[0][k]) * h[0][k] + std::abs(u[1][k]) * h[1][k] + std::abs(u[2][k]) * h[2][k];
      const double a = u[0][k] * ax[0][k] + u[1][k] * ax[1][k] + u[2][k] * ax[2][k];
      const double w0 = u[0][k] - ax[0][k] * a, w1 = u[1][k] - ax[1][k] * a, w2 = u[2][k] - ax[2][k] * a;
      const double wc = w0 * c[0][k] + w1 * c[1][k] + w2 * c[2][k];
      const double wh = std::abs(w0) * h[0][k] + std::abs(w1) * h[1][k] + std::abs(w2) * h[2][k];
      const double sLow = a >= 0 ? a * slo[k] : a * shi[k];
      const double pad = 1e-12 * (std::abs(uc) + std::abs(slo[k]) + std::abs(shi[k]) + h[0][k] + h[1][k] + h[2][k]) + 1e-300;
      const double ulo = std::max(uc - uh, sLow + (wc - wh)) - pad;
      const double ucen = u[0][k] * centre_.x + u[1][k] * centre_.y + u[2][k] * centre_.z;
      const double g = ulo - ucen - r_.rOut - 1e-12 * (std::abs(ucen) + r_.rOut);
      gap[k] = len[k] > 0 ? std::max(gap[k], g) : gap[k];
    }
    for (int k = 0; k < 2; ++k) {
      // The farthest corner, for bone inside the inner sphere (the range above bounds only from outside).
      // (The box's nearest point to the centre is left out: beside the range it pruned too little to pay
      // for itself, -8 % instructions at 405k without it.)
      double far2 = 0;
      for (int i = 0; i < 3; ++i) {
        const double a = centre_[i] - lo[i][k], b = centre_[i] - hi[i][k];
        far2 += std::max(a * a, b * b);
      }
      const double inner = r_.rIn - gap[k];
      const double g = r_.rIn - std::sqrt(far2);
      gap[k] = inner > 0 && far2 < inner * inner ? std::max(gap[k], g) : gap[k];
      out[k] = gap[k] * gap[k];
    }
  }

  // Is a's box centre nearer the region's middle surface (sphere or plane) than b's? A search for a crossing
  // looks there first.
  bool nearerToSurface(const BvhNode& a, const BvhNode& b) const { return offset(a) < offset(b); }

  double triangle(const BvhTriangle& t) const {
    const double za = dot(axis_, t.a) - z0_, zb = dot(axis_, t.b) - z0_, zc = dot(axis_, t.c) - z0_;
    double gap = std::max({0.0, std::min({za, zb, zc}) - r_.zMax, r_.zMin - std::max({za, zb, zc})});
    if (r_.shell) {
      const double near = norm(closestPointOnTriangle(centre_, t.a, t.b, t.c) - centre_);
      const double far = std::sqrt(std::max({squaredNorm(t.a - centre_), squaredNorm(t.b - centre_), squaredNorm(t.c - centre_)}));
      gap = std::max({gap, near - r_.rOut, r_.rIn - far});
    }
    return gap * gap;
  }

 private:
  double offset(const BvhNode& n) const {
    const Vec3 c = (n.lo + n.hi) * 0.5;
    if (r_.shell) return std::abs(norm(c - centre_) - 0.5 * (r_.rIn + r_.rOut));
    return std::abs(dot(axis_, c) - z0_ - 0.5 * (r_.zMin + r_.zMax));
  }

  double flatGap2(const Vec3& lo, const Vec3& hi, const BvhSlab& slab) const {
    double zlo, zhi;
    BoxSlabRegion(lo, hi, slab).range(axis_, zlo, zhi);
    const double gap = std::max({0.0, zlo - z0_ - r_.zMax, r_.zMin - (zhi - z0_)});
    return gap * gap;
  }

  const ReamerModel::FaceRegion& r_;
  Vec3 centre_, axis_;
  double z0_ = 0;
};

}  // namespace reamsim::detail
