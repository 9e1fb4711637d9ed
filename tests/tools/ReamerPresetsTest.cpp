#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <stdexcept>

#include "MeshChecks.h"
#include "reamsim/mesh/MeshError.h"
#include "reamsim/tools/ReamerGeometry.h"
#include "reamsim/tools/ReamerPresets.h"

using namespace reamsim;

namespace {
const std::string kPresets = std::string(REAMSIM_RESOURCE_DIR) + "/reamers.json";

template <class F>
std::string errorOf(F&& f) {
  try {
    f();
  } catch (const std::exception& e) {
    return e.what();
  }
  return "(no exception)";
}
bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }
}  // namespace

TEST(toolsReamerPresets, ShippedPresetsSpanTheRealSizesAndAllBuild) {
  const std::vector<ReamerSpec> presets = loadPresets(kPresets);
  ASSERT_GE(presets.size(), 9u);
  double minD = 1e9, maxD = 0, minR = 1e9, maxR = 0;
  int flats = 0;
  for (const ReamerSpec& s : presets) {
    SCOPED_TRACE(s.name);
    minD = std::min(minD, s.diameterMm);
    maxD = std::max(maxD, s.diameterMm);
    if (s.isFlat()) {
      ++flats;
    } else {
      minR = std::min(minR, s.sphereRadiusMm);
      maxR = std::max(maxR, s.sphereRadiusMm);
    }
    EXPECT_GE(s.guidePinDiameterMm, 2.5);
    EXPECT_LE(s.guidePinDiameterMm, 3.2);
    EXPECT_GT(s.guidePinLengthMm, 0);
    EXPECT_GT(s.shaftDiameterMm, 0);
    const TriangleMesh m = buildCuttingSolid(s);
    EXPECT_TRUE(test::isClosedOriented(m));
    const double v = signedVolume(m);
    EXPECT_GT(v, 0);
    EXPECT_LT(std::abs(v - idealCuttingVolume(s)) / idealCuttingVolume(s), 0.01);  // default 96 x 12
    const ReamerDisplayParts parts = buildDisplayParts(s);
    EXPECT_TRUE(test::isClosedOriented(parts.guidePin));
    EXPECT_TRUE(test::isClosedOriented(parts.shaft));
  }
  EXPECT_EQ(minD, 27.0);
  EXPECT_EQ(maxD, 56.0);
  EXPECT_EQ(minR, 25.0);
  EXPECT_EQ(maxR, 40.0);
  EXPECT_GE(flats, 2);
}

TEST(toolsReamerPresets, LoadsOnePresetByName) {
  const ReamerSpec s = loadPreset("glenoid-36-R30", kPresets);
  EXPECT_EQ(s.name, "glenoid-36-R30");
  EXPECT_EQ(s.diameterMm, 36.0);
  EXPECT_EQ(s.sphereRadiusMm, 30.0);
  const ReamerSpec f = loadPreset("baseplate-27-flat", kPresets);
  EXPECT_TRUE(f.isFlat());
  EXPECT_EQ(f.diameterMm, 27.0);
  for (const char* name : {"glenoid-28-R25", "glenoid-40-R32", "glenoid-44-R35", "glenoid-48-R36",
                           "glenoid-52-R38", "glenoid-56-R40", "peripheral-42-flat"})
    EXPECT_NO_THROW(loadPreset(name, kPresets)) << name;
}

TEST(toolsReamerPresets, UnknownNameListsKnownOnes) {
  const std::string msg = errorOf([] { loadPreset("glenoid-99", kPresets); });
  EXPECT_TRUE(contains(msg, "unknown reamer preset 'glenoid-99'")) << msg;
  EXPECT_TRUE(contains(msg, "glenoid-36-R30")) << msg;
  EXPECT_TRUE(contains(msg, "baseplate-27-flat")) << msg;
  EXPECT_THROW(loadPreset("glenoid-99", kPresets), std::invalid_argument);
}

TEST(toolsReamerPresets, MissingFile) {
  EXPECT_THROW(loadPresets("/nonexistent/reamers.json"), InputError);
}

TEST(toolsReamerPresets, MalformedJsonReportsTheLine) {
  try {
    parsePresets("{\n  \"presets\": [\n    { \"name\": \"a\", }\n  ]\n}", "bad.json");
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "bad.json");
    EXPECT_EQ(e.line(), 3);
    EXPECT_TRUE(contains(e.what(), "malformed JSON")) << e.what();
  }
}

// Found by fuzzing (session 27): nlohmann-json's out_of_range for a number beyond double escaped without
// the file's name.
TEST(toolsReamerPresets, NumberBeyondDoubleNamesTheFile) {
  try {
    parsePresets("[{\"name\": \"a\", \"diameterMm\": 1" + std::string(400, '1') + "}]", "huge.json");
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "huge.json");
    EXPECT_TRUE(contains(e.what(), "number overflow")) << e.what();
  }
}

TEST(toolsReamerPresets, StructuralProblemsNameThePresetAndField) {
  EXPECT_TRUE(contains(errorOf([] { parsePresets("{\"reamers\": []}"); }), "\"presets\""));
  EXPECT_TRUE(contains(errorOf([] { parsePresets("{\"presets\": {}}"); }), "must be an array"));
  EXPECT_TRUE(contains(errorOf([] { parsePresets("[{\"diameterMm\": 40, \"sphereRadiusMm\": 30}]"); }),
                       "\"name\""));
  const std::string typo =
      errorOf([] { parsePresets("[{\"name\":\"x\",\"diameterMm\":40,\"sphereRadiusMm\":30,\"bodyLenght\":3}]"); });
  EXPECT_TRUE(contains(typo, "'x'") && contains(typo, "unknown key \"bodyLenght\"")) << typo;
  const std::string wrongType =
      errorOf([] { parsePresets("[{\"name\":\"x\",\"diameterMm\":\"40\",\"sphereRadiusMm\":30}]"); });
  EXPECT_TRUE(contains(wrongType, "\"diameterMm\" must be a number")) << wrongType;
  const std::string tooWide =
      errorOf([] { parsePresets("[{\"name\":\"wide\",\"diameterMm\":60,\"sphereRadiusMm\":25}]"); });
  EXPECT_TRUE(contains(tooWide, "'wide'") && contains(tooWide, "D/2 <= R")) << tooWide;
  const std::string noRadius = errorOf([] { parsePresets("[{\"name\":\"x\",\"diameterMm\":40}]"); });
  EXPECT_TRUE(contains(noRadius, "\"sphereRadiusMm\" is required")) << noRadius;
  const std::string dup = errorOf([] {
    parsePresets("[{\"name\":\"x\",\"diameterMm\":40,\"sphereRadiusMm\":30},"
                 "{\"name\":\"x\",\"diameterMm\":44,\"sphereRadiusMm\":30}]");
  });
  EXPECT_TRUE(contains(dup, "used twice")) << dup;
  EXPECT_THROW(parsePresets("[{\"name\":\"x\",\"diameterMm\":40,\"sphereRadiusMm\":30,\"segments\":2.5}]"),
               InputError);
}

TEST(toolsReamerPresets, BareArrayAndDefaults) {
  const auto specs = parsePresets("[{\"name\":\"f\",\"diameterMm\":30,\"sphereRadiusMm\":\"flat\"}]");
  ASSERT_EQ(specs.size(), 1u);
  EXPECT_TRUE(specs[0].isFlat());
  const ReamerSpec defaults;
  EXPECT_EQ(specs[0].segments, defaults.segments);
  EXPECT_EQ(specs[0].bodyLengthMm, defaults.bodyLengthMm);
}

TEST(toolsReamerPresets, SingleSpecFromJsonText) {
  const ReamerSpec s = reamerSpecFromJsonText(
      R"({"name":"r","diameterMm":40,"sphereRadiusMm":32,"bodyLengthMm":8,"segments":64,"rings":10})");
  EXPECT_EQ(s.name, "r");
  EXPECT_EQ(s.sphereRadiusMm, 32.0);
  EXPECT_EQ(s.bodyLengthMm, 8.0);
  EXPECT_EQ(s.segments, 64);
  EXPECT_EQ(s.rings, 10);
  EXPECT_THROW(reamerSpecFromJsonText("{\"name\":"), InputError);
}

TEST(toolsReamerPresets, RelativeMeshFileIsResolvedAgainstTheJsonFolder) {
  const auto dir = std::filesystem::temp_directory_path() / "reamsim_tools_presets_test";
  std::filesystem::create_directories(dir);
  const auto path = dir / "presets.json";
  std::ofstream(path) << R"({"presets":[{"name":"custom","meshFile":"custom.stl"}]})";
  const ReamerSpec s = loadPreset("custom", path.string());
  EXPECT_EQ(std::filesystem::path(s.meshFile), dir / "custom.stl");
  std::filesystem::remove_all(dir);
}
