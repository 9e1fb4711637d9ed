// reamsim-cli as a user runs it: exit codes, messages naming the file, outputs written.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "MachineReading.h"
#include "RunCommand.h"

namespace {
namespace fs = std::filesystem;

// stdout and stderr together
using CliRun = reamsim::test::CommandOutput;

CliRun run(const std::string& args) { return reamsim::test::runCommand(std::string(REAMSIM_CLI) + " " + args + " 2>&1"); }

fs::path scratch(const std::string& name) {
  fs::path p = fs::temp_directory_path() / ("reamsim_cli_test_" + std::to_string(::getpid())) / name;
  fs::create_directories(p.parent_path());
  return p;
}

const std::string kData = REAMSIM_TEST_DATA_DIR;
const std::string kResources = REAMSIM_RESOURCE_DIR;

TEST(Cli, UsageErrors) {
  EXPECT_EQ(run("").exitCode, 2);
  EXPECT_EQ(run("frobnicate").exitCode, 2);
  const CliRun r = run("info --bogus x");
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.out.find("unknown option --bogus"), std::string::npos) << r.out;
  EXPECT_EQ(run("--help").exitCode, 0);
}

// A repair says where it is on a terminal (one line on stderr, rewritten in place) and nothing more when
// stderr is a file or a pipe. `script` (util-linux) gives the command a terminal.
TEST(Cli, RepairShowsProgressOnATerminalOnly) {
  if (reamsim::test::runCommand("command -v script >/dev/null 2>&1").exitCode != 0) GTEST_SKIP() << "no script(1)";
  const std::string original = kResources + "/bones/scapula_R_opensim.vtp";  // needs the remesh
  const std::string command = std::string(REAMSIM_CLI) + " repair " + original + " --voxel 1.5 --out " +
                              scratch("progress.ply").string();
  const CliRun onTerminal = reamsim::test::runCommand("script -qec '" + command + "' /dev/null");
  EXPECT_EQ(onTerminal.exitCode, 0) << onTerminal.out;
  // "\r", clear to the end of the line, the command and the stage.
  EXPECT_NE(onTerminal.out.find("\r\033[Krepair: remesh: inside and outside near the surface"), std::string::npos)
      << onTerminal.out;
  EXPECT_NE(onTerminal.out.find("result: closed, outward-oriented solid"), std::string::npos) << onTerminal.out;
  const CliRun piped = run("repair " + original + " --voxel 1.5 --out " + scratch("progress2.ply").string());
  EXPECT_EQ(piped.exitCode, 0) << piped.out;
  EXPECT_EQ(piped.out.find("remesh: inside"), std::string::npos) << piped.out;
  EXPECT_EQ(piped.out.find('\r'), std::string::npos);
}

TEST(Cli, BenchWindingComparesTheTreeWithTheDirectSum) {
  const CliRun r = run("bench winding --mesh " + kResources + "/bones/scapula_R_opensim.vtp --points 200 --json");
  ASSERT_EQ(r.exitCode, 0) << r.out;
  const nlohmann::json j = nlohmann::json::parse(r.out.substr(r.out.find('{')));
  EXPECT_EQ(j.at("bench"), "winding");
  EXPECT_EQ(j.at("triangles"), 1543);
  EXPECT_EQ(j.at("points"), 200);
  EXPECT_EQ(j.at("direct").at("terms_per_point"), 1543);
  for (const char* k : {"tree_beta2", "tree_beta8"}) {
    const nlohmann::json& t = j.at(k);
    EXPECT_EQ(t.at("sign_disagreements"), 0) << k;
    EXPECT_LT(t.at("max_abs_error").get<double>(), 0.05) << k;
    EXPECT_GT(t.at("terms_per_point").get<double>(), 0.0) << k;
    EXPECT_GT(t.at("median_us").get<double>(), 0.0) << k;
  }
  // The tree sums fewer terms than the direct sum, and fewer at beta 2 than at beta 8 (counts, not times).
  EXPECT_LT(j.at("tree_beta2").at("terms_per_point").get<double>(), j.at("tree_beta8").at("terms_per_point").get<double>());
  EXPECT_LT(j.at("tree_beta8").at("terms_per_point").get<double>(), 1543.0);
  EXPECT_LT(j.at("tree_beta8").at("max_abs_error").get<double>(), j.at("tree_beta2").at("max_abs_error").get<double>());
  EXPECT_EQ(run("bench winding --mesh " + kResources + "/bones/scapula_R_opensim.vtp --points 3").exitCode, 2);
}

TEST(Cli, InfoReportsTheBundledScapula) {
  const CliRun r = run("info " + kResources + "/bones/scapula_R_opensim.vtp --json");
  ASSERT_EQ(r.exitCode, 0) << r.out;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["vertices"], 770);
  EXPECT_EQ(j["triangles"], 1543);
  EXPECT_EQ(j["closed"], false);
  EXPECT_GT(j["self_intersecting_pairs"].get<int>(), 0);
}

// bench cut says how fast the machine was around ReamSim's steps (MachineSpeed.h), as bench collision does.
TEST(Cli, BenchCutReportsTheMachineSpeed) {
  const CliRun r = reamsim::test::runCommand(std::string(REAMSIM_CLI) + " bench cut --steps 2 --json 2>/dev/null");
  ASSERT_EQ(r.exitCode, 0) << r.out;
  reamsim::test::expectMachineReading(nlohmann::json::parse(r.out).at("machine"));
}

// bench cut --loop also measures the crash-recovery journal of the loop's history: appended after each cut and
// read back to the same bone.
TEST(Cli, BenchCutLoopMeasuresTheRecoveryJournal) {
  const CliRun r = reamsim::test::runCommand(std::string(REAMSIM_CLI) + " bench cut --steps 12 --loop --json 2>/dev/null");
  ASSERT_EQ(r.exitCode, 0) << r.out;
  const nlohmann::json j = nlohmann::json::parse(r.out).at("loop").at("recovery_journal");
  EXPECT_TRUE(j.at("replayed_state_matches").get<bool>()) << j.dump();
  EXPECT_GT(j.at("first_record_bytes").get<double>(), 14998 * 16.0);  // every triangle of the bundled bone
  EXPECT_EQ(j.at("states").get<int>(), nlohmann::json::parse(r.out).at("loop").at("cuts").get<int>() + 1);
}

TEST(Cli, MalformedFilesExitWithCodeThreeAndNameTheFile) {
  int checked = 0;
  for (const auto& entry : fs::directory_iterator(kData + "/malformed")) {
    if (entry.path().extension() == ".tsv" || entry.path().extension() == ".md") continue;
    const CliRun r = run("info '" + entry.path().string() + "'");
    EXPECT_EQ(r.exitCode, 3) << entry.path() << "\n" << r.out;
    EXPECT_NE(r.out.find(entry.path().filename().string()), std::string::npos) << r.out;
    ++checked;
  }
  EXPECT_GE(checked, 15);
}

TEST(Cli, ExportConvertsBetweenFormats) {
  const fs::path out = scratch("scapula.stl");
  const CliRun r = run("export default --out " + out.string());
  ASSERT_EQ(r.exitCode, 0) << r.out;
  const CliRun info = run("info " + out.string() + " --json --units mm");
  ASSERT_EQ(info.exitCode, 0) << info.out;
  const auto j = nlohmann::json::parse(info.out);
  EXPECT_EQ(j["closed"], true);
  EXPECT_EQ(run("export default --out /nonexistent-dir/x.stl").exitCode, 4);
}

// ReamSim's patient frame goes on into the converted file; another program's comments do not, nor what a save
// recorded of the cut log beside the file (no log is beside the export).
TEST(Cli, ExportKeepsThePatientFrame) {
  const fs::path in = scratch("framed.ply");
  std::ofstream(in) << "ply\nformat ascii 1.0\ncomment made by hand\ncomment reamsim patient_frame RAS\n"
                       "comment reamsim cut_log 3 1764781234567\ncomment reamsim removed_mm3 12.5\n"
                       "element vertex 4\nproperty double x\nproperty double y\nproperty double z\n"
                       "element face 4\nproperty list uchar int vertex_indices\nend_header\n"
                       "0 0 0\n10 0 0\n0 10 0\n0 0 10\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n";
  for (const char* ext : {".obj", ".off"}) {
    const fs::path out = scratch(std::string("framed") + ext);
    const CliRun r = run("export " + in.string() + " --out " + out.string());
    ASSERT_EQ(r.exitCode, 0) << r.out;
    std::ifstream f(out);
    const std::string text((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
    EXPECT_NE(text.find("# reamsim patient_frame RAS\n"), std::string::npos) << ext << "\n" << text.substr(0, 200);
    EXPECT_EQ(text.find("made by hand"), std::string::npos) << ext;
    // info lists a file's comments, where the frame is.
    const CliRun info = run("info " + out.string() + " --json");
    ASSERT_EQ(info.exitCode, 0) << info.out;
    const auto comments = nlohmann::json::parse(info.out)["comments"];
    EXPECT_EQ(comments, nlohmann::json({"written by ReamSim", "reamsim patient_frame RAS"})) << ext;
  }
}

TEST(Cli, ReamWritesLogsAndMesh) {
  const fs::path plan = scratch("plan.json");
  {
    // Three steps of the default feed, taken from the default plan's start (found by the glenoid).
    std::ifstream in(kResources + "/plans/default_plan.json");
    nlohmann::json p = nlohmann::json::parse(in);
    p["feed"]["count"] = 10;
    p["feed"]["step_mm"] = 0.25;
    std::ofstream(plan) << p.dump();
  }
  const fs::path dir = scratch("ream-out");
  const CliRun r = run("ream --bone default --reamer glenoid-36-R30 --plan " + plan.string() + " --out " + dir.string());
  ASSERT_EQ(r.exitCode, 0) << r.out;
  EXPECT_NE(r.out.find("removed_mm3"), std::string::npos);
  ASSERT_TRUE(fs::exists(dir / "log.csv"));
  ASSERT_TRUE(fs::exists(dir / "log.json"));
  ASSERT_TRUE(fs::exists(dir / "bone_final.ply"));
  std::ifstream csv(dir / "log.csv");
  std::string line, header;
  int rows = -1;
  while (std::getline(csv, line)) header = ++rows == 0 ? line : header;
  EXPECT_EQ(rows, 10);
  // The bundled landmarks come with the default bone: each step's version and inclination, and the glenoid face.
  EXPECT_EQ(header.substr(header.size() - 28), ",version_deg,inclination_deg") << header;
  std::ifstream js(dir / "log.json");
  const auto j = nlohmann::json::parse(js);
  EXPECT_EQ(j["steps"].size(), 10u);
  EXPECT_TRUE(j["summary"]["glenoid_face"]["as_opened"].contains("version_deg")) << j["summary"].dump();
  EXPECT_TRUE(j["summary"]["glenoid_face"]["now"].contains("version_deg")) << j["summary"].dump();
  EXPECT_TRUE(j["steps"][0]["version_deg"].is_number()) << j["steps"][0].dump();  // as the CSV's column
  const fs::path bare = scratch("ream-out-bare");
  ASSERT_EQ(run("ream --bone default --reamer glenoid-36-R30 --plan " + plan.string() + " --landmarks none --out " +
                bare.string()).exitCode, 0);
  std::ifstream bareCsv(bare / "log.csv");
  std::getline(bareCsv, header);
  EXPECT_EQ(header.substr(header.size() - 12), ",undone,note") << header;
  std::ifstream bareJson(bare / "log.json");
  EXPECT_FALSE(nlohmann::json::parse(bareJson)["steps"][0].contains("version_deg"));
  EXPECT_GT(j["summary"]["removed_total_mm3"].get<double>(), 0.0);
  EXPECT_LT(j["summary"]["max_volume_bookkeeping_error_rel"].get<double>(), 1e-6);
}

// The default plan with and without the band clean-up: the same removed volume to 1e-4 (the clean-up moves
// the surface by at most a micrometre per operation), fewer faces with it, exact bookkeeping both ways.
TEST(Cli, ReamWithAndWithoutTheBandCleanup) {
  nlohmann::json logs[2];
  for (int i = 0; i < 2; ++i) {
    const fs::path dir = scratch(i ? "ream-exact" : "ream-cleaned");
    const CliRun r = run("ream --bone default --plan default --out " + dir.string() + (i ? " --no-cleanup" : ""));
    ASSERT_EQ(r.exitCode, 0) << r.out;
    std::ifstream js(dir / "log.json");
    logs[i] = nlohmann::json::parse(js);
    EXPECT_LT(logs[i]["summary"]["max_volume_bookkeeping_error_rel"].get<double>(), 1e-9);
  }
  const double cleaned = logs[0]["summary"]["removed_total_mm3"], exact = logs[1]["summary"]["removed_total_mm3"];
  EXPECT_GT(exact, 1000.0);
  EXPECT_NEAR(cleaned, exact, 1e-4 * exact);
  const auto faces = [](const nlohmann::json& j) { return j["summary"]["faces_end"].get<double>(); };
  EXPECT_LT(faces(logs[0]), faces(logs[1]));
}

TEST(Cli, ReamRejectsBadInputsClearly) {
  const CliRun badPreset = run("ream --bone default --reamer no-such-reamer --out " + scratch("x").string());
  EXPECT_NE(badPreset.exitCode, 0);
  EXPECT_NE(badPreset.out.find("no-such-reamer"), std::string::npos) << badPreset.out;
  const fs::path badPlan = scratch("bad.json");
  std::ofstream(badPlan) << "{\"feed\": 3}";
  const CliRun r = run("ream --bone default --plan " + badPlan.string() + " --out " + scratch("y").string());
  EXPECT_EQ(r.exitCode, 3);
  EXPECT_NE(r.out.find("bad.json"), std::string::npos) << r.out;
  const CliRun badBone = run("ream --bone " + kData + "/malformed/" +
                          fs::directory_iterator(kData + "/malformed")->path().filename().string() + " --out " +
                          scratch("z").string());
  EXPECT_NE(badBone.exitCode, 0);
  EXPECT_EQ(run("ream --out").exitCode, 2);
}

}  // namespace

namespace {
nlohmann::json parseJson(const CliRun& r) {
  try {
    return nlohmann::json::parse(r.out);
  } catch (const std::exception& e) {
    ADD_FAILURE() << e.what() << "\n" << r.out;
    return {};
  }
}
}  // namespace

// The planning loop on the command line: angles -> a plan -> the plan's axis measured back -> reamed along it.
TEST(Cli, AxisAimsAPlanAtAVersionAndInclinationAndMeasuresItBack) {
  const fs::path plan = scratch("aimed_plan.json");
  const CliRun aimed = run("axis --version -8.5 --inclination 4 --clearance 6 --count 40 --plan-out " + plan.string());
  ASSERT_EQ(aimed.exitCode, 0) << aimed.out;
  ASSERT_TRUE(fs::exists(plan));
  const nlohmann::json a = parseJson(aimed);
  EXPECT_EQ(a["side"], "right");
  const CliRun back = run("axis --plan " + plan.string());
  ASSERT_EQ(back.exitCode, 0) << back.out;
  const nlohmann::json m = parseJson(back);
  ASSERT_EQ(m["axes"].size(), 1u);
  EXPECT_NEAR(m["axes"][0]["version_deg"].get<double>(), -8.5, 1e-9);
  EXPECT_NEAR(m["axes"][0]["inclination_deg"].get<double>(), 4, 1e-9);
  // The plan reams the bundled bone: 40 steps of 0.2 mm from 6 mm out reach 2 mm past the glenoid centre.
  const fs::path dir = scratch("aimed-ream");
  const CliRun r = run("ream --bone default --plan " + plan.string() + " --out " + dir.string());
  ASSERT_EQ(r.exitCode, 0) << r.out;
  std::ifstream js(dir / "log.json");
  const auto log = nlohmann::json::parse(js);
  EXPECT_GT(log["summary"]["removed_total_mm3"].get<double>(), 100.0);
  EXPECT_NEAR(log["summary"]["last_pose_version_deg"].get<double>(), -8.5, 1e-9);
  // The report beside the log says the same, cut by cut.
  std::ifstream reportFile(dir / "report.html");
  std::stringstream report;
  report << reportFile.rdbuf();
  EXPECT_NE(report.str().find("-8.5° (retroversion), 4.0° (superior)"), std::string::npos);
  // A pose's note (an educator's annotation) goes to that step's row, in the log and the report.
  {
    std::ifstream in(plan);
    nlohmann::json noted = nlohmann::json::parse(in);
    const nlohmann::json& feed = noted["feed"];
    nlohmann::json pose = feed["start"];
    const double advance = feed["step_mm"].get<double>() * (feed["count"].get<int>() + 0.5);
    for (int k = 0; k < 3; ++k)
      pose["tip"][k] = pose["tip"][k].get<double>() + advance * pose["axis"][k].get<double>();
    pose["note"] = "last half step, \"gently\" <here>";
    noted["poses"] = nlohmann::json::array({pose});
    const fs::path notedPlan = scratch("noted_plan.json");
    std::ofstream(notedPlan) << noted.dump();
    const CliRun n = run("ream --bone default --plan " + notedPlan.string() + " --out " + dir.string());
    ASSERT_EQ(n.exitCode, 0) << n.out;
    std::ifstream notedLog(dir / "log.json");
    const auto rows = nlohmann::json::parse(notedLog)["steps"];
    ASSERT_EQ(rows.size(), std::size_t(feed["count"].get<int>() + 1));
    EXPECT_EQ(rows.back()["note"], "last half step, \"gently\" <here>");
    EXPECT_EQ(rows.front()["note"], "");
    std::ifstream notedReport(dir / "report.html");
    std::stringstream html;
    html << notedReport.rdbuf();
    EXPECT_NE(html.str().find("last half step, &quot;gently&quot; &lt;here&gt;"), std::string::npos);
  }
  const CliRun bare = run("ream --bone default --plan " + plan.string() + " --landmarks none --out " + dir.string());
  ASSERT_EQ(bare.exitCode, 0) << bare.out;
  std::ifstream bareFile(dir / "report.html");
  std::stringstream bareReport;
  bareReport << bareFile.rdbuf();
  EXPECT_NE(bareReport.str().find("No scapular frame"), std::string::npos);
  EXPECT_EQ(run("ream --bone default --plan " + plan.string() + " --landmarks /nonexistent.json --out " + dir.string()).exitCode, 3);
  // The same angles through --axis, and the default plan's axis measured by default.
  const std::vector<double> axis = a["aimed"]["axis"].get<std::vector<double>>();
  std::ostringstream arg;
  arg.precision(17);
  arg << axis[0] << "," << axis[1] << "," << axis[2];
  const nlohmann::json byAxis = parseJson(run("axis --axis " + arg.str()));
  EXPECT_NEAR(byAxis["axes"][0]["version_deg"].get<double>(), -8.5, 1e-9);
  const nlohmann::json byDefault = parseJson(run("axis"));
  ASSERT_EQ(byDefault["axes"].size(), 1u);
  EXPECT_NE(byDefault["axes"][0]["source"].get<std::string>().find("default_plan.json"), std::string::npos);
}

// --bone measures the glenoid face about the landmarks' glenoid centre; each axis says what it corrects of it.
TEST(Cli, AxisMeasuresTheGlenoidFaceAndWhatEachAxisCorrects) {
  const CliRun r = run("axis --bone default");
  ASSERT_EQ(r.exitCode, 0) << r.out;
  const nlohmann::json out = parseJson(r);
  const nlohmann::json& face = out["glenoid_face"];
  EXPECT_EQ(face["bone"], "the bundled scapula");
  EXPECT_EQ(face["radius_mm"].get<double>(), 10);
  EXPECT_GT(face["triangles"].get<int>(), 50);
  const double version = face["version_deg"].get<double>(), inclination = face["inclination_deg"].get<double>();
  const nlohmann::json& axis = out["axes"][0];
  EXPECT_NEAR(axis["correction_deg"]["version"].get<double>(), axis["version_deg"].get<double>() - version, 1e-12);
  EXPECT_NEAR(axis["correction_deg"]["inclination"].get<double>(), axis["inclination_deg"].get<double>() - inclination, 1e-12);
  // Aimed along the glenoid's own angles: no correction.
  std::ostringstream aim;
  aim.precision(17);
  aim << "axis --bone default --version " << version << " --inclination " << inclination;
  const nlohmann::json along = parseJson(run(aim.str()));
  EXPECT_NEAR(along["aimed"]["correction_deg"]["version"].get<double>(), 0, 1e-9);
  EXPECT_NEAR(along["aimed"]["correction_deg"]["inclination"].get<double>(), 0, 1e-9);
  // A radius outside 2..40 mm, or a glenoid centre off the bone, is named.
  CliRun bad = run("axis --bone default --glenoid-radius 100");
  EXPECT_EQ(bad.exitCode, 3);
  EXPECT_NE(bad.out.find("the bundled scapula: glenoid face: the glenoid face is measured within 2 to 40 mm"), std::string::npos)
      << bad.out;
  const fs::path away = scratch("away_landmarks.json");
  std::ofstream(away) << R"({"side": "right", "glenoid_centre": [100, 100, 300], "trigonum_scapulae": [-100, 0, 100],)"
                      << R"( "inferior_angle": [-80, -120, 110]})";
  bad = run("axis --bone default --landmarks " + away.string());
  EXPECT_EQ(bad.exitCode, 3);
  EXPECT_NE(bad.out.find("no bone surface lies within 10 mm of the glenoid centre"), std::string::npos) << bad.out;
  EXPECT_EQ(run("axis --glenoid-radius 8").exitCode, 2);  // without --bone
  EXPECT_EQ(run("axis --bone " + away.string()).exitCode, 2);  // another bone without its landmarks
}

TEST(Cli, AxisRejectsBadLandmarksAndAnglesClearly) {
  const fs::path half = scratch("half_landmarks.json");
  std::ofstream(half) << R"({"side": "right", "glenoid_centre": [1, 2, 3]})";
  CliRun r = run("axis --landmarks " + half.string());
  EXPECT_EQ(r.exitCode, 3);
  EXPECT_NE(r.out.find(half.string() + ": the trigonum scapulae is not placed"), std::string::npos) << r.out;
  const fs::path broken = scratch("broken_landmarks.json");
  std::ofstream(broken) << R"({"side": "sideways"})";
  r = run("axis --landmarks " + broken.string());
  EXPECT_EQ(r.exitCode, 3);
  EXPECT_NE(r.out.find("\"side\" must be"), std::string::npos) << r.out;
  r = run("axis --version 90 --inclination 0");
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.out.find("within ±89 degrees"), std::string::npos) << r.out;
  r = run("axis --axis 1,0,0");  // the bundled scapula's posterior-medial: not a reaming direction
  EXPECT_EQ(r.exitCode, 3);
  EXPECT_NE(r.out.find("points medially"), std::string::npos) << r.out;
  EXPECT_EQ(run("axis --axis 0,0,0").exitCode, 2);
  EXPECT_EQ(run("axis --version 5 --axis 0,0,-1").exitCode, 2);
  EXPECT_EQ(run("axis --plan-out x.json").exitCode, 2);
}
