#pragma once
// Reading CT volumes. The format follows the path:
//   directory, or a .dcm/.dicom file, or a file starting with the DICOM preamble → DICOM series (vtk-dicom;
//     compressed transfer syntaxes through GDCM);
//   .nrrd (attached header) / .nhdr (detached header; data files may be a list or a numbered pattern) → NRRD;
//   .mha (header + data) / .mhd (header, data elsewhere) → MetaImage;
//   .nii / .nii.gz → NIfTI-1 (and NIfTI-2 through VTK).
// Headers are never trusted: sizes are checked against the data actually present before allocating, and any
// problem (truncated, wrong header, missing slices, inconsistent spacing) throws reamsim::InputError naming
// the file. See docs/CT_IMPORT.md for the fields honoured and the patient-space convention of each format.
#include <string>
#include <vector>

#include "reamsim/ctimport/CtVolume.h"
#include "reamsim/ctimport/Progress.h"

namespace reamsim::ct {

// `progress` (optional) gets the fraction read with stage "reading"; returning false cancels (ImportCancelled).
CtVolume readVolume(const std::string& path, const ProgressCallback& progress = {});

// What readVolume would use for `path` ("dicom", "nrrd", "metaimage", "nifti"), or "" if none.
std::string detectVolumeFormat(const std::string& path);

std::vector<std::string> supportedVolumeExtensions();  // ".nrrd", ".nhdr", ".mha", ".mhd", ".nii", ".nii.gz", ".dcm"

// Upper bound on voxels a reader will allocate (2^31: 8 GiB of float); larger volumes are refused.
constexpr std::size_t kMaxVoxels = std::size_t{1} << 31;

}  // namespace reamsim::ct
