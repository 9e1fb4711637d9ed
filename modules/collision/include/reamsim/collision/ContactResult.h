#pragma once
// What the reaming loop learns from a contact query at one reamer pose, whichever engine answered it: the
// thesis's rays (ThesisContact.h) or the BVH queries (BoneCollider.h). The GUI's status bar and the alerts
// are made from it.
#include <cstddef>
#include <limits>
#include <optional>

#include "reamsim/mesh/Vec3.h"

namespace reamsim {

// Where a move first brought the cutting solid's surface onto the bone's: the first-contact query
// (FirstContact.h) between the pose before the move and the pose after it.
struct MoveContact {
  bool reached = false;  // false: the surfaces never meet along the move
  double t = 1;          // fraction of the move at first contact (0: touching at its start)
  Vec3 point, normal;    // on the bone; the normal points from the bone towards the reamer
};

struct ContactResult {
  // Broad phase: bone box vs the reamer's box grown by stepMm (a gap <= stepMm cannot hide outside it).
  // When false nothing else is queried and contact is false.
  bool boxesOverlap = false;
  bool contact = false;      // the reamer touches or enters the bone (thesis rays: or the gap is <= stepMm)
  bool penetrating = false;  // the cutting volume enters the bone
  double minDistanceMm = std::numeric_limits<double>::infinity();  // 0 when penetrating; +inf: no hit
  double penetrationDepthMm = 0;     // how far the reamer must back out along its axis to leave the bone
  std::optional<Vec3> contactPoint;  // on the bone: the deepest or the closest point
  // Exact engines only: whether the closed cutting solid overlaps the bone (touching counts). When set,
  // the reaming loop runs the Boolean only if it is true; otherwise whenever the boxes overlap.
  std::optional<bool> solidOverlapsBone;
  std::size_t touchedFaces = 0;  // bone faces the cutting solid touches (exact engines)
  // Exact engines, for a step that moved the reamer (ContactInput::movedFrom): the first contact along the
  // move. With solidOverlapsBone false at the end pose, `reached` false means a translation swept past
  // the bone without touching it, so the loop has nothing to cut (ReamEngine skips the swept hull).
  std::optional<MoveContact> alongMove;
  // Thesis rays only.
  std::size_t insideVertices = 0;
  std::size_t raysCast = 0;  // forward + backward rays
};

}  // namespace reamsim
