#include "reamsim/tools/ReamedSurface.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "reamsim/mesh/ClosestPoints.h"
#include "reamsim/tools/ReamerGeometry.h"

namespace reamsim {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kCosMaxTilt = 0.8660254037844386;  // cos 30 degrees

// The ideal cutting face in the reamer's frame: where a point stands against it.
struct IdealFace {
  bool flat = false;
  double radius = 0;   // R (sphere)
  double rim = 0;      // D / 2
  double height = 0;   // h: the cap spans z in [-h, 0]
  Vec3 centre;         // (0, 0, -R)
  double standoff(const Vec3& p) const { return flat ? -p.z : radius - norm(p - centre); }
  // The ideal face's normal at (or nearest) p, pointing into the bone it cut: the reamed bone's outward
  // normal points the other way, at the reamer.
  Vec3 towardsReamer(const Vec3& p) const { return flat ? Vec3{0, 0, -1} : normalized(centre - p); }
  // Over the face: inside the rim and not behind the cap's base, where the body's wall begins (a wall
  // face just behind the rim lies as close to the sphere as the face does).
  bool overFace(const Vec3& p) const { return std::hypot(p.x, p.y) <= rim && p.z >= -height; }
};

// The deepest point of the reamer mesh's cutting-face facets below the ideal face: for a cap, R minus the
// least distance from the centre to a facet (its corners lie on the sphere, its inside below it).
double facetSag(const ReamerSpec& spec, const IdealFace& face) {
  if (face.flat) return 0;  // the disc's facets lie in its plane
  const TriangleMesh solid = buildCuttingSolid(spec);
  const double tol = 1e-9 * (1 + face.radius);
  double sag = 0;
  for (const Triangle& t : solid.triangles) {
    const Vec3 &a = solid.vertices[t[0]], &b = solid.vertices[t[1]], &c = solid.vertices[t[2]];
    const bool onFace = std::abs(face.standoff(a)) < tol && std::abs(face.standoff(b)) < tol && std::abs(face.standoff(c)) < tol;
    if (onFace) sag = std::max(sag, face.standoff(closestPointOnTriangle(face.centre, a, b, c)));
  }
  return sag;
}

}  // namespace

ReamedSurfaceReport measureReamedSurface(const TriangleMesh& bone, const ReamerSpec& spec, const Pose& pose,
                                         double bandMm) {
  validateReamerSpec(spec);
  if (!(bandMm > 0)) throw std::invalid_argument("measureReamedSurface: the band must be positive");
  IdealFace face;
  face.flat = spec.isFlat();
  face.rim = 0.5 * spec.diameterMm;
  face.height = capHeight(spec);
  if (!face.flat) {
    face.radius = spec.sphereRadiusMm;
    face.centre = {0, 0, -spec.sphereRadiusMm};
  }
  ReamedSurfaceReport out;
  out.faceAreaMm2 = face.flat ? kPi * face.rim * face.rim : 2 * kPi * face.radius * face.height;
  out.facetSagMm = facetSag(spec, face);

  // Bone coordinates into the reamer's frame: p = R^T (x - t).
  const RigidTransform toBone = toTransform(pose);
  const auto& r = toBone.rotation;
  auto local = [&](const Vec3& x) {
    const Vec3 d = x - toBone.translation;
    return Vec3{r[0] * d.x + r[3] * d.y + r[6] * d.z, r[1] * d.x + r[4] * d.y + r[7] * d.z,
                r[2] * d.x + r[5] * d.y + r[8] * d.z};
  };
  double lo = std::numeric_limits<double>::infinity(), hi = -lo, sumSq = 0;
  for (const Triangle& t : bone.triangles) {
    const Vec3 a = local(bone.vertices[t[0]]), b = local(bone.vertices[t[1]]), c = local(bone.vertices[t[2]]);
    const Vec3 g = (a + b + c) / 3.0;
    const double sg = face.standoff(g);
    const bool onFace = std::abs(sg) <= bandMm && std::abs(face.standoff(a)) <= bandMm &&
                        std::abs(face.standoff(b)) <= bandMm && std::abs(face.standoff(c)) <= bandMm;
    if (!onFace || !face.overFace(g)) continue;
    const Vec3 n = cross(b - a, c - a);
    const double twiceArea = norm(n);
    // Facing the reamer, within kMaxTiltDeg of the ideal face's normal (the reamed faces follow the
    // reamer's facets and the path's tilt; the cavity's wall stands at the cap's rim angle or steeper).
    if (!(twiceArea > 0) || dot(n, face.towardsReamer(g)) < kCosMaxTilt * twiceArea) continue;
    const double area = 0.5 * twiceArea;
    ++out.faces;
    out.seatedAreaMm2 += area;
    sumSq += area * sg * sg;
    for (const Vec3* p : {&a, &b, &c, &g}) {
      const double s = face.standoff(*p);
      lo = std::min(lo, s);
      hi = std::max(hi, s);
    }
  }
  if (out.faces > 0) {
    out.standoffMinMm = lo;
    out.standoffMaxMm = hi;
    out.standoffRmsMm = std::sqrt(sumSq / out.seatedAreaMm2);
  }
  out.seatedFraction = out.faceAreaMm2 > 0 ? std::min(1.0, out.seatedAreaMm2 / out.faceAreaMm2) : 0.0;
  return out;
}

}  // namespace reamsim
