#pragma once
// A reaming plan: a reamer and the poses to visit, written as JSON (docs/PLAN_FORMAT.md).
#include <optional>
#include <string>
#include <vector>

#include "reamsim/core/Pose.h"

namespace reamsim {

// "feed" shorthand: start pose, then `count` steps of `stepMm` along the start pose's axis.
struct FeedSpec {
  Pose start;
  double stepMm = 0.2;
  int count = 20;
};

struct ReamPlan {
  std::string reamer;                 // preset name or mesh path; empty = chosen on the command line
  std::optional<FeedSpec> feed;       // either a feed...
  std::vector<Pose> poses;            // ...or an explicit list (both: the feed's steps come first)
  // Indices into `poses` where the reamer is placed, not moved: nothing is swept to it from the pose before
  // (a recorded session's placements, docs/PLAN_FORMAT.md). Ascending. A runner places the first pose anyway.
  std::vector<std::size_t> placedPoses;
  std::string description;

  std::vector<Pose> expandedPoses() const;  // feed steps (start excluded), then the explicit poses
  // Beside expandedPoses(): true where that pose is placed (from placedPoses; the feed's steps never are).
  std::vector<bool> expandedPlacements() const;
  double maxStepMm() const;                 // largest tip displacement between consecutive poses
};

// Throws reamsim::InputError naming the file and the problem.
ReamPlan loadPlan(const std::string& path);
ReamPlan parsePlan(const std::string& jsonText, const std::string& sourceName);
std::string planToJson(const ReamPlan& plan);

}  // namespace reamsim
