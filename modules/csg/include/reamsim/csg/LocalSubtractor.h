#pragma once
// The local CSG engine: exact subtraction whose cost follows the cut, not the bone.
//
// Per cut: (1) a uniform grid gives the bone faces whose boxes overlap the tool's box (the patch: no face
// outside it, and no edge on its border, can touch the tool); (2) the patch and the tool are corefined
// with exact constructions (CGAL Epeck); (3) patch components are classified against the tool and tool
// components against the bone by exact wedge tests at the intersection edges; (4) the result is committed
// to a BoneState as a MeshDelta (removed slots, new vertices and faces), so storage, volume and the grid
// are updated in O(cut). Vertices created by cuts keep their exact coordinates in a side table; the
// BoneState holds their rounded doubles (what is shown and exported).
//
// Dirty bones are accepted: faces in self-intersecting pairs, on non-manifold edges or degenerate are
// found once at construction; a cut whose tool touches one of them, or whose intersection curve reaches
// an open border, throws CutError and leaves the bone unchanged. Defects away from the tool are ignored.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>

#include "reamsim/core/BoneState.h"
#include "reamsim/csg/ReferenceSubtractor.h"
#include "reamsim/mesh/TriangleMesh.h"

namespace reamsim {

class CutError : public std::runtime_error {
 public:
  enum class Kind {
    BadTool,          // the tool is not a closed, outward-oriented triangle mesh
    DefectReached,    // the tool touches a self-intersecting, non-manifold or degenerate bone face
    OpenBorderReached,// the intersection curve reaches an open border of the bone
    Degenerate,       // coplanar or tangential contact the wedge tests cannot decide
    ToolEnclosed,     // the tool lies entirely inside the bone without touching its surface
    Inconsistent,     // an internal check failed (the result would not be a closed surface)
  };
  CutError(Kind kind, const std::string& what) : std::runtime_error(what), kind_(kind) {}
  Kind kind() const { return kind_; }

 private:
  Kind kind_;
};
const char* toString(CutError::Kind kind);

struct LocalCut {
  bool changed = false;          // false: the tool did not reach the bone
  double removedMm3 = 0;         // from the changed faces only: Σ removed − Σ added (divergence theorem)
  double removedPieceMm3 = 0;    // independently: volume of the closed piece bone ∩ tool
  double volumeBeforeMm3 = 0;    // of the BoneState (rounded coordinates)
  double volumeAfterMm3 = 0;
  std::size_t facesAfter = 0;
  std::size_t patchFaces = 0;    // bone faces taken into the local Boolean
  // How big the cut was (for the benchmark): bone faces whose boxes meet the tool's box, and tool faces
  // that meet a bone face (corefined with the patch).
  std::size_t candidateFaces = 0, nearToolFaces = 0;
  std::size_t removedFaces = 0;  // triangle slots removed from the bone
  std::size_t addedFaces = 0;
  bool roundingFailed = false;  // rounding the new vertices was not safe: their exact values were kept
  // The cut was made with the tool moved by this much (1 to 2 nanometres, a different offset every time):
  // the tool lay on the bone's surface where they meet, to rounding (a bone face within 1e-9 mm of a tool
  // face's plane; toolMovedOffBoneSurface, found before the corefinement), or rounding failed on the first
  // attempt, where the tool lay exactly on the bone's surface (the first attempt rolled back).
  double redoneWithOffsetMm = 0;
  bool toolMovedOffBoneSurface = false;
  // The band clean-up after the cut (see BandCleanup): its volume change is part of removedMm3 (so
  // removedMm3 = V_before − V_after still holds), not of removedPieceMm3.
  double cleanupVolumeMm3 = 0;
  std::size_t cleanupCollapses = 0, cleanupFlips = 0;
  double cleanupDeviationMm = 0;  // the deviation bound it used (BandCleanup::maxDeviationMm or the tool's)
  bool cleanupReplanned = false;  // its optimistic plan failed the self-intersection test: planned op by op
  double cleanupMilliseconds = 0;
  // Where the time went (ms), for the benchmark: tool and patch set-up (grid query, defect test, exact
  // meshes), the corefinement, the classification and seam check, the rounding check, the commit. The
  // rounding check runs on a second thread beside the commit and the clean-up's planning: `rounding` is
  // what the cut waited for it (with the work after a failed check), `roundingCheck` its own time there.
  struct Phases {
    double setup = 0, corefine = 0, classify = 0, rounding = 0, roundingCheck = 0, commit = 0;
  } phaseMilliseconds;
  double milliseconds = 0;
};

// Clean-up of the cut band after each cut: short edges collapsed and caps flipped around the new faces, so
// that faces do not accumulate and slivers do not pile up over many cuts. Each operation moves the surface
// by at most the deviation bound; the result is checked exactly for self-intersections (src/CutBandCleanup.h).
struct BandCleanup {
  bool enabled = true;
  // The deviation bound in mm; 0 (the default): half the tool's own facet sag, as its mesh shows it
  // (toolFacetSagMm), within [kMinAutoDeviationMm, kMaxAutoDeviationMm]. The cut surface is the tool's
  // facets, which stand off the ideal reamer by their sag; moves within half of it keep the reamed surface's
  // error about the reamer mesh's own (docs/CSG.md, session 27: a quarter of the 16.8 um sag, 4.3 um, instead
  // of the fixed 1 um before; session 42: half, 8.4 um, with faces under 30 degrees taken as slivers: fewer,
  // better-shaped faces in the band, so the next cut's corefinement gets fewer, 10-15 % faster cuts).
  double maxDeviationMm = 0;
  double deviationPerToolSag = 0.5;
  static constexpr double kMinAutoDeviationMm = 0.0005, kMaxAutoDeviationMm = 0.01;
  double minEdgeMm = 0.05;
  double minAngleDeg = 30;
  // Test every operation for self-intersections before taking it, instead of the plan's outcome once (with
  // the operation-by-operation plan only when that test fails). Same result, slower; for tests.
  bool testEachOperation = false;
};

struct LocalDefects {
  std::size_t selfIntersectingPairs = 0;  // pairs meeting other than at shared vertices/edges (by index)
  std::size_t selfIntersectingFaces = 0;
  std::size_t nonManifoldFaces = 0;
  std::size_t degenerateFaces = 0;
  std::size_t borderEdges = 0;
  double scanMilliseconds = 0;
};

class LocalSubtractor {
 public:
  // Any triangle mesh with finite coordinates (open, self-intersecting and non-manifold regions are
  // recorded as defects). Throws std::invalid_argument for an empty mesh or bad indices.
  explicit LocalSubtractor(const TriangleMesh& bone);
  // The same from a document state, keeping its slots: each cut's state() is then derived from `bone` by
  // a MeshDelta, so it shares every untouched chunk with it and can be committed as is (no diff).
  explicit LocalSubtractor(const BoneState& bone);
  ~LocalSubtractor();
  LocalSubtractor(LocalSubtractor&&) noexcept;
  LocalSubtractor& operator=(LocalSubtractor&&) noexcept;

  // Subtracts a closed, outward-oriented tool (bone coordinates). Throws CutError (bone unchanged) when
  // the cut cannot be computed correctly here.
  LocalCut subtract(const TriangleMesh& tool);
  // The clean-up after each cut (on by default). Off, the result is the exact Boolean alone.
  void setBandCleanup(const BandCleanup& cleanup);
  const BandCleanup& bandCleanup() const;
  // The solid the tools are made from (a reamer's cutting solid, placed or swept into a hull), in any
  // placement: the clean-up's automatic deviation bound then follows its facet sag instead of each tool's
  // (a swept hull's faces span the sweep and say nothing of the reamer's faceting, and every cut of a
  // session gets the same bound).
  void setReferenceTool(const TriangleMesh& solid);
  // Tests only: treat every rounding check as failed, so that new vertices keep their exact values (the
  // rare path, which real cuts seldom take).
  void failRoundingChecksForTesting(bool fail);

  const BoneState& state() const;  // rounded coordinates, slot based (cheap to copy), the input's slots
  TriangleMesh mesh() const;       // rounded to doubles
  double volumeMm3() const;
  std::size_t faceCount() const;
  std::size_t exactVertexCount() const;  // vertices whose exact coordinates are not doubles
  const LocalDefects& defects() const;
  // Closed/oriented/self-intersection checks over the whole bone (exact and rounded); costly.
  BoneInvariants checkInvariants() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace reamsim
