#pragma once
// How the bone under a reamer's cutting face compares with the face's ideal shape at a pose (the sphere of
// radius R about (0, 0, -R) in the reamer's frame, or the plane z = 0 of a flat face, inside the rim): what
// a surgeon asks once a glenoid is reamed. Is the face seated over its whole area, and how far does the
// reamed bone stand off the surface a perfect, spinning reamer would leave?
//
// A bone face counts as reamed surface when its corners and centroid lie within `bandMm` of the ideal face,
// its centroid over the face (inside the rim, not behind the cap's base where the body's wall begins) and
// its outward normal within 30 degrees of the face's normal there, looking at the reamer (towards the
// sphere's centre, or along -Z for a flat face). The standoff of a point is how far it lies inside the
// ideal cutting solid: R - |p - c| on a sphere, -z on a flat face. Positive: bone left where a perfect
// reamer would have cut (under the facets of the reamer's mesh, at most its facet sag); negative: bone cut
// beyond the ideal face (by earlier, tilted or deeper poses).
#include <cstddef>

#include "reamsim/core/Pose.h"
#include "reamsim/core/ReamerSpec.h"
#include "reamsim/mesh/TriangleMesh.h"

namespace reamsim {

struct ReamedSurfaceReport {
  double faceAreaMm2 = 0;      // the ideal cutting face's area: 2 pi R h for a cap, pi (D/2)^2 for a disc
  double seatedAreaMm2 = 0;    // area of the bone faces counted as reamed surface
  double seatedFraction = 0;   // seatedAreaMm2 / faceAreaMm2, at most 1 (the face's share in contact with bone)
  std::size_t faces = 0;       // bone faces counted
  // Standoff over the counted faces' corners and centroids (0 when none are counted), mm.
  double standoffMinMm = 0;    // most over-reamed (negative) or least under-reamed
  double standoffMaxMm = 0;    // most under-reamed
  double standoffRmsMm = 0;    // area-weighted over the centroids
  double facetSagMm = 0;       // the reamer mesh's own deepest facet below its ideal face (buildCuttingSolid)
};

// The band the CLI and the GUI measure with: wider than the facet sag of any preset, narrow enough to leave
// out bone the reamer never reached.
inline constexpr double kReamedSurfaceBandMm = 0.05;

// Throws std::invalid_argument for an invalid spec (validateReamerSpec) or a band that is not positive.
ReamedSurfaceReport measureReamedSurface(const TriangleMesh& bone, const ReamerSpec& spec, const Pose& pose,
                                         double bandMm = kReamedSurfaceBandMm);

}  // namespace reamsim
