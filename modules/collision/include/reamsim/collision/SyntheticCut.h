#pragma once
// A stand-in cut for tests and benchmarks where the exact Boolean is unavailable (open bones such as the CT
// skull) or too slow to repeat thousands of times: the bone triangles the reamer touches are replaced by the
// same connectivity with every vertex that lies inside the cutting solid pushed forward (+feed) onto the
// solid's surface. It produces a MeshDelta of the size and locality of a real cut (a few hundred to a few
// thousand triangles removed and added in one place); it is not a volume-exact Boolean.
#include <cstdint>
#include <vector>

#include "reamsim/collision/ReamerModel.h"
#include "reamsim/core/BoneState.h"
#include "reamsim/core/MeshDelta.h"
#include "reamsim/core/Pose.h"

namespace reamsim {

// `touchedSlots`: the bone slots touched by the reamer at `pose` (query 1).
MeshDelta dentDelta(const BoneState& bone, const std::vector<std::uint32_t>& touchedSlots, const ReamerModel& reamer,
                    const RigidTransform& pose);

}  // namespace reamsim
