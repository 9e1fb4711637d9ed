// Every logged step carries the wall-clock time it was committed, and the CSV/JSON files give it in UTC.
#include <gtest/gtest.h>

#include <chrono>

#include "ReamFixture.h"
#include "reamsim/ream/CutLogIO.h"
#include "reamsim/tools/Primitives.h"

namespace reamsim {
namespace {

TEST(CutLog, StepsCarryTheirCommitTimeIntoTheFiles) {
  test::ReamScene s(test::blockBelowZ0(), test::flatReamer20());
  const auto now = [] {
    return std::chrono::duration_cast<std::chrono::milliseconds>(std::chrono::system_clock::now().time_since_epoch())
        .count();
  };
  const std::int64_t before = now();
  s.controller->moveTo(Pose{{0, 0, 0.5}, {0, 0, -1}, 0});
  s.controller->moveTo(Pose{{0, 0, -0.5}, {0, 0, -1}, 0});
  const std::int64_t after = now();
  ASSERT_GE(s.log->size(), 1u);
  const CutLogEntry& e = s.log->entries().back();
  EXPECT_TRUE(e.contact);
  EXPECT_GE(e.timeUnixMs, before);
  EXPECT_LE(e.timeUnixMs, after);

  EXPECT_EQ(isoTimeUtc(1795325231325), "2026-11-22T05:27:11.325Z");
  EXPECT_EQ(isoTimeUtc(0), "");
  const std::string csv = cutLogCsv(s.log->entries());
  EXPECT_EQ(csv.rfind("step,time_utc,", 0), 0u) << csv;
  EXPECT_NE(csv.find("," + isoTimeUtc(e.timeUnixMs) + ","), std::string::npos) << csv;
  EXPECT_NE(cutLogJson(s.log->entries()).find("\"time_utc\": \"" + isoTimeUtc(e.timeUnixMs) + "\""), std::string::npos);
}

}  // namespace
}  // namespace reamsim
