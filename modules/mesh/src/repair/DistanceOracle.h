#pragma once
// Unsigned distance to a triangle soup (CGAL AABB tree behind a pimpl, so callers stay CGAL-free).
#include <memory>

#include "reamsim/mesh/TriangleMesh.h"

namespace reamsim {

class DistanceOracle {
 public:
  explicit DistanceOracle(const TriangleMesh& mesh);
  ~DistanceOracle();
  DistanceOracle(const DistanceOracle&) = delete;
  DistanceOracle& operator=(const DistanceOracle&) = delete;

  double distance(const Vec3& p) const;  // thread-safe after construction

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace reamsim
