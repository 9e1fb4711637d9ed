#pragma once
// The three bones of the collision property tests and their query budget, shared by every query type.
#include <cstddef>

#include "CollisionFixtures.h"

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

}  // namespace reamsim::test
