#include "reamsim/collision/ThesisContact.h"

#include <cmath>
#include <stdexcept>

#include "reamsim/collision/BroadPhase.h"
#include "reamsim/collision/MeshRayCast.h"

namespace reamsim {

ContactResult thesisContactQuery(const TriangleMesh& bone, const Bounds& boneBounds,
                                 const TriangleMesh& cuttingSolidInBoneCoords,
                                 const std::vector<Vec3>& cuttingFaceVerticesInBoneCoords, const Vec3& feedAxis,
                                 double stepMm) {
  const double axisLength = norm(feedAxis);
  if (!(axisLength > 0) || !isFinite(feedAxis))
    throw std::invalid_argument("thesisContactQuery: feed axis must be a non-zero finite vector");
  if (!(stepMm >= 0) || !std::isfinite(stepMm))
    throw std::invalid_argument("thesisContactQuery: stepMm must be a finite number >= 0");
  const Vec3 axis = feedAxis / axisLength;

  ContactResult r;
  // Broad phase. Growing the reamer box by one step in every direction keeps it conservative: a vertex
  // that reaches the bone within stepMm along the axis stays inside the grown box.
  Bounds reamerBox = computeBounds(cuttingSolidInBoneCoords);
  for (const Vec3& p : cuttingFaceVerticesInBoneCoords) reamerBox.add(p);
  r.boxesOverlap = boundsOverlap(boneBounds, reamerBox.expanded(stepMm));
  if (!r.boxesOverlap) return r;

  double minGap = std::numeric_limits<double>::infinity();
  std::optional<Vec3> closestPoint, deepestPoint;
  for (const Vec3& p : cuttingFaceVerticesInBoneCoords) {
    const std::vector<MeshHit> hits = allHits(bone, p, axis);
    ++r.raysCast;
    if (hits.size() % 2 == 1) {
      // Odd number of crossings ahead: the vertex is inside the bone. Its depth is how far it must back
      // out along -axis to leave the bone.
      ++r.insideVertices;
      const std::optional<MeshHit> back = firstHit(bone, p, -axis);
      ++r.raysCast;
      const double depth = back ? back->t : 0.0;  // no back hit only for an open bone mesh
      if (!deepestPoint || depth > r.penetrationDepthMm) {
        r.penetrationDepthMm = depth;
        deepestPoint = back ? back->point : p;
      }
    } else if (!hits.empty() && hits.front().t < minGap) {
      minGap = hits.front().t;
      closestPoint = hits.front().point;
    }
  }
  r.penetrating = r.insideVertices > 0;
  r.minDistanceMm = r.penetrating ? 0.0 : minGap;
  r.contact = r.penetrating || minGap <= stepMm;
  r.contactPoint = r.penetrating ? deepestPoint : closestPoint;
  return r;
}

}  // namespace reamsim
