#pragma once
// bench cut --loop's planning figures: what the planning dock's measure of the glenoid face costs
// (loop.glenoid_face), and what a removal preview's seat adds to it (loop.preview_seat).
#include <nlohmann/json.hpp>

#include "reamsim/core/Pose.h"
#include "reamsim/core/ReamerSpec.h"
#include "reamsim/mesh/TriangleMesh.h"

namespace reamsim::cli {

// measureGlenoidFace about the point where the first pose's axis meets the bone, timed over repeated calls.
nlohmann::json glenoidFaceCost(const TriangleMesh& bone, const Pose& first);

// previewSeat's measure (the bone state as a mesh, then measureReamedSurface) of a reamed bone at the last pose
// of its reaming, timed.
nlohmann::json previewSeatCost(const TriangleMesh& reamed, const ReamerSpec& spec, const Pose& last);

}  // namespace reamsim::cli
