#pragma once
// Internal: conservative bounds on where a parametric reamer's cutting face, backed out along its axis, can
// touch bone (PenetrationQuery.cpp's face path; CapShadow.h gives the exact interval of one triangle).
//
// Backed out by d, the face touches a bone point q (reamer frame) at d = top(q.xy) - q.z, where top is the
// face's height over its shadow. The face's top lies between its lowest and highest vertex. For a spherical
// cap it also lies within the ideal sphere's height less the facets' sag and that height (plus the slack of
// vertices rounded off the sphere), both measured along the axis: the sphere is concave across the axis, so
// its tangent plane at any shadow point bounds it from above over the whole disc and, less half its largest
// curvature times the squared distance from that point, from below.
#include "PoseFrame.h"
#include "reamsim/collision/ReamerModel.h"
#include "reamsim/collision/TriangleBvh.h"

namespace reamsim::detail {

class CapBounds {
 public:
  // `reamer` must have a face height field (ReamerModel::capShadow()); `frame` is the reamer's pose.
  CapBounds(const ReamerModel& reamer, const PoseFrame& frame);

  // Where the face can touch a bone point within the world box [lo, hi] ∩ slab: [dlo, dhi]. False when the
  // region lies wholly outside the face's shadow (it cannot touch at any d).
  bool node(const Vec3& lo, const Vec3& hi, const BvhSlab& slab, double& dlo, double& dhi) const;
  // The same for a bone triangle given in the reamer frame; it holds CapShadow::interval's interval.
  void triangle(const Vec3 (&q)[3], double& dlo, double& dhi) const;

 private:
  const PoseFrame& frame_;
  Vec3 u_;  // the axis in the world
  double faceTop_ = 0, faceBottom_ = 0, rim_ = 0;
  bool sphere_ = false;  // a spherical cap whose slope is finite over the disc: the ideal sphere's bounds apply
  double sphereRadius_ = 0, sphereCentreZ_ = 0, idealRadius_ = 0;
  double belowSphere_ = 0, aboveSphere_ = 0;  // how far the face's top may lie below / above the sphere

  void tangentPlane(double px, double py, double& gx, double& gy, double& k) const;
  double sphereTopLessSag(double r) const;
};

}  // namespace reamsim::detail
