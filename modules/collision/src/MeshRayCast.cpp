#include "reamsim/collision/MeshRayCast.h"

#include <algorithm>
#include <cmath>

#include "QueryArguments.h"

namespace reamsim {

namespace {
MeshHit toMeshHit(const RayHit& h, std::size_t triangle, const Vec3& origin, const Vec3& dir) {
  return MeshHit{h.t, h.u, h.v, h.frontFacing, triangle, origin + dir * h.t};
}
}  // namespace

std::optional<MeshHit> firstHit(const TriangleMesh& mesh, const Vec3& origin, const Vec3& dir, Culling culling) {
  detail::requireRay(origin, dir, "firstHit");
  std::optional<MeshHit> best;
  for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
    const Triangle& tri = mesh.triangles[i];
    const auto h = intersectRayTriangle(origin, dir, mesh.vertices[tri[0]], mesh.vertices[tri[1]],
                                        mesh.vertices[tri[2]], culling);
    if (h && (!best || h->t < best->t)) best = toMeshHit(*h, i, origin, dir);
  }
  return best;
}

std::optional<MeshHit> firstHit(const BoneState& bone, const Vec3& origin, const Vec3& dir, Culling culling) {
  detail::requireRay(origin, dir, "firstHit");
  std::optional<MeshHit> best;
  bone.forEachLiveTriangle([&](std::uint32_t slot, const Triangle& tri) {
    const auto h = intersectRayTriangle(origin, dir, bone.vertex(tri[0]), bone.vertex(tri[1]), bone.vertex(tri[2]), culling);
    if (h && (!best || h->t < best->t)) best = toMeshHit(*h, slot, origin, dir);
  });
  return best;
}

std::vector<MeshHit> allHits(const TriangleMesh& mesh, const Vec3& origin, const Vec3& dir, Culling culling) {
  detail::requireRay(origin, dir, "allHits");
  std::vector<MeshHit> raw;
  for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
    const Triangle& tri = mesh.triangles[i];
    const auto h = intersectRayTriangle(origin, dir, mesh.vertices[tri[0]], mesh.vertices[tri[1]],
                                        mesh.vertices[tri[2]], culling);
    if (h) raw.push_back(toMeshHit(*h, i, origin, dir));
  }
  return mergeCrossings(std::move(raw));
}

std::vector<MeshHit> mergeCrossings(std::vector<MeshHit> raw) {
  // Sort by t, ties by triangle index so the result does not depend on the sort's stability.
  std::sort(raw.begin(), raw.end(), [](const MeshHit& x, const MeshHit& y) {
    return x.t < y.t || (x.t == y.t && x.triangle < y.triangle);
  });
  std::vector<MeshHit> out;
  out.reserve(raw.size());
  for (const MeshHit& h : raw) {
    const double tol = kHitMergeEpsilon * std::max(1.0, std::abs(h.t));
    bool duplicate = false;
    // Kept hits are sorted too, so only the tail can be within tolerance.
    for (auto it = out.rbegin(); it != out.rend() && h.t - it->t <= tol; ++it)
      if (it->frontFacing == h.frontFacing) { duplicate = true; break; }
    if (!duplicate) out.push_back(h);
  }
  return out;
}

}  // namespace reamsim
