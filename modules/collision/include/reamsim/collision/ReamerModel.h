#pragma once
// The reamer as the collision queries see it, in reamer-local coordinates (tip at the origin, feed +Z):
// the closed cutting solid with a BVH over all its triangles, and a second BVH over the cutting-face
// triangles only (for the face-to-bone distance). Built once per reamer; a pose is applied per query.
#include <cstdint>
#include <memory>
#include <vector>

#include "reamsim/collision/TriangleBvh.h"
#include "reamsim/core/ReamerSpec.h"
#include "reamsim/mesh/TriangleMesh.h"

namespace reamsim {

namespace detail {
class CapShadow;  // src/CapShadow.h
}

class ReamerModel {
 public:
  // `faceTriangles`: indices of the solid's triangles that form the cutting face. Throws
  // std::invalid_argument for an empty solid, an out-of-range index or an empty face.
  ReamerModel(TriangleMesh cuttingSolid, std::vector<std::uint32_t> faceTriangles);

  // Parametric reamer: the face is every triangle whose three vertices are cutting-face vertices (the
  // first cuttingFaceVertices(spec).size() vertices of buildCuttingSolid(spec)).
  static ReamerModel fromSpec(const ReamerSpec& spec);
  // A cutting solid from a file: the face is every triangle whose normal points forward (n.z > 0).
  static ReamerModel fromSolid(TriangleMesh cuttingSolid);
  // The model for a reamer node's cutting volume: fromSpec when `builtFrom` is a parametric spec and
  // `cuttingSolid` is exactly the solid built from it (its ideal solid then bounds this very mesh, which
  // makes first contact ~2.5x and the touched-face overlap ~3x faster at 400k faces), else fromSolid.
  static ReamerModel fromCuttingVolume(const TriangleMesh& cuttingSolid, const ReamerSpec* builtFrom);

  const TriangleMesh& solid() const { return solid_; }
  const std::vector<std::uint32_t>& faceTriangles() const { return face_; }  // face BVH slot -> solid triangle
  const TriangleBvh& solidBvh() const { return solidBvh_; }
  const TriangleBvh& faceBvh() const { return faceBvh_; }
  // The other triangles of the solid (body and back); slot -> solid triangle in restTriangles().
  const TriangleBvh& restBvh() const { return restBvh_; }
  const std::vector<std::uint32_t>& restTriangles() const { return rest_; }
  // Per solid-BVH node: largest distance from the tip (origin) to its box, for motion bounds.
  const std::vector<double>& solidNodeRadius() const { return solidNodeRadius_; }
  double radius() const { return radius_; }  // largest |vertex|
  // Per solid-BVH node: a slab holding its triangles (unit local axis = their area-weighted normal, and
  // the range of axis.p over their vertices). Thin for a patch of the cutting face however the reamer is
  // tilted, where the node's box, once rotated into the bone's frame, is as thick as it is wide.
  struct NodeSlab {
    Vec3 axis{0, 0, 1};
    double lo = 0, hi = 0;
  };
  const std::vector<NodeSlab>& solidNodeSlabs() const { return solidNodeSlabs_; }

  // Point strictly inside the closed cutting solid (local coordinates): the sign of p - c against the
  // angle-weighted pseudo-normal of the feature holding the closest surface point c (Baerentzen & Aanaes
  // 2005). Robust arbitrarily close to the surface, unlike crossing parity whose triangle tests have slack.
  bool containsLocal(const Vec3& p) const;
  // A thin region holding the whole cutting face, for cheap distance bounds: the face lies between the
  // heights zMin..zMax (local z) and, for a curved face, in the spherical shell rIn..rOut about `centre`
  // (fitted on the axis). A smooth cap is held to within its facets' sag.
  struct FaceRegion {
    bool shell = false;
    Vec3 centre;
    double rIn = 0, rOut = 0;
    double zMin = 0, zMax = 0;
  };
  const FaceRegion& faceRegion() const { return faceRegion_; }

  // The ideal solid a parametric reamer's mesh is inscribed in (cylinder of radius `radius` from zBack up,
  // capped by the sphere about (0,0,sphereCentreZ) above capBaseZ, or by the plane z = 0 when flat), and
  // how far the mesh's facets fall inside it. The mesh lies inside the ideal solid, so a point outside the
  // ideal solid is outside the mesh, and one deeper inside than `maxSag` is inside: containsLocal() decides
  // those without a search and searches only in the thin band between.
  struct IdealSolid {
    bool valid = false, flat = false;
    double radius = 0, zBack = 0, capBaseZ = 0, sphereCentreZ = 0, sphereRadius = 0, maxSag = 0;
    double vertexSlack = 0;  // how far a mesh vertex may lie off the ideal surface it was checked on
  };
  const IdealSolid& idealSolid() const { return ideal_; }
  // A parametric reamer's face as a height field across the axis (internal, for the axial penetration);
  // null for a solid from a file.
  const detail::CapShadow* capShadow() const { return capShadow_.get(); }
  // Unit normal of each face-BVH slot's triangle (local), for plane distance bounds.
  const std::vector<Vec3>& faceUnitNormals() const { return faceNormals_; }
  // Padded box of each face-BVH slot's triangle (TriangleBvh::paddedBox, local): the distance query bounds
  // face triangles by them for every bone triangle it measures.
  struct Box {
    Vec3 lo, hi;
  };
  const std::vector<Box>& faceBoxes() const { return faceBoxes_; }

  // Closest point of the solid's surface to p (local coordinates).
  Vec3 closestSurfacePoint(const Vec3& p) const;
  // An interior point far from the surface and its distance to it: any bone surface that does not meet the
  // solid is at least this far from the point, so crossing parity from it is reliable.
  const Vec3& deepPoint() const { return deepPoint_; }
  double deepClearance() const { return deepClearance_; }

 private:
  TriangleMesh solid_;
  std::vector<std::uint32_t> face_, rest_;
  TriangleBvh solidBvh_, faceBvh_, restBvh_;
  std::vector<double> solidNodeRadius_;
  std::vector<NodeSlab> solidNodeSlabs_;
  std::vector<Vec3> vertexNormal_, edgeNormal_, faceNormal_;  // pseudo-normals; edges as 3 x triangle + k
  Vec3 deepPoint_;
  FaceRegion faceRegion_;
  IdealSolid ideal_;
  std::shared_ptr<const detail::CapShadow> capShadow_;
  bool containsBySearch(const Vec3& p) const;
  std::vector<Vec3> faceNormals_;
  std::vector<Box> faceBoxes_;
  double deepClearance_ = 0;
  double radius_ = 0;

  Vec3 closest(const Vec3& p, std::uint32_t& triangle, int& region) const;
};

}  // namespace reamsim
