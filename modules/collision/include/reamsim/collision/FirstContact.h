#pragma once
// Query 3: first contact of the reamer's cutting solid with the bone along a motion between two poses
// (translation and rotation). Time of impact in [0, 1], contact point and normal.
//
// Path: the tip moves linearly; the orientation turns about the fixed axis of R1 R0^T, in segments of at
// most 90 degrees, with tan(phi/2) proportional to the time within a segment (a rational parametrisation
// that makes every contact condition a cubic: see docs/COLLISION.md). interpolateMotion() gives the pose at
// any t, so callers can place the reamer exactly where contact happens.
//
// Contact = the two surfaces touch (closed triangles, touching counts). The first contact of two triangles
// is a vertex reaching a face or an edge reaching an edge; each is the earliest valid root of a cubic.
// Triangle pairs whose contact would need in-plane sliding of coplanar features (identically-zero cubics)
// fall back to conservative advancement on that pair, to kFallbackToleranceMm.
#include <cstddef>
#include <cstdint>

#include "reamsim/collision/ReamerModel.h"
#include "reamsim/collision/TriangleBvh.h"
#include "reamsim/core/Pose.h"

namespace reamsim {

inline constexpr double kFallbackToleranceMm = 1e-9;

enum class ContactFeature {
  None,
  Initial,               // already touching or crossing at t = 0
  ReamerVertexBoneFace,
  BoneVertexReamerFace,
  EdgeEdge,
  Fallback,              // conservative advancement on a degenerate pair
};

struct FirstContactResult {
  bool hit = false;
  double t = 1;          // time of impact in [0, 1]; 1 when there is no contact
  Vec3 point;            // contact point, bone coordinates
  Vec3 normal;           // unit, from the bone towards the reamer (the direction that separates them)
  std::uint32_t boneSlot = 0;
  std::uint32_t reamerTriangle = 0;  // index into reamer.solid().triangles
  ContactFeature feature = ContactFeature::None;
  std::size_t trianglePairs = 0;     // exact triangle-pair evaluations (a cost indicator)
  // What else the query did, as counts (cost indicators: `bench collision` reports them per kind of motion,
  // docs/COLLISION.md). The first three are counted for a parametric reamer only (zero for a reamer read
  // from a file, whose start test and search take other paths).
  struct Work {
    std::size_t startTestNodes = 0;  // bone nodes the cutting face's start test opened
    std::size_t sweepPassNodes = 0;  // bone nodes the yes/no pass over the ideal solid's sweep took
    std::size_t hullBounds = 0;      // bone nodes bounded against the moving ideal solid by the search
    std::size_t pairBounds = 0;      // (bone, reamer) triangle pairs given the pair bounds
  } work;
};

FirstContactResult queryFirstContact(const TriangleBvh& bone, const ReamerModel& reamer, const RigidTransform& from,
                                     const RigidTransform& to);
FirstContactResult queryFirstContact(const TriangleBvh& bone, const ReamerModel& reamer, const Pose& from,
                                     const Pose& to);

// The pose of the path above at t in [0, 1].
RigidTransform interpolateMotion(const RigidTransform& from, const RigidTransform& to, double t);

}  // namespace reamsim
