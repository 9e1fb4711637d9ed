#pragma once
// Turns per-axis step vectors (spacing included, as NRRD "space directions" or a scaled matrix) into the
// volume's spacing and direction; errors name the file and header line. The direction is orthonormal, except
// for slices slanted along one axis (SlantedSlices.h): then the slanted axis is left as the steps give it, for
// readVolume to resample once the values are read.
#include <array>
#include <string>

#include "reamsim/ctimport/CtVolume.h"

namespace reamsim::ct::io {

void setAxesFromSteps(CtVolume& v, const std::array<Vec3, 3>& steps, const std::string& path, long line);

}  // namespace reamsim::ct::io
