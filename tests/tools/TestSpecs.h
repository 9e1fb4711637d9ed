#pragma once
// Reamer specs for the tools tests.
#include <limits>

#include "reamsim/core/ReamerSpec.h"

namespace reamsim::test {

inline ReamerSpec spherical(double d, double r, double body = 12, int segments = 96, int rings = 12) {
  ReamerSpec s;
  s.name = "test";
  s.diameterMm = d;
  s.sphereRadiusMm = r;
  s.bodyLengthMm = body;
  s.segments = segments;
  s.rings = rings;
  return s;
}
inline ReamerSpec flat(double d, double body = 10, int segments = 96, int rings = 12) {
  return spherical(d, std::numeric_limits<double>::infinity(), body, segments, rings);
}

}  // namespace reamsim::test
