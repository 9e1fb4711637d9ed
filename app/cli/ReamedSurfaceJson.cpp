#include "ReamedSurfaceJson.h"

#include <cstdio>

namespace reamsim::cli {

nlohmann::json reamedSurfaceJson(const ReamedSurfaceReport& r, double bandMm) {
  return {{"what", "bone faces within band_mm of the reamer's ideal face at the last pose, over the face (inside the rim, "
                   "not behind the cap's base) with their normal within 30 degrees of the face's; "
                   "standoff = how far bone stands inside the ideal cutting solid (> 0: left by the facets, < 0: cut beyond)"},
          {"band_mm", bandMm},
          {"face_area_mm2", r.faceAreaMm2},
          {"seated_area_mm2", r.seatedAreaMm2},
          {"seated_fraction", r.seatedFraction},
          {"faces", r.faces},
          {"standoff_min_mm", r.standoffMinMm},
          {"standoff_max_mm", r.standoffMaxMm},
          {"standoff_rms_mm", r.standoffRmsMm},
          {"reamer_facet_sag_mm", r.facetSagMm}};
}

std::string reamedSurfaceLine(const ReamedSurfaceReport& r) {
  char line[256];
  std::snprintf(line, sizeof line,
                "reamed surface at the last pose: %.1f %% of the cutting face seated on bone; standoff from the ideal "
                "face %.4f to %.4f mm (rms %.4f; the reamer mesh's facets sag %.4f mm)",
                100 * r.seatedFraction, r.standoffMinMm, r.standoffMaxMm, r.standoffRmsMm, r.facetSagMm);
  return line;
}

}  // namespace reamsim::cli
