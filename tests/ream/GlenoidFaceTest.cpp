// The glenoid face's direction (measureGlenoidFace): exact on a dish whose rim is a circle about a known axis,
// whatever the mesh's resolution and whether the centre sits on the surface or above a reamed one; the far side of
// a thin plate stays out; bad input is named; on the bundled scapula it agrees with the glenoid's sphere fit.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "reamsim/ream/DefaultCase.h"
#include "reamsim/ream/Glenoid.h"
#include "reamsim/ream/GlenoidFace.h"
#include "reamsim/ream/ScapularFrame.h"

namespace reamsim {
namespace {

constexpr double kPi = 3.14159265358979323846;

double angleDeg(const Vec3& a, const Vec3& b) {
  return std::acos(std::clamp(dot(normalized(a), normalized(b)), -1.0, 1.0)) * 180 / kPi;
}

struct Dish {
  Vec3 centre{3, -7, 11};
  Vec3 axis = normalized(Vec3{0.3, -0.2, 1});  // out of the bone
  double sphereRadius = 30, dishRadius = 16;   // a concave spherical dish within a flat surround
};

// The surface of a height field over a square grid of `cells` per side (40 mm wide) in the dish's frame, its
// triangles facing +axis; `skew` alternates the diagonals so the triangulation is not symmetric about the axis.
TriangleMesh dishSurface(const Dish& d, int cells, bool skew, double heightShift = 0) {
  const Vec3 u = normalized(anyPerpendicular(d.axis)), v = cross(d.axis, u);
  TriangleMesh m;
  const double h = 40.0 / cells;
  for (int j = 0; j <= cells; ++j)
    for (int i = 0; i <= cells; ++i) {
      const double a = -20 + i * h, b = -20 + j * h, rho = std::hypot(a, b);
      const double r = std::min(rho, d.dishRadius);
      const double w = d.sphereRadius - std::sqrt(d.sphereRadius * d.sphereRadius - r * r) + heightShift;
      m.vertices.push_back(d.centre + u * a + v * b + d.axis * w);
    }
  auto at = [cells](int i, int j) { return std::uint32_t(j * (cells + 1) + i); };
  for (int j = 0; j < cells; ++j)
    for (int i = 0; i < cells; ++i) {
      if (skew && (i + j) % 3 == 0) {
        m.triangles.push_back({at(i, j), at(i + 1, j), at(i, j + 1)});
        m.triangles.push_back({at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)});
      } else {
        m.triangles.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
        m.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
      }
    }
  return m;
}

TEST(GlenoidFace, ADishFacesAlongItsAxisAtEveryResolution) {
  const Dish d;
  for (int cells : {40, 160})
    for (bool skew : {false, true}) {
      const BoneState bone = BoneState::fromMesh(dishSurface(d, cells, skew));
      const GlenoidFace face = measureGlenoidFace(bone, d.centre);
      // The rim of the piece within 10 mm lies on the sphere of 10 mm about the centre and on the dish, a circle
      // about the axis, up to the centroid rule's ragged edge: a fraction of a triangle.
      EXPECT_LT(angleDeg(face.outward, d.axis), cells == 40 ? 1.0 : 0.25) << cells << " cells, skew " << skew;
      EXPECT_NEAR(face.centreGapMm, 0, 1e-9);
      // Archimedes: a sphere's area within chord c of a point on it is pi c^2, whatever the sphere's radius.
      EXPECT_NEAR(face.areaMm2, kPi * 100, cells == 40 ? 25.0 : 6.0);
      EXPECT_EQ(face.radiusMm, 10);
    }
}

TEST(GlenoidFace, MoreTrianglesOnTheSameSurfaceChangeNothingBeyondTheEdge) {
  const Dish d;
  const TriangleMesh coarse = dishSurface(d, 80, true);
  const GlenoidFace a = measureGlenoidFace(BoneState::fromMesh(coarse), d.centre);
  const GlenoidFace b = measureGlenoidFace(BoneState::fromMesh(subdivideMidpoints(coarse)), d.centre);
  EXPECT_GT(b.triangles, 3 * a.triangles);
  EXPECT_LT(angleDeg(a.outward, b.outward), 0.3);
}

TEST(GlenoidFace, ACentreAboveAReamedFaceStillFindsIt) {
  // The centre was placed on the bone before it was reamed 3 mm deeper.
  const Dish d;
  const GlenoidFace face = measureGlenoidFace(BoneState::fromMesh(dishSurface(d, 120, true, -3.0)), d.centre);
  EXPECT_NEAR(face.centreGapMm, 3, 1e-3);  // the facets lie up to their sag inside the sphere
  EXPECT_LT(angleDeg(face.outward, d.axis), 0.5);
}

TEST(GlenoidFace, TheFarSideOfAThinPlateStaysOut) {
  const Dish d;
  const TriangleMesh top = dishSurface(d, 80, true);
  // The same dish 2 mm below, turned to face the other way: the plate's far side, within the radius.
  TriangleMesh plate = top;
  const TriangleMesh below = dishSurface(d, 80, true, -2.0);
  const std::uint32_t base = std::uint32_t(plate.vertices.size());
  plate.vertices.insert(plate.vertices.end(), below.vertices.begin(), below.vertices.end());
  for (const Triangle& t : below.triangles) plate.triangles.push_back({base + t[0], base + t[2], base + t[1]});
  const GlenoidFace alone = measureGlenoidFace(BoneState::fromMesh(top), d.centre);
  const GlenoidFace withFarSide = measureGlenoidFace(BoneState::fromMesh(plate), d.centre);
  EXPECT_EQ(withFarSide.triangles, alone.triangles);
  EXPECT_LT(angleDeg(withFarSide.outward, alone.outward), 1e-12);
}

// Each triangle with vertices of its own: the same surface, no vertex slot shared.
TriangleMesh unshared(const TriangleMesh& in) {
  TriangleMesh out;
  for (const Triangle& t : in.triangles) {
    const std::uint32_t base = std::uint32_t(out.vertices.size());
    for (std::uint32_t v : t) out.vertices.push_back(in.vertices[v]);
    out.triangles.push_back({base, base + 1, base + 2});
  }
  return out;
}

TEST(GlenoidFace, TrianglesMeetWhereTheirCornersMeetSharedSlotsOrNot) {
  const Dish d;
  const TriangleMesh mesh = dishSurface(d, 80, true);
  const GlenoidFace shared = measureGlenoidFace(BoneState::fromMesh(mesh, BoneState::Ordering::Preserve), d.centre);
  const GlenoidFace apart = measureGlenoidFace(BoneState::fromMesh(unshared(mesh), BoneState::Ordering::Preserve), d.centre);
  EXPECT_EQ(apart.triangles, shared.triangles);
  EXPECT_LT(angleDeg(apart.outward, shared.outward), 1e-9);
}

TEST(GlenoidFace, APieceCutOffFromTheCentreStaysOut) {
  // A ring of triangles 5-6 mm out removed: what lies beyond faces the same way but does not touch the centre's piece.
  const Dish d;
  TriangleMesh mesh = dishSurface(d, 160, false);
  const Vec3 u = normalized(anyPerpendicular(d.axis)), v = cross(d.axis, u);
  TriangleMesh ringed = mesh;
  ringed.triangles.clear();
  for (const Triangle& t : mesh.triangles) {
    const Vec3 c = (mesh.vertices[t[0]] + mesh.vertices[t[1]] + mesh.vertices[t[2]]) * (1.0 / 3.0) - d.centre;
    const double rho = std::hypot(dot(c, u), dot(c, v));
    if (rho < 5 || rho > 6) ringed.triangles.push_back(t);
  }
  const GlenoidFace face = measureGlenoidFace(BoneState::fromMesh(ringed), d.centre);
  // The piece within 5 mm: pi c^2 with c its chord from the centre (~5 mm), not the 10 mm's pi 100.
  EXPECT_LT(face.areaMm2, kPi * 5.2 * 5.2);
  EXPECT_GT(face.areaMm2, kPi * 4.5 * 4.5);
  EXPECT_LT(angleDeg(face.outward, d.axis), 1.0);
}

TEST(GlenoidFace, ANeckBeyondASteepRimStaysOut) {
  // Beyond 6 mm the surface falls away at 70 degrees to the face (the neck): turned more than 60, left out.
  const Dish d;
  const Vec3 u = normalized(anyPerpendicular(d.axis)), v = cross(d.axis, u);
  TriangleMesh m = dishSurface(d, 160, false);
  for (Vec3& p : m.vertices) {
    const Vec3 q = p - d.centre;
    const double a = dot(q, u), b = dot(q, v), rho = std::hypot(a, b);
    if (rho > 6) p = p - d.axis * ((rho - 6) * std::tan(70 * kPi / 180));
  }
  const GlenoidFace face = measureGlenoidFace(BoneState::fromMesh(m), d.centre);
  EXPECT_LT(face.areaMm2, kPi * 6.5 * 6.5);
  EXPECT_LT(angleDeg(face.outward, d.axis), 1.0);
  GlenoidFaceOptions loose;
  loose.maxTurnDeg = 80;  // let the neck in: more area, the same axis (it is symmetric about it)
  EXPECT_GT(measureGlenoidFace(BoneState::fromMesh(m), d.centre, loose).areaMm2, face.areaMm2 + 20);
}

TEST(GlenoidFace, BadInputIsNamed) {
  const Dish d;
  const BoneState bone = BoneState::fromMesh(dishSurface(d, 40, false));
  auto message = [&](const BoneState& b, const Vec3& c, GlenoidFaceOptions o = {}) -> std::string {
    try {
      measureGlenoidFace(b, c, o);
    } catch (const std::invalid_argument& e) {
      return e.what();
    }
    return "no error";
  };
  EXPECT_NE(message(bone, {NAN, 0, 0}).find("not a finite point"), std::string::npos);
  GlenoidFaceOptions tiny;
  tiny.radiusMm = 0.5;
  EXPECT_NE(message(bone, d.centre, tiny).find("2 to 40 mm"), std::string::npos);
  GlenoidFaceOptions flat;
  flat.maxTurnDeg = 90;
  EXPECT_NE(message(bone, d.centre, flat).find("1 to 89 degrees"), std::string::npos);
  EXPECT_NE(message(BoneState{}, d.centre).find("no surface"), std::string::npos);
  const std::string far = message(bone, d.centre + d.axis * 60.0);
  EXPECT_NE(far.find("no bone surface lies within 10 mm"), std::string::npos) << far;
  EXPECT_NE(far.find("place it on the glenoid face"), std::string::npos) << far;
  // A surface folded flat on itself, both sides within the radius: the areas cancel.
  TriangleMesh folded;
  folded.vertices = {{0, 0, 0}, {4, 0, 0}, {0, 4, 0}};
  folded.triangles = {{0, 1, 2}, {0, 2, 1}};
  EXPECT_NE(message(BoneState::fromMesh(folded), {1, 1, 0}).find("faces no single way"), std::string::npos);
}

TEST(GlenoidFace, TheBundledScapulasGlenoidAgreesWithItsSphereFit) {
  const DefaultBone bone = loadDefaultBone();
  const ScapulaLandmarks marks = loadDefaultLandmarks();
  const BoneState state = BoneState::fromMesh(bone.mesh);
  const GlenoidFace face = measureGlenoidFace(state, *marks[ScapulaLandmark::GlenoidCentre]);
  // The rim's plane and the fitted sphere's axis are two definitions of one direction: a few degrees apart.
  EXPECT_LT(angleDeg(face.outward, bone.glenoid.outwardAxis), 6.0);
  EXPECT_LT(face.centreGapMm, 1.0);
  // Within the published range of glenoid version (about -20..+10) and inclination (about -5..+20).
  const AxisAngles a = axisAngles(scapularFrame(marks), face.outward);
  EXPECT_GT(a.versionDeg, -20);
  EXPECT_LT(a.versionDeg, 10);
  EXPECT_GT(a.inclinationDeg, -5);
  EXPECT_LT(a.inclinationDeg, 20);
  // Nearly the same over radii that stay on the fossa.
  for (double r : {8.0, 12.0}) {
    GlenoidFaceOptions o;
    o.radiusMm = r;
    EXPECT_LT(angleDeg(measureGlenoidFace(state, *marks[ScapulaLandmark::GlenoidCentre], o).outward, face.outward), 2.0) << r;
  }
}

}  // namespace
}  // namespace reamsim
