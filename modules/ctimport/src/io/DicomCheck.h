#pragma once
// A structural check of a DICOM file before vtk-dicom parses it: the element structure is walked (meta group,
// then the data set in its transfer syntax, sequences and items included) without decoding values.
// vtk-dicom 0.8.14 trusts that structure. Fuzzing found: a corrupt VR followed by bytes read as a length
// (770 MB allocated for a 1.5 kB file); an element out of tag order, of group 0000 (command) or 0001
// (reserved), or a group length that is not 4 bytes, in any slice but the first (a null pointer in
// vtkDICOMParser::ReadMetaData); a NumberOfFrames of 99999999 (minutes in vtkDICOMSliceSorter).
#include <string>
#include <string_view>

namespace reamsim::ct::io {

// "" if the structure is sound, else the problem, e.g. "element (0028,0010) claims 4294967294 bytes but
// only 600 remain (file truncated or corrupt)"; NumberOfFrames must fit in the file and Rows × Columns ×
// NumberOfFrames within 2^31 voxels. Deflated data sets are checked up to their meta group only.
std::string dicomStructureProblem(std::string_view bytes);

}  // namespace reamsim::ct::io
