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

// The largest "t_ms" a plan may hold (11.6 days: beyond any session).
inline constexpr double kMaxPlanTimeMs = 1e9;

struct ReamPlan {
  std::string reamer;                 // preset name or mesh path; empty = chosen on the command line
  std::optional<FeedSpec> feed;       // either a feed...
  std::vector<Pose> poses;            // ...or an explicit list (both: the feed's steps come first)
  // Indices into `poses` where the reamer is placed, not moved: nothing is swept to it from the pose before
  // (a recorded session's placements, docs/PLAN_FORMAT.md). Ascending. A runner places the first pose anyway.
  std::vector<std::size_t> placedPoses;
  // Beside `poses`, each either empty or as long as `poses`: a note per pose ("" for none; the step's log row
  // gets it) and when the pose was reached, in ms since the path began (a recorded session's pace: a replay
  // at that pace waits for it; unset where not recorded). Times never go back from one pose to a later one.
  std::vector<std::string> poseNotes;
  std::vector<std::optional<double>> poseTimesMs;
  std::string description;

  std::vector<Pose> expandedPoses() const;  // feed steps (start excluded), then the explicit poses
  // Beside expandedPoses(): true where that pose is placed (from placedPoses; the feed's steps never are).
  std::vector<bool> expandedPlacements() const;
  // Beside expandedPoses(): each pose's note and time (the feed's steps have neither).
  std::vector<std::string> expandedNotes() const;
  std::vector<std::optional<double>> expandedTimesMs() const;
  bool hasTimes() const;  // some pose has a time: the plan can be replayed at its recorded pace
  double maxStepMm() const;                 // largest tip displacement between consecutive poses

 private:
  template <class T>
  std::vector<T> besideExpandedPoses(const std::vector<T>& perPose) const;
};

// Throws reamsim::InputError naming the file and the problem.
ReamPlan loadPlan(const std::string& path);
ReamPlan parsePlan(const std::string& jsonText, const std::string& sourceName);
std::string planToJson(const ReamPlan& plan);

}  // namespace reamsim
