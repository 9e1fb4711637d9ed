#include "reamsim/core/PatientFrame.h"

#include <cctype>
#include <string>

namespace reamsim {

const char* toString(PatientFrame frame) {
  switch (frame) {
    case PatientFrame::LPS: return "LPS";
    case PatientFrame::RAS: return "RAS";
    case PatientFrame::Unspecified: break;
  }
  return "unspecified";
}

std::optional<PatientFrame> parsePatientFrame(std::string_view text) {
  std::string lower;
  for (char c : text) lower += char(std::tolower(static_cast<unsigned char>(c)));
  if (lower == "lps") return PatientFrame::LPS;
  if (lower == "ras") return PatientFrame::RAS;
  if (lower == "unspecified") return PatientFrame::Unspecified;
  return std::nullopt;
}

}  // namespace reamsim
