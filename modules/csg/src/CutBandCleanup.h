#pragma once
// Internal: keeps the cut band of the local engine bounded and well shaped. Consecutive cuts with slightly
// different poses leave slivers (thin strips between nearly coincident tool placements, needles where
// intersection curves run close) and faces accumulate. After each cut this pass removes short edges by
// half-edge collapses (a vertex moves onto a neighbour: no new coordinates) and fixes caps by edge flips,
// around the faces the cut created.
//
// Every operation is checked before it is taken, with exact predicates on the doubles:
//   - topology: the link condition and no duplicated face (collapse), the new edge not existing yet
//     (flip); only vertices whose whole star is found (through the engine's grid) and closes up (not on
//     an open border) take part;
//   - geometry: the surface moves by at most `BandCleanup::maxDeviationMm` (the removed vertex, or the flipped quad's
//     far corner, lies that close to the new faces' planes); no new face is degenerate or turns by more
//     than ~45 degrees from the one it replaces; the smallest angle does not drop below the old one or
//     the threshold, whichever is lower;
//   - no self-intersection: every face the clean-up made and kept is tested against every face of the
//     bone its box could meet (the engine's grid) and every other face it made. Pairs of faces it did not
//     make were pairs of the surface before it, free of self-intersections. The test runs once on the
//     outcome of the whole plan (operations nearly never fail it: none in 87,000 collapses at the glenoid of
//     a 400k-face scapula), and only when the outcome fails is the plan made again with the test before
//     each operation (`CleanupPlan::retested`; `BandCleanup::testEachOperation` asks for that plan).
// The bone's faces and vertices are looked at only where an operation is tried, so the work follows the
// faces that need it, not the size of the cut.
// Vertices with exact (non-double) coordinates and faces flagged as defects are never touched, and no new
// face may come near a face that has either.
#include <cstdint>
#include <functional>
#include <vector>

#include "TriangleGrid.h"
#include "reamsim/core/BoneState.h"
#include "reamsim/core/MeshDelta.h"
#include "reamsim/csg/LocalSubtractor.h"

namespace reamsim::csg {

struct CleanupPlan {
  MeshDelta delta;  // removed slots and added faces (no new vertices); empty when nothing was done
  std::size_t collapses = 0, flips = 0;
  bool retested = false;  // the optimistic plan's outcome failed its test: planned again, op by op
};

// Plans the clean-up around the faces `seeds` (live slots of `state`). `grid` holds every live face's box.
// `frozenVertex` / `frozenFace`: vertices and faces that must not change.
CleanupPlan planCutBandCleanup(const BoneState& state, TriangleGrid& grid, const std::vector<std::uint32_t>& seeds,
                               const std::function<bool(std::uint32_t)>& frozenVertex,
                               const std::function<bool(std::uint32_t)>& frozenFace, const BandCleanup& options);

}  // namespace reamsim::csg
