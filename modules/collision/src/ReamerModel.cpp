#include "reamsim/collision/ReamerModel.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include <map>
#include <utility>

#include "CapShadow.h"
#include "reamsim/collision/TriangleGeometry.h"
#include "reamsim/tools/ReamerGeometry.h"

namespace reamsim {

namespace {

// Slabs of every node (see ReamerModel::NodeSlab), bottom-up: a node's triangles are its leaf slots or its
// children's, gathered once per level (the reamer tree is small).
std::vector<ReamerModel::NodeSlab> nodeSlabs(const TriangleBvh& bvh) {
  const auto& nodes = bvh.nodes();
  std::vector<ReamerModel::NodeSlab> out(nodes.size());
  std::vector<std::vector<std::uint32_t>> slots(nodes.size());
  // Post-order without recursion: children before parents.
  std::vector<std::pair<std::int32_t, bool>> stack{{bvh.root(), false}};
  while (!stack.empty()) {
    auto [i, expanded] = stack.back();
    stack.pop_back();
    if (i < 0) continue;
    const BvhNode& n = nodes[i];
    if (!expanded && !n.isLeaf()) {
      stack.push_back({i, true});
      stack.push_back({n.left, false});
      stack.push_back({n.right, false});
      continue;
    }
    if (n.isLeaf()) {
      const std::uint32_t* s = bvh.leafSlots(n);
      slots[i].assign(s, s + n.count);
    } else {
      slots[i] = slots[n.left];
      slots[i].insert(slots[i].end(), slots[n.right].begin(), slots[n.right].end());
    }
    Vec3 sum;
    for (std::uint32_t t : slots[i]) {
      const BvhTriangle& tri = bvh.triangle(t);
      sum += cross(tri.b - tri.a, tri.c - tri.a);
    }
    ReamerModel::NodeSlab& slab = out[i];
    const double len = norm(sum);
    if (len > 0) slab.axis = sum / len;
    slab.lo = std::numeric_limits<double>::infinity();
    slab.hi = -slab.lo;
    for (std::uint32_t t : slots[i]) {
      const BvhTriangle& tri = bvh.triangle(t);
      for (const Vec3& v : {tri.a, tri.b, tri.c}) {
        const double d = dot(slab.axis, v);
        slab.lo = std::min(slab.lo, d);
        slab.hi = std::max(slab.hi, d);
      }
    }
    if (!n.isLeaf()) {  // the children's lists are no longer needed
      std::vector<std::uint32_t>().swap(slots[n.left]);
      std::vector<std::uint32_t>().swap(slots[n.right]);
    }
  }
  return out;
}

}  // namespace

ReamerModel::ReamerModel(TriangleMesh cuttingSolid, std::vector<std::uint32_t> faceTriangles)
    : solid_(std::move(cuttingSolid)), face_(std::move(faceTriangles)) {
  if (solid_.triangles.empty()) throw std::invalid_argument("ReamerModel: the cutting solid has no triangles");
  if (face_.empty()) throw std::invalid_argument("ReamerModel: the cutting face has no triangles");
  solidBvh_ = TriangleBvh::fromMesh(solid_);
  std::vector<std::uint32_t> slots(face_.size());
  std::vector<BvhTriangle> tris(face_.size());
  for (std::size_t i = 0; i < face_.size(); ++i) {
    if (face_[i] >= solid_.triangles.size())
      throw std::invalid_argument("ReamerModel: face triangle " + std::to_string(face_[i]) + " out of range");
    const Triangle& t = solid_.triangles[face_[i]];
    slots[i] = static_cast<std::uint32_t>(i);
    tris[i] = {solid_.vertices[t[0]], solid_.vertices[t[1]], solid_.vertices[t[2]]};
  }
  faceBvh_ = TriangleBvh::fromTriangles(slots, tris);
  {
    std::vector<bool> isFace(solid_.triangles.size(), false);
    for (std::uint32_t f : face_) isFace[f] = true;
    std::vector<std::uint32_t> rslots;
    std::vector<BvhTriangle> rtris;
    for (std::uint32_t i = 0; i < solid_.triangles.size(); ++i) {
      if (isFace[i]) continue;
      const Triangle& t = solid_.triangles[i];
      rslots.push_back(static_cast<std::uint32_t>(rest_.size()));
      rest_.push_back(i);
      rtris.push_back({solid_.vertices[t[0]], solid_.vertices[t[1]], solid_.vertices[t[2]]});
    }
    restBvh_ = TriangleBvh::fromTriangles(rslots, rtris);
  }
  for (const BvhTriangle& t : tris) {
    faceNormals_.push_back(normalized(cross(t.b - t.a, t.c - t.a)));
    faceBoxes_.emplace_back();
    TriangleBvh::paddedBox(t, faceBoxes_.back().lo, faceBoxes_.back().hi);
  }
  for (const Vec3& v : solid_.vertices) radius_ = std::max(radius_, norm(v));
  const auto& nodes = solidBvh_.nodes();
  solidNodeRadius_.assign(nodes.size(), 0.0);
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    double r = 0;
    for (int c = 0; c < 8; ++c) {
      const Vec3 corner{(c & 1) ? nodes[i].hi.x : nodes[i].lo.x, (c & 2) ? nodes[i].hi.y : nodes[i].lo.y,
                        (c & 4) ? nodes[i].hi.z : nodes[i].lo.z};
      r = std::max(r, norm(corner));
    }
    solidNodeRadius_[i] = r;
  }
  solidNodeSlabs_ = nodeSlabs(solidBvh_);

  // Pseudo-normals: unit face normals, edge = sum of its two faces, vertex = angle-weighted sum.
  const std::size_t nt = solid_.triangles.size();
  faceNormal_.resize(nt);
  edgeNormal_.assign(3 * nt, Vec3{});
  vertexNormal_.assign(solid_.vertices.size(), Vec3{});
  std::map<std::pair<std::uint32_t, std::uint32_t>, Vec3> edgeSum;
  for (std::size_t i = 0; i < nt; ++i) {
    const Triangle& t = solid_.triangles[i];
    const Vec3 P[3] = {solid_.vertices[t[0]], solid_.vertices[t[1]], solid_.vertices[t[2]]};
    faceNormal_[i] = normalized(cross(P[1] - P[0], P[2] - P[0]));
    for (int k = 0; k < 3; ++k) {
      const Vec3 e1 = normalized(P[(k + 1) % 3] - P[k]), e2 = normalized(P[(k + 2) % 3] - P[k]);
      vertexNormal_[t[k]] += faceNormal_[i] * std::acos(std::clamp(dot(e1, e2), -1.0, 1.0));
      edgeSum[std::minmax(t[k], t[(k + 1) % 3])] += faceNormal_[i];
    }
  }
  for (std::size_t i = 0; i < nt; ++i) {
    const Triangle& t = solid_.triangles[i];
    for (int k = 0; k < 3; ++k) edgeNormal_[3 * i + k] = edgeSum[std::minmax(t[k], t[(k + 1) % 3])];
  }

  // Face region: its z range, and a sphere with its centre on the axis fitted to the face vertices (least
  // squares in the centre height), kept when its shell is thinner than the z range.
  {
    std::vector<Vec3> fv;
    for (std::uint32_t f : face_)
      for (std::uint32_t v : solid_.triangles[f]) fv.push_back(solid_.vertices[v]);
    FaceRegion& r = faceRegion_;
    r.zMin = std::numeric_limits<double>::infinity();
    r.zMax = -r.zMin;
    for (const Vec3& v : fv) { r.zMin = std::min(r.zMin, v.z); r.zMax = std::max(r.zMax, v.z); }
    const double pad = 1e-12 * (1 + radius_);
    r.zMin -= pad;
    r.zMax += pad;
    // x^2+y^2+z^2 = 2 c z + k for points on the sphere about (0,0,c).
    double szz = 0, sz = 0, n = 0, sqz = 0, sq = 0;
    for (const Vec3& v : fv) {
      const double q = squaredNorm(v);
      szz += v.z * v.z; sz += v.z; n += 1; sqz += q * v.z; sq += q;
    }
    const double det = szz * n - sz * sz;
    if (det > 1e-12 * (szz * n + 1)) {
      const Vec3 centre{0, 0, 0.5 * (sqz * n - sz * sq) / det};
      double rin = std::numeric_limits<double>::infinity(), rout = 0;
      for (std::uint32_t f : face_) {  // exact extremes over the triangles, not only the vertices
        const Triangle& t = solid_.triangles[f];
        const Vec3 P[3] = {solid_.vertices[t[0]], solid_.vertices[t[1]], solid_.vertices[t[2]]};
        rin = std::min(rin, norm(closestPointOnTriangle(centre, P[0], P[1], P[2]) - centre));
        for (const Vec3& p : P) rout = std::max(rout, norm(p - centre));
      }
      if (rout - rin < 0.5 * (r.zMax - r.zMin)) {
        r.shell = true;
        r.centre = centre;
        r.rIn = rin * (1 - 1e-12) - pad;
        r.rOut = rout * (1 + 1e-12) + pad;
      }
    }
  }

  // Deep point: the inside point of largest clearance among samples of the local bounds (the axis first).
  const Bounds b = computeBounds(solid_);
  const Vec3 c = b.center();
  for (int i = 0; i <= 64; ++i) {
    for (int j = 0; j < 5; ++j) {
      const double f = double(i) / 64;
      Vec3 q{c.x, c.y, b.min.z + f * (b.max.z - b.min.z)};
      if (j > 0) q = q + Vec3{double((j == 1) - (j == 2)), double((j == 3) - (j == 4)), 0} * (0.25 * (b.max.x - b.min.x));
      if (!containsLocal(q)) continue;
      const double clearance = norm(q - closestSurfacePoint(q));
      if (clearance > deepClearance_) {
        deepClearance_ = clearance;
        deepPoint_ = q;
      }
    }
  }
  if (!(deepClearance_ > 0)) throw std::invalid_argument("ReamerModel: the cutting solid encloses no volume");
}

Vec3 ReamerModel::closest(const Vec3& p, std::uint32_t& triangle, int& region) const {
  const auto& nodes = solidBvh_.nodes();
  double best2 = std::numeric_limits<double>::infinity();
  Vec3 best;
  std::vector<std::int32_t> stack{solidBvh_.root()};
  while (!stack.empty()) {
    const BvhNode& n = nodes[stack.back()];
    stack.pop_back();
    if (boxSquaredDistance(n.lo, n.hi, p, p) >= best2) continue;
    if (n.isLeaf()) {
      const std::uint32_t* s = solidBvh_.leafSlots(n);
      for (int i = 0; i < n.count; ++i) {
        const BvhTriangle& t = solidBvh_.triangle(s[i]);
        TriangleRegion r;
        const Vec3 q = closestPointOnTriangle(p, t.a, t.b, t.c, &r);
        const double d2 = squaredNorm(q - p);
        if (d2 < best2) {
          best2 = d2;
          best = q;
          triangle = s[i];
          region = static_cast<int>(r);
        }
      }
      continue;
    }
    const double dl = boxSquaredDistance(nodes[n.left].lo, nodes[n.left].hi, p, p);
    const double dr = boxSquaredDistance(nodes[n.right].lo, nodes[n.right].hi, p, p);
    if (dl <= dr) { stack.push_back(n.right); stack.push_back(n.left); }
    else { stack.push_back(n.left); stack.push_back(n.right); }
  }
  return best;
}

Vec3 ReamerModel::closestSurfacePoint(const Vec3& p) const {
  std::uint32_t t = 0;
  int r = 0;
  return closest(p, t, r);
}

ReamerModel ReamerModel::fromSpec(const ReamerSpec& spec) {
  TriangleMesh solid = buildCuttingSolid(spec);
  const std::size_t faceVertices = cuttingFaceVertices(spec).size();
  std::vector<std::uint32_t> face;
  for (std::size_t i = 0; i < solid.triangles.size(); ++i) {
    const Triangle& t = solid.triangles[i];
    if (t[0] < faceVertices && t[1] < faceVertices && t[2] < faceVertices) face.push_back(static_cast<std::uint32_t>(i));
  }
  ReamerModel model(std::move(solid), std::move(face));
  // The ideal solid (docs/REAMERS.md) and the largest facet sag: every mesh vertex lies on it, so a facet
  // strays inside by at most (radius - distance of its plane from the axis or centre).
  IdealSolid& id = model.ideal_;
  id.flat = spec.isFlat();
  id.radius = 0.5 * spec.diameterMm;
  const double h = capHeight(spec);
  id.capBaseZ = id.flat ? 0.0 : -h;
  id.zBack = id.capBaseZ - spec.bodyLengthMm;
  id.sphereRadius = id.flat ? 0.0 : spec.sphereRadiusMm;
  id.sphereCentreZ = id.flat ? 0.0 : -spec.sphereRadiusMm;
  const Vec3 centre{0, 0, id.sphereCentreZ};
  const double tolOn = 1e-9 * (1 + id.radius + id.sphereRadius);
  for (const Triangle& t : model.solid_.triangles) {
    const Vec3 P[3] = {model.solid_.vertices[t[0]], model.solid_.vertices[t[1]], model.solid_.vertices[t[2]]};
    const Vec3 n = normalized(cross(P[1] - P[0], P[2] - P[0]));
    bool onSphere = !id.flat, onCylinder = true, flatFacet = std::abs(n.z) > 1 - 1e-12;
    for (const Vec3& p : P) {
      onSphere = onSphere && std::abs(norm(p - centre) - id.sphereRadius) <= tolOn;
      onCylinder = onCylinder && std::abs(std::hypot(p.x, p.y) - id.radius) <= tolOn;
    }
    if (flatFacet) continue;  // discs lie exactly on their ideal planes
    if (onSphere) {
      id.maxSag = std::max(id.maxSag, id.sphereRadius - std::abs(dot(n, P[0] - centre)));
    } else if (onCylinder && std::abs(n.z) < 1e-9) {
      id.maxSag = std::max(id.maxSag, id.radius - std::abs(n.x * P[0].x + n.y * P[0].y));
    } else {
      return model;  // not the expected structure: keep the exact search only
    }
  }
  id.maxSag = id.maxSag * (1 + 1e-9) + tolOn;
  id.vertexSlack = tolOn;
  id.valid = true;
  model.capShadow_ = detail::CapShadow::build(model.solid_, model.face_);
  return model;
}

ReamerModel ReamerModel::fromSolid(TriangleMesh cuttingSolid) {
  std::vector<std::uint32_t> face;
  for (std::size_t i = 0; i < cuttingSolid.triangles.size(); ++i) {
    const Triangle& t = cuttingSolid.triangles[i];
    const Vec3 n = cross(cuttingSolid.vertices[t[1]] - cuttingSolid.vertices[t[0]],
                         cuttingSolid.vertices[t[2]] - cuttingSolid.vertices[t[0]]);
    // Forward-facing, with a margin so that side walls (n.z ~ 0 up to rounding) are not taken.
    if (n.z > 1e-9 * norm(n)) face.push_back(static_cast<std::uint32_t>(i));
  }
  return ReamerModel(std::move(cuttingSolid), std::move(face));
}

ReamerModel ReamerModel::fromCuttingVolume(const TriangleMesh& cuttingSolid, const ReamerSpec* builtFrom) {
  if (builtFrom && builtFrom->meshFile.empty()) {
    ReamerModel model = fromSpec(*builtFrom);
    // The ideal solid's bounds hold for the spec's own mesh only: any other mesh takes the general path.
    if (model.solid_.vertices == cuttingSolid.vertices && model.solid_.triangles == cuttingSolid.triangles) return model;
  }
  return fromSolid(cuttingSolid);
}

bool ReamerModel::containsLocal(const Vec3& p) const {
  if (ideal_.valid) {
    // Outside the ideal solid: outside the mesh. Deeper inside than the sag: inside the mesh.
    const double r = std::hypot(p.x, p.y);
    const double top = ideal_.flat ? -p.z : ideal_.sphereRadius - norm(p - Vec3{0, 0, ideal_.sphereCentreZ});
    const double capMargin = (!ideal_.flat && p.z <= ideal_.capBaseZ) ? std::numeric_limits<double>::infinity() : top;
    const double margin = std::min({ideal_.radius - r, p.z - ideal_.zBack, capMargin});
    if (margin < 0) return false;
    if (margin > ideal_.maxSag) return true;
  }
  return containsBySearch(p);
}

bool ReamerModel::containsBySearch(const Vec3& p) const {
  std::uint32_t t = 0;
  int region = 0;
  const Vec3 c = closest(p, t, region);
  const Triangle& tri = solid_.triangles[t];
  Vec3 n;
  switch (static_cast<TriangleRegion>(region)) {
    case TriangleRegion::Face: n = faceNormal_[t]; break;
    case TriangleRegion::VertexA: n = vertexNormal_[tri[0]]; break;
    case TriangleRegion::VertexB: n = vertexNormal_[tri[1]]; break;
    case TriangleRegion::VertexC: n = vertexNormal_[tri[2]]; break;
    case TriangleRegion::EdgeAB: n = edgeNormal_[3 * t]; break;
    case TriangleRegion::EdgeBC: n = edgeNormal_[3 * t + 1]; break;
    case TriangleRegion::EdgeCA: n = edgeNormal_[3 * t + 2]; break;
  }
  return dot(p - c, n) < 0;
}

}  // namespace reamsim
