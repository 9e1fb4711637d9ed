#pragma once
// The patient coordinate convention a bone's coordinates are given in, kept with the bone in the
// document (BoneNode::patientFrame). A bone imported from CT is in the frame the import chose (LPS by
// default); a mesh file names none unless ReamSim wrote it (docs/CT_IMPORT.md, "Patient coordinates").
//   LPS: +x toward the patient's left, +y posterior, +z superior (DICOM, ITK).
//   RAS: +x toward the patient's right, +y anterior, +z superior (NIfTI, 3D Slicer).
// Core knows only the name: converting points is the CT import module's job.
#include <optional>
#include <string_view>

namespace reamsim {

enum class PatientFrame { Unspecified, LPS, RAS };

const char* toString(PatientFrame frame);  // "unspecified", "LPS", "RAS"
// Case-insensitive "LPS", "RAS", "unspecified"; nullopt for anything else.
std::optional<PatientFrame> parsePatientFrame(std::string_view text);

}  // namespace reamsim
