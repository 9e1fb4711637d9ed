#pragma once
// Percentiles of timed samples as `bench collision` and `bench winding` report them (nearest rank).
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

namespace reamsim::cli {

inline double percentile(std::vector<double> v, double q) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  const std::size_t i = std::min(v.size() - 1, static_cast<std::size_t>(std::ceil(q * double(v.size())) - 1));
  return v[q <= 0 ? 0 : i];
}

}  // namespace reamsim::cli
