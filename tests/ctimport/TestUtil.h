#pragma once
// Small helpers shared by the CT-import tests.
#include <unistd.h>

#include <filesystem>
#include <string>

#include "reamsim/mesh/TriangleMesh.h"

namespace cttest {

namespace fs = std::filesystem;

// A fresh scratch directory per test binary run (and name).
inline fs::path scratch(const std::string& name) {
  const fs::path p = fs::temp_directory_path() / ("reamsim_ctimport_test_" + std::to_string(::getpid())) / name;
  fs::remove_all(p);
  fs::create_directories(p);
  return p;
}

// Centroid of the solid bounded by a closed, outward mesh (divergence theorem over origin tetrahedra).
inline reamsim::Vec3 solidCentroid(const reamsim::TriangleMesh& m) {
  reamsim::Vec3 sum;
  double volume = 0;
  for (const reamsim::Triangle& t : m.triangles) {
    const reamsim::Vec3 &a = m.vertices[t[0]], &b = m.vertices[t[1]], &c = m.vertices[t[2]];
    const double v = reamsim::dot(a, reamsim::cross(b, c)) / 6;
    volume += v;
    sum += (a + b + c) * (v / 4);
  }
  return sum / volume;
}

inline const std::string kSharedData = REAMSIM_SHARED_DATA_DIR;

}  // namespace cttest
