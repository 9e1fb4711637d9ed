#pragma once
// The three bones of the collision property tests and their query budget, shared by every query type.
#include <cstddef>

#include "CollisionFixtures.h"
#include "reamsim/collision/TriangleBvh.h"

namespace reamsim::test {

// >= 10,000 queries per query type over the three bones (brute force on the 1.5k scapula is the costly part).
inline constexpr std::size_t kSphereQueries = 4000, kSlabQueries = 4000, kScapulaQueries = 2000;
static_assert(kSphereQueries + kSlabQueries + kScapulaQueries >= 10000);

inline const TriangleMesh& sphere() {
  static const TriangleMesh m = icosphere(2, 20, {3, -2, 1});
  return m;
}
inline const TriangleMesh& slab() {
  static const TriangleMesh m = block({-30, -30, 0}, {30, 30, 20}, 4);
  return m;
}
inline const TriangleMesh& scapula() {
  static const TriangleMesh m = bundledScapula();
  return m;
}

// Bones that run parallel to the reamer, as the glenoid runs beside a seated reamer, for the property tests
// of the node bounds where they decide the most: the wall of a 17 mm spherical cavity about `centre` (faces
// turned inwards: the bone is around the hole) and the slab's top, with the cap (sphere radius 16, so 1 mm
// from the wall when the two centres meet) and the flat reamer, both finer than smallSpec's default.
struct ParallelBones {
  Vec3 centre{3, -2, 1};
  TriangleMesh cavity;
  TriangleBvh cavityBvh, slabBvh;
  ReamerModel round = ReamerModel::fromSpec(smallSpec(false, 24, 6));
  ReamerModel flat = ReamerModel::fromSpec(smallSpec(true, 24, 6));
  // The same solids read as plain meshes: the queries' general paths (no ideal solid, no face height field).
  ReamerModel roundSolid = ReamerModel::fromSolid(round.solid());
  ReamerModel flatSolid = ReamerModel::fromSolid(flat.solid());
  explicit ParallelBones(int subdivisions) : cavity(icosphere(subdivisions, 17, centre)) {
    for (Triangle& t : cavity.triangles) std::swap(t[1], t[2]);
    cavityBvh = TriangleBvh::fromMesh(cavity);
    slabBvh = TriangleBvh::fromMesh(slab());
  }
};

// A random unit vector (rejection sampling in the unit ball).
inline Vec3 randomUnit(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(-1, 1);
  Vec3 v;
  do v = {u(rng), u(rng), u(rng)};
  while (squaredNorm(v) > 1 || squaredNorm(v) < 1e-4);
  return normalized(v);
}

}  // namespace reamsim::test
