#pragma once
// A regular grid of samples: point (i, j, k) sits at origin + h * (i, j, k).
#include <cstdint>
#include <vector>

#include "reamsim/mesh/Vec3.h"

namespace reamsim {

struct ScalarGrid {
  Vec3 origin;
  double h = 1;
  int n[3] = {0, 0, 0};
  std::vector<double> value;  // signed distance: negative inside, never exactly zero

  std::size_t size() const { return std::size_t(n[0]) * n[1] * n[2]; }
  std::size_t index(int i, int j, int k) const { return std::size_t(i) + std::size_t(n[0]) * (std::size_t(j) + std::size_t(n[1]) * k); }
  Vec3 point(int i, int j, int k) const { return origin + Vec3{i * h, j * h, k * h}; }
  Vec3 point(std::size_t idx) const {
    const int i = int(idx % n[0]);
    const int j = int((idx / n[0]) % n[1]);
    const int k = int(idx / (std::size_t(n[0]) * n[1]));
    return point(i, j, k);
  }
};

}  // namespace reamsim
