#pragma once
// Brute-force ray casts over every triangle of a mesh (deliberately no BVH: this is the reference path).
#include <cstddef>
#include <optional>
#include <vector>

#include "reamsim/collision/RayTriangle.h"
#include "reamsim/core/BoneState.h"
#include "reamsim/mesh/TriangleMesh.h"

namespace reamsim {

struct MeshHit {
  double t = 0;
  double u = 0, v = 0;
  bool frontFacing = true;
  std::size_t triangle = 0;  // index into mesh.triangles
  Vec3 point;                // origin + t * dir
};

// Nearest hit (smallest t >= 0), or nullopt.
std::optional<MeshHit> firstHit(const TriangleMesh& mesh, const Vec3& origin, const Vec3& dir,
                                 Culling culling = Culling::None);

// The same over a bone state's live triangles, read in place (no mesh copy: a click in the view on a bone of
// millions of faces); `triangle` is the slot. Ties in t go to the lowest slot.
std::optional<MeshHit> firstHit(const BoneState& bone, const Vec3& origin, const Vec3& dir,
                                 Culling culling = Culling::None);

// Distinct surface crossings sorted by t. Hits whose t agree within kHitMergeEpsilon * max(1, |t|) and
// that face the same way (both entering or both leaving) are one crossing through a shared edge or vertex
// and are reported once. Same-t hits facing opposite ways (a ray grazing a silhouette edge) are both
// kept, so the crossing count stays even for a ray that only touches the solid. For a closed mesh the
// count is odd exactly when the origin is inside (ignoring rays that lie in a face's plane).
inline constexpr double kHitMergeEpsilon = 1e-9;
std::vector<MeshHit> allHits(const TriangleMesh& mesh, const Vec3& origin, const Vec3& dir,
                             Culling culling = Culling::None);

// The merge rule above applied to raw per-triangle hits (any order); shared with the BVH ray casts so both
// paths report identical crossings.
std::vector<MeshHit> mergeCrossings(std::vector<MeshHit> raw);

}  // namespace reamsim
