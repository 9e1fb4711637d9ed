#pragma once
// The correctness reference for cutting: CGAL corefinement over the whole bone with exact
// constructions (Epeck). The bone is kept in exact coordinates between cuts, so consecutive cuts
// never drift into self-intersections (rounding to doubles after every cut would, as measured with
// inexact constructions after 5–10 cuts). Cost grows with the bone (~1 µs per face per cut): this
// is the reference the fast local engine is tested against, not the engine.
#include <memory>

#include "reamsim/mesh/TriangleMesh.h"

namespace reamsim {

struct ReferenceCut {
  bool changed = false;       // false: the tool did not reach the bone (the bone is untouched)
  double removedMm3 = 0;      // volume of bone ∩ tool, from its own mesh (independent of the two below)
  double volumeBeforeMm3 = 0;
  double volumeAfterMm3 = 0;
  std::size_t facesAfter = 0;
  double milliseconds = 0;
};

struct BoneInvariants {
  bool closed = false;
  bool outwardOriented = false;
  bool selfIntersectsExact = true;    // on the exact coordinates the engine keeps
  bool selfIntersectsRounded = true;  // on the double coordinates shown and exported
  // The same, not counting the pairs the bone came with (both faces self-intersecting defects found on
  // loading, which a cut never changes: LocalSubtractor refuses cuts that reach them): whether cutting made
  // any. Equal to the above for a clean bone and for the reference engine, which takes clean bones only.
  bool newSelfIntersectionsExact = true;
  bool newSelfIntersectionsRounded = true;
  std::size_t inputSelfIntersectingPairs = 0;  // the pairs left out of the two above
};

class ReferenceSubtractor {
 public:
  // Throws std::invalid_argument if `bone` is not a closed, outward-oriented triangle mesh.
  explicit ReferenceSubtractor(const TriangleMesh& bone);
  ~ReferenceSubtractor();
  ReferenceSubtractor(ReferenceSubtractor&&) noexcept;
  ReferenceSubtractor& operator=(ReferenceSubtractor&&) noexcept;

  // Subtracts a closed, outward-oriented tool (bone coordinates). Throws std::runtime_error if CGAL
  // cannot compute the Boolean; the bone is then unchanged.
  ReferenceCut subtract(const TriangleMesh& tool);

  TriangleMesh mesh() const;  // rounded to doubles
  double volumeMm3() const;
  std::size_t faceCount() const;
  BoneInvariants checkInvariants() const;  // costly (self-intersection tests): for tests and checks

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace reamsim
