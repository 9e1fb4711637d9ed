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

  double box(const Vec3& lo, const Vec3& hi) const {
    double zlo = -z0_, zhi = -z0_;
    for (int k = 0; k < 3; ++k) {
      zlo += axis_[k] * (axis_[k] > 0 ? lo[k] : hi[k]);
      zhi += axis_[k] * (axis_[k] > 0 ? hi[k] : lo[k]);
    }
    double gap = std::max({0.0, zlo - r_.zMax, r_.zMin - zhi});
    if (r_.shell) {
      double far2 = 0;
      for (int k = 0; k < 3; ++k) {
        const double a = centre_[k] - lo[k], b = centre_[k] - hi[k];
        far2 += std::max(a * a, b * b);
      }
      gap = std::max({gap, std::sqrt(boxSquaredDistance(lo, hi, centre_, centre_)) - r_.rOut, r_.rIn - std::sqrt(far2)});
    }
    return gap * gap;
  }

  // The same over a node's box ∩ slab (TriangleBvh.h). A patch of surface is thin along its own normal
  // however it is tilted, where its box is as thick as it is wide: where the bone runs parallel to the face
  // (a reamer seated in the glenoid, a flat reamer on a plateau) the box's corners reach far nearer the face
  // than the patch does, and a search bounded by boxes alone opens every node down to the size of the gap.
  // Ranged along the axis (z) and, for a shell, along the direction from the centre to the box's middle
  // (|x - c| >= u . (x - c) for unit u). A lower bound like box(), not always as tight: it keeps the terms
  // that pay for themselves in the searches (measured with callgrind on the hand-held path and random poses).
  double node(const Vec3& lo, const Vec3& hi, const BvhSlab& slab) const {
    const BoxSlabRegion region(lo, hi, slab);
    double gap;
    if (r_.shell) {
      // Along the axis by the box alone: the shell term below decides nodes over the cap, where the slab
      // would narrow this range for nothing (a ~20 % dearer bound, measured on the hand-held path).
      const double zc = dot(axis_, region.c) - z0_;
      const double zh = std::abs(axis_.x) * region.h.x + std::abs(axis_.y) * region.h.y + std::abs(axis_.z) * region.h.z;
      gap = std::max({0.0, zc - zh - r_.zMax, r_.zMin - (zc + zh)});
    } else {
      double zlo, zhi;
      region.range(axis_, zlo, zhi);  // never looser than the box's own z range beyond its rounding pad
      const double zgap = std::max({0.0, zlo - z0_ - r_.zMax, r_.zMin - (zhi - z0_)});
      return zgap * zgap;
    }
    const Vec3 toMiddle = region.c - centre_;
    const double len = norm(toMiddle);
    if (len > 0) {
      double ulo, uhi;
      region.range(toMiddle / len, ulo, uhi);
      const double uc = dot(toMiddle / len, centre_);
      gap = std::max(gap, ulo - uc - r_.rOut - 1e-12 * (std::abs(uc) + r_.rOut));
    }
    // The farthest corner for bone inside the inner sphere (the range above bounds only from outside),
    // computed only when it can raise the gap: no corner is nearer the centre than the box's middle. (The
    // nearest box point, box()'s other shell term, is left out: beside the range along u it pruned too
    // little to pay for itself, -3 to -5 % instructions without it.)
    const double inner = r_.rIn - gap;
    if (len < inner) {
      double far2 = 0;
      for (int k = 0; k < 3; ++k) {
        const double a = centre_[k] - lo[k], b = centre_[k] - hi[k];
        far2 += std::max(a * a, b * b);
      }
      if (far2 < inner * inner) gap = std::max(gap, r_.rIn - std::sqrt(far2));
    }
    return gap * gap;
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

  const ReamerModel::FaceRegion& r_;
  Vec3 centre_, axis_;
  double z0_ = 0;
};

}  // namespace reamsim::detail
