#pragma once
// The volume a reamer's cutting solid sweeps between two poses, for cuts that must leave no ridge when the
// reamer moves further than its own size between two computed steps (a fast hand move, a coarse plan).
//
// For a translation (same orientation at both poses) the volume a convex solid sweeps is exactly the convex
// hull of its two placements; every hull vertex is a placed vertex, so nothing is approximated. A move that
// turns the reamer sweeps no hull (and the hull of its two placements reaches bone no placement between
// them reaches, first order in the angle: the wedge under a flat reamer's tilting face): it is cut in
// sub-steps along `TurnPath` (placements, or translation hulls where the tip travels sideways; ReamEngine).
#include <optional>
#include <vector>

#include "reamsim/core/Pose.h"
#include "reamsim/mesh/TriangleMesh.h"

namespace reamsim {

// Closed mesh whose vertices all lie on or behind every face's plane (within a relative tolerance).
bool isConvexSolid(const TriangleMesh& closedMesh, double relativeTolerance = 1e-9);

// The volume `convexSolidLocal` sweeps moving from `from` to `to` without turning: its Minkowski sum with the
// move, which for a convex solid is the convex hull of its two placements. Built from the solid's own faces
// (those facing away from the move at `from`, those facing along it at `to`) and its silhouette edges swept
// into parallelograms (two triangles each, on the shorter diagonal), outward, closed, the same every time for
// the same input (vertices in the input's order, triangles sorted). Empty when that surface fails its checks
// on the placed points (one closed piece of genus 0, no triangle with an angle under ~1e-6 rad, no edge reflex
// beyond rounding, no face folded back onto its neighbour), as nearly degenerate moves make it (a feed along
// the axis: the strips between the cylinder's edges become needles). ~0.4 ms for the glenoid reamer.
// Throws std::invalid_argument when the two rotations differ.
std::optional<TriangleMesh> sweptBySilhouette(const TriangleMesh& convexSolidLocal, const RigidTransform& from,
                                              const RigidTransform& to);

// Convex hull of `convexSolidLocal` placed at `from` and at `to` (CGAL convex_hull_3, exact predicates),
// triangulated and outward, the same every time for the same input: its vertices are the hull's corners
// (points inside a planar face or on an edge are left out), in the input's order; each planar face of
// several triangles is split by its corners' Delaunay triangulation in its plane; triangles are sorted.
// 6-9 ms for the glenoid reamer. Throws std::invalid_argument when the two rotations differ.
TriangleMesh hullOfPlacements(const TriangleMesh& convexSolidLocal, const RigidTransform& from,
                              const RigidTransform& to);

// sweptBySilhouette, or hullOfPlacements where that is empty. Throws std::invalid_argument when the two
// rotations differ.
TriangleMesh sweptByTranslation(const TriangleMesh& convexSolidLocal, const RigidTransform& from,
                                const RigidTransform& to);

// A move from `from` to `to` whose axes (local +Z) differ, as the turn the cuts follow: the tip moves
// linearly and the axis swings on the great circle between the two, the solid keeping its roll relative to
// the swing (a reamer spins, so the roll changes only its facets). `at(s)` is the pose at s in [0, 1]
// (`at(1)` is `to` itself, roll included).
class TurnPath {
 public:
  // Empty (no turn) when the axes are the same (a translation: `sweptByTranslation`), opposite (no unique
  // turn) or not finite.
  TurnPath(const RigidTransform& from, const RigidTransform& to);
  bool isTurn() const { return angle_ > 0; }
  double angle() const { return angle_; }  // radians
  double sidewaysTravelMm() const;  // the tip's travel across the end pose's axis
  RigidTransform at(double s) const;

 private:
  RigidTransform from_, to_;
  Vec3 k_;
  double angle_ = 0;
};

// Sub-steps that keep every point within `radiusMm` of the tip from moving more than `maxTravelMm` in one,
// counting the turn and, with `countSidewaysTravel`, the tip's travel across the end pose's axis (travel
// along it is a feed, which the solid's own length covers); at least 1, at most `maxSteps`.
int turnSubSteps(const TurnPath& path, double radiusMm, double maxTravelMm, bool countSidewaysTravel,
                 int maxSteps = 96);

}  // namespace reamsim
