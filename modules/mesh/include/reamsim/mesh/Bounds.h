#pragma once
#include <algorithm>
#include <limits>

#include "reamsim/mesh/Vec3.h"

namespace reamsim {

// Axis-aligned box; empty until the first point is added.
struct Bounds {
  Vec3 min{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
           std::numeric_limits<double>::infinity()};
  Vec3 max{-std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
           -std::numeric_limits<double>::infinity()};

  bool empty() const { return min.x > max.x; }
  void add(const Vec3& p) {
    min = {std::min(min.x, p.x), std::min(min.y, p.y), std::min(min.z, p.z)};
    max = {std::max(max.x, p.x), std::max(max.y, p.y), std::max(max.z, p.z)};
  }
  void add(const Bounds& b) {
    if (!b.empty()) { add(b.min); add(b.max); }
  }
  Vec3 size() const { return empty() ? Vec3{} : max - min; }
  Vec3 center() const { return (min + max) * 0.5; }
  double diagonal() const { return norm(size()); }
  bool overlaps(const Bounds& o) const {
    return !empty() && !o.empty() && min.x <= o.max.x && o.min.x <= max.x && min.y <= o.max.y &&
           o.min.y <= max.y && min.z <= o.max.z && o.min.z <= max.z;
  }
  Bounds expanded(double margin) const {
    Bounds b = *this;
    if (!b.empty()) { b.min -= Vec3{margin, margin, margin}; b.max += Vec3{margin, margin, margin}; }
    return b;
  }
};

}  // namespace reamsim
