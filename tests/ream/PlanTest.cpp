#include <gtest/gtest.h>

#include "reamsim/mesh/MeshError.h"
#include "reamsim/ream/Plan.h"

namespace reamsim {
namespace {

TEST(Plan, FeedExpandsAlongTheAxis) {
  const ReamPlan p = parsePlan(
      R"({"reamer": "glenoid-36-R30", "feed": {"start": {"tip": [1, 2, 3], "axis": [0, 0, -2]}, "step_mm": 0.25, "count": 4}})",
      "plan.json");
  EXPECT_EQ(p.reamer, "glenoid-36-R30");
  const auto poses = p.expandedPoses();
  ASSERT_EQ(poses.size(), 4u);
  EXPECT_NEAR(poses[0].tip.z, 3 - 0.25, 1e-12);
  EXPECT_NEAR(poses[3].tip.z, 3 - 1.0, 1e-12);
  EXPECT_EQ(poses[3].axis, (Vec3{0, 0, -1}));
  EXPECT_NEAR(p.maxStepMm(), 0.25, 1e-12);
}

TEST(Plan, ExplicitPosesAndRoundTrip) {
  const ReamPlan p = parsePlan(
      R"({"poses": [{"tip": [0, 0, 0], "axis": [1, 0, 0]}, {"tip": [0, 0, 1], "axis": [1, 0, 0], "roll_deg": 30}]})",
      "plan.json");
  ASSERT_EQ(p.expandedPoses().size(), 2u);
  EXPECT_EQ(p.poses[1].rollDeg, 30);
  const ReamPlan q = parsePlan(planToJson(p), "again.json");
  EXPECT_EQ(q.poses.size(), 2u);
  EXPECT_EQ(q.poses[1].tip, p.poses[1].tip);
}

void expectRejected(const std::string& text, const std::string& fragment) {
  try {
    parsePlan(text, "bad_plan.json");
    FAIL() << "accepted: " << text;
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("bad_plan.json"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos) << e.what();
  }
}

TEST(Plan, BadPlansAreRejectedClearly) {
  expectRejected("{", "not valid JSON");
  expectRejected("[]", "must be a JSON object");
  expectRejected("{}", "neither");
  expectRejected(R"({"poses": [{"tip": [0, 0], "axis": [1, 0, 0]}]})", "poses[0].tip");
  expectRejected(R"({"poses": [{"tip": [0, 0, 0], "axis": [0, 0, 0]}]})", "must not be zero");
  expectRejected(R"({"feed": {"start": {"tip": [0, 0, 0], "axis": [0, 0, 1]}, "step_mm": -1, "count": 3}})", "step_mm");
  expectRejected(R"({"feed": {"start": {"tip": [0, 0, 0], "axis": [0, 0, 1]}, "step_mm": 0.1, "count": 0}})", "count");
  expectRejected(R"({"feed": {"start": {"tip": [0, 0, 0], "axis": [0, 0, 1]}, "count": 3}})", "step_mm");
  // Values whose derived poses would not be finite (fuzzing, session 26).
  expectRejected(R"({"poses": [{"tip": [0, 0, 0], "axis": [1e200, 0, 0]}]})", "beyond");
  expectRejected(R"({"poses": [{"tip": [0, 0, 1e300], "axis": [0, 0, 1]}]})", "beyond");
  expectRejected(R"({"feed": {"start": {"tip": [0, 0, 0], "axis": [0, 0, 1]}, "step_mm": 1e308, "count": 3}})",
                 "step_mm × feed.count");
  // A number beyond double: nlohmann-json's out_of_range escaped without the file's name (fuzzing, session 27).
  expectRejected(R"({"poses": [{"tip": [0, 0, 1)" + std::string(400, '1') + R"(], "axis": [0, 0, 1]}]})", "number overflow");
  EXPECT_THROW(loadPlan("/nonexistent/plan.json"), InputError);
}

// "placed": a recorded session's placements (nothing swept to the pose), kept through a round trip and
// counted after the feed's steps, which are never placed.
TEST(Plan, PlacedPosesRoundTripAndFollowTheFeed) {
  const ReamPlan p = parsePlan(
      R"({"feed": {"start": {"tip": [0, 0, 5], "axis": [0, 0, -1]}, "step_mm": 0.5, "count": 2},
          "poses": [{"tip": [0, 0, 0], "axis": [1, 0, 0], "placed": true}, {"tip": [0, 0, 1], "axis": [1, 0, 0]},
                    {"tip": [0, 0, 2], "axis": [1, 0, 0], "placed": false}, {"tip": [0, 0, 3], "axis": [1, 0, 0], "placed": true}]})",
      "plan.json");
  EXPECT_EQ(p.placedPoses, (std::vector<std::size_t>{0, 3}));
  EXPECT_EQ(p.expandedPlacements(), (std::vector<bool>{false, false, true, false, false, true}));
  const ReamPlan q = parsePlan(planToJson(p), "again.json");
  EXPECT_EQ(q.placedPoses, p.placedPoses);
  expectRejected(R"({"poses": [{"tip": [0, 0, 0], "axis": [1, 0, 0], "placed": 1}]})", "poses[0].placed must be true or false");
  expectRejected(R"({"feed": {"start": {"tip": [0, 0, 0], "axis": [1, 0, 0], "placed": true}, "step_mm": 1, "count": 1}})",
                 "feed.start.placed is for the poses");
}

// A recorded session's notes and times ("note", "t_ms"): kept through a round trip, counted after the feed's
// steps (which have neither), and refused clearly when they are not a string, or a time that is negative, huge
// or earlier than an earlier pose's.
TEST(Plan, NotesAndRecordedTimesRoundTrip) {
  const ReamPlan p = parsePlan(
      R"({"feed": {"start": {"tip": [0, 0, 5], "axis": [0, 0, -1]}, "step_mm": 0.5, "count": 2},
          "poses": [{"tip": [0, 0, 0], "axis": [1, 0, 0], "t_ms": 0, "note": "seat, \"then\" tilt\nslowly"},
                    {"tip": [0, 0, 1], "axis": [1, 0, 0]},
                    {"tip": [0, 0, 2], "axis": [1, 0, 0], "t_ms": 1250.5, "note": ""},
                    {"tip": [0, 0, 3], "axis": [1, 0, 0], "t_ms": 1250.5, "note": "5° – done ✓"}]})",
      "plan.json");
  EXPECT_EQ(p.poseNotes, (std::vector<std::string>{"seat, \"then\" tilt\nslowly", "", "", "5° – done ✓"}));
  ASSERT_EQ(p.poseTimesMs.size(), 4u);
  EXPECT_EQ(p.poseTimesMs[0], 0.0);
  EXPECT_FALSE(p.poseTimesMs[1].has_value());
  EXPECT_EQ(p.poseTimesMs[3], 1250.5);
  EXPECT_TRUE(p.hasTimes());
  EXPECT_EQ(p.expandedNotes(), (std::vector<std::string>{"", "", "seat, \"then\" tilt\nslowly", "", "", "5° – done ✓"}));
  const std::vector<std::optional<double>> times = p.expandedTimesMs();
  ASSERT_EQ(times.size(), 6u);
  EXPECT_FALSE(times[0].has_value());
  EXPECT_EQ(times[2], 0.0);
  EXPECT_EQ(times[5], 1250.5);
  const ReamPlan q = parsePlan(planToJson(p), "again.json");
  EXPECT_EQ(q.poseNotes, p.poseNotes);
  EXPECT_EQ(q.poseTimesMs, p.poseTimesMs);
  // A plan without them has none (and writes none).
  const ReamPlan bare = parsePlan(R"({"poses": [{"tip": [0, 0, 0], "axis": [1, 0, 0]}]})", "bare.json");
  EXPECT_TRUE(bare.poseNotes.empty());
  EXPECT_TRUE(bare.poseTimesMs.empty());
  EXPECT_FALSE(bare.hasTimes());
  EXPECT_EQ(bare.expandedNotes(), std::vector<std::string>{""});
  EXPECT_EQ(planToJson(bare).find("t_ms"), std::string::npos);
  expectRejected(R"({"poses": [{"tip": [0, 0, 0], "axis": [1, 0, 0], "note": 3}]})", "poses[0].note must be a string");
  expectRejected(R"({"poses": [{"tip": [0, 0, 0], "axis": [1, 0, 0], "t_ms": -1}]})", "poses[0].t_ms must be a number");
  expectRejected(R"({"poses": [{"tip": [0, 0, 0], "axis": [1, 0, 0], "t_ms": 1e12}]})", "from 0 to 1e9");
  expectRejected(R"({"poses": [{"tip": [0, 0, 0], "axis": [1, 0, 0], "t_ms": "1"}]})", "poses[0].t_ms");
  expectRejected(R"({"poses": [{"tip": [0, 0, 0], "axis": [1, 0, 0], "t_ms": 500}, {"tip": [0, 0, 1], "axis": [1, 0, 0]},
                               {"tip": [0, 0, 2], "axis": [1, 0, 0], "t_ms": 499}]})",
                 "poses[2].t_ms goes back in time (499.0 after 500.0)");
  expectRejected(R"({"feed": {"start": {"tip": [0, 0, 0], "axis": [1, 0, 0], "note": "x"}, "step_mm": 1, "count": 1}})",
                 "feed.start.note is for the poses");
}

}  // namespace
}  // namespace reamsim
