#pragma once
// Volumes whose slices are slanted (sheared along one axis, as a gantry-tilted CT converted to NRRD, MetaImage
// or NIfTI without correction) resampled onto a rectangular grid, as the DICOM reader's rectifier does.
#include <functional>

#include "reamsim/ctimport/CtVolume.h"

namespace reamsim::ct::io {

// Scanners tilt the gantry by at most about ±30°; a larger slant is a wrong header, not a scan.
inline constexpr double kMaxSlantDegrees = 45;

// The axis whose steps are slanted against the plane of the other two, which are perpendicular to each other
// (within 1e-3), when the slant is at most kMaxSlantDegrees; -1 otherwise. `axes` are unit vectors.
int slantedAxis(const std::array<Vec3, 3>& axes);

// When v's axes are not perpendicular and slantedAxis finds the slanted one: the slices stay where they are;
// within each, the voxels are sampled (bilinearly) where the grid rebuilt on the slices' normal puts them, the
// normal becomes that axis (spacing: the distance between slices) and a note says so. Samples that fall outside
// a slice get the volume's lowest value (air). `keepGoing` is asked every few slices; false stops (the caller
// throws ImportCancelled). Returns false when stopped; true otherwise (also when there was nothing to do).
bool resampleSlantedSlices(CtVolume& v, const std::function<bool()>& keepGoing);

}  // namespace reamsim::ct::io
