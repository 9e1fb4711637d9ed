#pragma once
// The reamed-surface report (modules/tools ReamedSurface.h) as the CLI prints it: in `ream`'s summary and
// in `bench cut`'s JSON.
#include <nlohmann/json.hpp>
#include <string>

#include "reamsim/tools/ReamedSurface.h"

namespace reamsim::cli {

nlohmann::json reamedSurfaceJson(const ReamedSurfaceReport& r, double bandMm);
// One line for a person: "reamed surface at the last pose: 48.2 % of the face seated, ...".
std::string reamedSurfaceLine(const ReamedSurfaceReport& r);

}  // namespace reamsim::cli
