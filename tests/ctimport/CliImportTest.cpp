// reamsim-cli import-ct as a user runs it: exit codes, messages naming the file, the JSON report, and the
// imported bone cut by the reamer through reamsim-cli ream.
#include <gtest/gtest.h>

#include <cstdio>
#include <nlohmann/json.hpp>

#include "Phantom.h"
#include "RunCommand.h"
#include "TestUtil.h"
#include "reamsim/mesh/MeshIO.h"

namespace {

using namespace reamsim;

struct CliRun {
  int exitCode = -1;
  std::string out;  // stdout
  std::string all;  // stdout and stderr
};

CliRun run(const std::string& args) {
  const cttest::fs::path err = cttest::fs::temp_directory_path() / ("reamsim_ctcli_err_" + std::to_string(::getpid()));
  const reamsim::test::CommandOutput o =
      reamsim::test::runCommand(std::string(REAMSIM_CLI) + " " + args + " 2>" + err.string());
  return {o.exitCode, o.out, o.out + phantom::readBytes(err.string())};
}

// A small phantom volume on disk (sphere pierced by a cylinder).
std::string phantomNrrd(const cttest::fs::path& dir) {
  phantom::SphereAndCylinder shape;
  const phantom::Grid g = phantom::gridAround(shape.center, 26, {1, 1, 1}, phantom::rotation({0, 1, 1}, 25));
  const std::string path = (dir / "phantom.nrrd").string();
  phantom::writeNrrd(path, g, phantom::sample(g, [&](const Vec3& p) { return shape.inside(p); }));
  return path;
}

// A short plan: the reamer approaches the most lateral (+x) point of the bone along -x and feeds 1 mm in.
std::string planAgainst(const std::string& mesh, const cttest::fs::path& dir) {
  const TriangleMesh m = readMesh(mesh, {Units::Millimetres}).mesh;
  Vec3 lateral = m.vertices.front();
  for (const Vec3& p : m.vertices)
    if (p.x > lateral.x) lateral = p;
  const nlohmann::json plan = {
      {"description", "CT-import test: 8 steps of 0.5 mm along -x from 3 mm outside the most lateral point"},
      {"reamer", "glenoid-36-R30"},
      {"feed",
       {{"start", {{"tip", {lateral.x + 3, lateral.y, lateral.z}}, {"axis", {-1, 0, 0}}, {"roll_deg", 0}}},
        {"step_mm", 0.5},
        {"count", 8}}}};
  const std::string path = (dir / "plan.json").string();
  phantom::writeBytes(path, plan.dump(2));
  return path;
}

void expectReamCuts(const std::string& bone, const cttest::fs::path& dir) {
  const CliRun r = run("ream --bone " + bone + " --plan " + planAgainst(bone, dir) + " --out " + (dir / "ream").string() +
                       " --units mm --json");
  ASSERT_EQ(r.exitCode, 0) << r.all;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_GT(j["summary"]["removed_total_mm3"].get<double>(), 1.0) << r.out;
  EXPECT_TRUE(cttest::fs::exists(dir / "ream" / "bone_final.ply"));
  // The import was already clean: ream's own import check had nothing to repair.
  EXPECT_EQ(r.all.find("repaired on import"), std::string::npos) << r.all;
}

TEST(CliImportCt, PhantomToMeshWithJsonReport) {
  const cttest::fs::path dir = cttest::scratch("cli_phantom");
  const std::string out = (dir / "bone.ply").string();
  const CliRun r = run("import-ct " + phantomNrrd(dir) + " --threshold 620 --target-faces 3000 --out " + out + " --json");
  ASSERT_EQ(r.exitCode, 0) << r.all;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_TRUE(j["clean_solid"].get<bool>());
  EXPECT_EQ(j["mesh_space"], "LPS");
  EXPECT_LE(j["validation"]["triangles"].get<int>(), 3000);
  for (const char* stage : {"threshold", "regions", "isosurface", "decimation", "smoothing", "validation"})
    EXPECT_TRUE(j["stage_ms"].contains(stage)) << stage;
  EXPECT_GT(j["peak_rss_mb"].get<double>(), 1.0);
  EXPECT_GT(j["volume_to_mesh_ms"].get<double>(), 0.0);
  const TriangleMesh m = readMesh(out).mesh;
  EXPECT_EQ(m.triangles.size(), j["validation"]["triangles"].get<std::size_t>());
  expectReamCuts(out, dir);
}

TEST(CliImportCt, ErrorsNameTheFileAndUseTheDocumentedExitCodes) {
  const cttest::fs::path dir = cttest::scratch("cli_errors");
  const std::string nrrd = phantomNrrd(dir);
  const std::string bytes = phantom::readBytes(nrrd);
  const std::string cut = (dir / "cut.nrrd").string();
  phantom::writeBytes(cut, bytes.substr(0, bytes.size() / 2));
  CliRun r = run("import-ct " + cut + " --out " + (dir / "x.ply").string());
  EXPECT_EQ(r.exitCode, 3) << r.all;
  EXPECT_NE(r.all.find("cut.nrrd"), std::string::npos) << r.all;
  EXPECT_NE(r.all.find("truncated"), std::string::npos) << r.all;

  EXPECT_EQ(run("import-ct " + nrrd).exitCode, 2);  // no --out
  EXPECT_EQ(run("import-ct " + nrrd + " --out x.ply --space xyz").exitCode, 2);
  EXPECT_EQ(run("import-ct " + nrrd + " --out x.ply --threshold abc").exitCode, 2);
  r = run("import-ct " + nrrd + " --out x.ply --threshold 700 --upper-threshold 300");
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.all.find("upper threshold"), std::string::npos) << r.all;
  r = run("import-ct " + nrrd + " --out " + (dir / "y.ply").string() + " --threshold 5000");
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_NE(r.all.find("no voxel"), std::string::npos) << r.all;
  r = run("import-ct " + nrrd + " --threshold 620 --out " + (dir / "no_such_dir" / "z.ply").string());
  EXPECT_EQ(r.exitCode, 4) << r.all;
}

TEST(CliImportCt, HeadsqBoneIsCutByTheReamer) {
  const std::string headsq = cttest::kSharedData + "/ct_headsq/quarter.nhdr";
  if (!cttest::fs::exists(headsq)) GTEST_SKIP() << headsq << " not present";
  const cttest::fs::path dir = cttest::scratch("cli_headsq");
  const std::string out = (dir / "headsq.ply").string();
  const CliRun r = run("import-ct " + headsq + " --threshold 1150 --target-faces 20000 --out " + out + " --json");
  ASSERT_EQ(r.exitCode, 0) << r.all;
  expectReamCuts(out, dir);
}

}  // namespace
