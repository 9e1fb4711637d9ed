#pragma once
// Broad phase of the thesis pipeline: axis-aligned bounding boxes (closed intervals, so touching boxes
// overlap; empty boxes never overlap).
#include "reamsim/mesh/Bounds.h"

namespace reamsim {

inline bool boundsOverlap(const Bounds& a, const Bounds& b) { return a.overlaps(b); }

}  // namespace reamsim
