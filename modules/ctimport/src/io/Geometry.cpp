#include "Geometry.h"

#include <cmath>

#include "SlantedSlices.h"
#include "reamsim/mesh/MeshError.h"

namespace reamsim::ct::io {

void setAxesFromSteps(CtVolume& v, const std::array<Vec3, 3>& steps, const std::string& path, long line) {
  for (int a = 0; a < 3; ++a) {
    const double n = norm(steps[a]);
    if (!std::isfinite(n) || n <= 0)
      throw InputError(path, line, "axis " + std::to_string(a) + " has a zero or non-finite step vector");
    v.spacing[a] = n;
    const Vec3 u = steps[a] / n;
    v.direction[a] = u.x;
    v.direction[3 + a] = u.y;
    v.direction[6 + a] = u.z;
  }
  // Slices slanted along one axis (a gantry tilt) are resampled once the values are read (readVolume,
  // SlantedSlices.h); any other shear is refused here.
  if (slantedAxis({v.axis(0), v.axis(1), v.axis(2)}) >= 0) return;
  for (int a = 0; a < 3; ++a)
    for (int b = a + 1; b < 3; ++b)
      if (std::abs(dot(v.axis(a), v.axis(b))) > 1e-3)
        throw InputError(path, line, "axes " + std::to_string(a) + " and " + std::to_string(b) +
                                         " are not perpendicular, and the volume is not a stack of parallel slices "
                                         "slanted by at most 45° (as by a gantry tilt): such a shear is not supported");
}

}  // namespace reamsim::ct::io
