// The import report as text (for people) and JSON (for scripts and the benchmark).
#include <nlohmann/json.hpp>

#include <cstdio>
#include <sstream>

#include "reamsim/ctimport/CtImport.h"

namespace reamsim::ct {

std::string toText(const ImportReport& r) {
  std::ostringstream out;
  char b[512];
  out << "volume:                 " << r.source << " (" << r.format << ")\n";
  std::snprintf(b, sizeof b, "grid:                   %d x %d x %d, spacing %.4g x %.4g x %.4g mm\n", r.dims[0], r.dims[1],
                r.dims[2], r.spacing[0], r.spacing[1], r.spacing[2]);
  out << b;
  std::snprintf(b, sizeof b, "values:                 %.0f .. %.0f %s\n", double(r.minValue), double(r.maxValue),
                r.valueUnit.c_str());
  out << b;
  out << "patient space:          volume " << toString(r.volumeSpace) << ", mesh " << toString(r.outputSpace) << "\n";
  std::snprintf(b, sizeof b, "threshold:              %g%s\n", r.lowerThreshold,
                r.upperThreshold ? (" .. " + std::to_string(*r.upperThreshold)).c_str() : " and above");
  out << b;
  out << "voxels in range:        " << r.voxelsInRange << " in " << r.regions << " region(s); kept " << r.keptVoxels
      << ", cavities filled " << r.cavityVoxelsFilled << "\n";
  std::snprintf(b, sizeof b, "isosurface:             %zu faces, %.1f mm3\n", r.isosurfaceFaces, r.isosurfaceVolumeMm3);
  out << b;
  out << "decimated:              " << (r.decimated ? "yes" : "no") << " (" << r.decimationAttempts << " attempt(s))\n";
  out << toText(r.validation);
  out << "self-intersection check: " << r.selfIntersectionCheck << "\n";
  out << "stages (ms):           ";
  for (const StageTime& s : r.stages) {
    std::snprintf(b, sizeof b, " %s %.0f;", s.stage.c_str(), s.ms);
    out << b;
  }
  std::snprintf(b, sizeof b, " total %.0f\n", r.totalMs);
  out << b;
  for (const std::string& n : r.notes) out << "note: " << n << "\n";
  return out.str();
}

std::string toJson(const ImportReport& r, int indent) {
  nlohmann::json j;
  j["source"] = r.source;
  j["format"] = r.format;
  j["value_unit"] = r.valueUnit;
  j["dims"] = r.dims;
  j["spacing_mm"] = r.spacing;
  j["value_range"] = {r.minValue, r.maxValue};
  j["volume_space"] = toString(r.volumeSpace);
  j["mesh_space"] = toString(r.outputSpace);
  j["threshold"] = r.lowerThreshold;
  j["upper_threshold"] = r.upperThreshold ? nlohmann::json(*r.upperThreshold) : nlohmann::json(nullptr);
  j["volume_smoothing_sigma_mm"] = r.volumeSmoothingSigmaMm;
  j["voxels_in_range"] = r.voxelsInRange;
  j["regions"] = r.regions;
  j["kept_voxels"] = r.keptVoxels;
  j["cavity_voxels_filled"] = r.cavityVoxelsFilled;
  j["field_of_view_cuts"] = r.fieldOfViewCuts;
  j["isosurface_faces"] = r.isosurfaceFaces;
  j["isosurface_volume_mm3"] = r.isosurfaceVolumeMm3;
  j["smoothing_restored_vertices"] = r.smoothingRestoredVertices;
  j["smoothing_volume_correction_mm"] = r.smoothingVolumeCorrectionMm;
  j["decimated"] = r.decimated;
  j["decimation_attempts"] = r.decimationAttempts;
  j["decimation_guarded_vertices"] = r.decimationGuardedVertices;
  j["repaired"] = r.repaired;
  j["validation"] = nlohmann::json::parse(toJson(r.validation, -1));
  j["clean_solid"] = r.validation.isCleanSolid();
  j["self_intersection_check"] = r.selfIntersectionCheck;
  nlohmann::json stages = nlohmann::json::object();
  for (const StageTime& s : r.stages) stages[s.stage] = s.ms;
  j["stage_ms"] = stages;
  j["total_ms"] = r.totalMs;
  j["notes"] = r.notes;
  return j.dump(indent);
}

}  // namespace reamsim::ct
