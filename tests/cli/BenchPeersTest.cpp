// bench cut --peers with the npm peers (bench/peers, run with node) on a tiny sequence: a box with a
// raised top centre, two steps of the default reamer (the first short of the bone, the second cutting).
// Checks results, never times. Skips when node or bench/peers/node_modules is missing (npm ci there).
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "RunCommand.h"

namespace {
namespace fs = std::filesystem;

const std::string kPeersDir = REAMSIM_PEERS_DIR;

using Run = reamsim::test::CommandOutput;

Run run(const std::string& command) { return reamsim::test::runCommand(command + " 2>/dev/null </dev/null"); }

fs::path scratch(const std::string& name) {
  fs::path p = fs::temp_directory_path() / ("reamsim_peers_test_" + std::to_string(::getpid())) / name;
  fs::create_directories(p.parent_path());
  return p;
}

// 40 x 40 x 10 mm box, the top a fan about a centre raised 0.2 mm (the bench's spot: the highest vertex).
// `open`: without the two bottom faces (a bone with an open border away from the cut).
fs::path writeBox(const std::string& name, bool open) {
  const fs::path path = scratch(name);
  const char* vertices =
      "-20 -20 0\n20 -20 0\n20 20 0\n-20 20 0\n-20 -20 10\n20 -20 10\n20 20 10\n-20 20 10\n0 0 10.2\n";
  std::string faces =
      "3 4 5 8\n3 5 6 8\n3 6 7 8\n3 7 4 8\n3 0 1 5\n3 0 5 4\n3 1 2 6\n3 1 6 5\n3 2 3 7\n3 2 7 6\n3 3 0 4\n3 3 4 7\n";
  if (!open) faces += "3 0 2 1\n3 0 3 2\n";
  std::ofstream(path) << "ply\nformat ascii 1.0\nelement vertex 9\nproperty double x\nproperty double y\n"
                         "property double z\nelement face "
                      << (open ? 12 : 14) << "\nproperty list uchar int vertex_indices\nend_header\n"
                      << vertices << faces;
  return path;
}

nlohmann::json benchCut(const fs::path& bone, const std::string& extra = "") {
  const Run r = run(std::string(REAMSIM_CLI) + " bench cut --bone " + bone.string() +
                    " --units mm --steps 2 --peers --json" + extra);
  const auto start = r.out.find('{');
  EXPECT_NE(start, std::string::npos) << r.out;
  return nlohmann::json::parse(r.out.substr(start == std::string::npos ? 0 : start));
}

bool nodePeersInstalled(std::string& why) {
  if (run("node --version").exitCode != 0) {
    why = "node not found on PATH";
    return false;
  }
  for (const char* package : {"manifold-3d", "csg"})
    if (!fs::exists(fs::path(kPeersDir) / "node_modules" / package)) {
      why = "bench/peers/node_modules missing (run npm ci in bench/peers)";
      return false;
    }
  return true;
}

TEST(BenchPeers, MissingNodeModulesAreReportedNotFaked) {
  const fs::path empty = scratch("no-peers");
  fs::create_directories(empty);
  const nlohmann::json j = benchCut(writeBox("closed.ply", false), " --peers-dir " + empty.string());
  for (const char* peer : {"manifold_3d", "csgjs_bsp"}) {
    const nlohmann::json& p = j["peers"][peer];
    ASSERT_TRUE(p.contains("not_run")) << p.dump();
    EXPECT_FALSE(p.contains("median_ms")) << p.dump();
    EXPECT_FALSE(p.contains("ratio_to_reamsim")) << p.dump();
  }
}

TEST(BenchPeers, EndVolumesAgreeWithReamSimAndTheReference) {
  std::string why;
  if (!nodePeersInstalled(why)) GTEST_SKIP() << why;
  // The Boolean alone (no band clean-up), so that the exact end volumes can be compared.
  const nlohmann::json j = benchCut(writeBox("closed.ply", false), " --no-cleanup");
  ASSERT_EQ(j["cuts"], 1) << j.dump();  // the second step cuts, the first does not reach the box
  const double removed = j["removed_mm3"].get<double>();
  ASSERT_GT(removed, 100.0);
  const nlohmann::json& cgal = j["peers"]["cgal_corefinement_epeck"];
  const double volumeEnd = cgal["volume_end_mm3"].get<double>();
  EXPECT_LT(cgal["volume_end_diff_rel"].get<double>(), 1e-12) << cgal.dump();

  const nlohmann::json& m = j["peers"]["manifold_3d"];
  ASSERT_FALSE(m.contains("refused")) << m.dump();
  ASSERT_FALSE(m.contains("error")) << m.dump();
  EXPECT_EQ(m["steps_completed"], 2) << m.dump();
  EXPECT_EQ(m["coordinates"]["bone"], "double") << m.dump();
  // Manifold's end volume against ReamSim's (and so the reference's), relative to the removed volume.
  EXPECT_NEAR(m["volume_end_mm3"].get<double>(), volumeEnd, 1e-6 * removed) << m.dump();
  EXPECT_TRUE(m["ratio_to_reamsim"].is_number()) << m.dump();
  EXPECT_TRUE(m["median_ms"].is_number()) << m.dump();

  // csg.js finishes two steps on a 14-face box; its planes are tested with EPSILON 1e-5 mm.
  const nlohmann::json& c = j["peers"]["csgjs_bsp"];
  ASSERT_FALSE(c.contains("error")) << c.dump();
  EXPECT_EQ(c["steps_completed"], 2) << c.dump();
  EXPECT_NEAR(c["volume_end_mm3"].get<double>(), volumeEnd, 1e-4 * removed) << c.dump();
}

TEST(BenchPeers, RefusedInputIsRecordedAsRefused) {
  std::string why;
  if (!nodePeersInstalled(why)) GTEST_SKIP() << why;
  const nlohmann::json j = benchCut(writeBox("open.ply", true));
  // ReamSim cuts away from the open border; the whole-mesh peers that need a closed solid refuse it.
  EXPECT_EQ(j["cuts"], 1) << j.dump();
  EXPECT_TRUE(j["peers"]["cgal_corefinement_epeck"].contains("refused")) << j["peers"].dump();
  const nlohmann::json& m = j["peers"]["manifold_3d"];
  ASSERT_TRUE(m.contains("refused")) << m.dump();
  EXPECT_NE(m["refused"].get<std::string>().find("NotManifold"), std::string::npos) << m.dump();
  EXPECT_FALSE(m.contains("median_ms")) << m.dump();
  EXPECT_FALSE(m.contains("ratio_to_reamsim")) << m.dump();
  EXPECT_EQ(m["input_bone_edges"]["border_edges"], 4) << m.dump();
  // csg.js checks nothing: it runs, and the record says what it was given.
  const nlohmann::json& c = j["peers"]["csgjs_bsp"];
  EXPECT_FALSE(c.contains("refused")) << c.dump();
  EXPECT_EQ(c["input_bone_edges"]["border_edges"], 4) << c.dump();
  EXPECT_EQ(c["input_checks"], "none (csg.js accepts any polygon soup)") << c.dump();
  EXPECT_FALSE(c.contains("volume_end_diff_rel")) << c.dump();
}

}  // namespace
