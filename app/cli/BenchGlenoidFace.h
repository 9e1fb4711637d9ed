#pragma once
// bench cut --loop's loop.glenoid_face: what the planning dock's measure of the glenoid face costs.
#include <nlohmann/json.hpp>

#include "reamsim/core/Pose.h"
#include "reamsim/mesh/TriangleMesh.h"

namespace reamsim::cli {

// measureGlenoidFace about the point where the first pose's axis meets the bone, timed over repeated calls.
nlohmann::json glenoidFaceCost(const TriangleMesh& bone, const Pose& first);

}  // namespace reamsim::cli
