// The malformed-file corpus: every file listed in tests/data/malformed/EXPECTED.tsv must make readMesh
// throw InputError naming the file, containing the expected text and, for text formats, the line.
#include <gtest/gtest.h>

#include <cctype>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "reamsim/mesh/MeshError.h"
#include "reamsim/mesh/MeshIO.h"

namespace fs = std::filesystem;
using namespace reamsim;

namespace {

const std::string kCorpus = std::string(REAMSIM_IO_DATA_DIR) + "/malformed";

struct CorpusCase {
  std::string file;
  std::string expected;  // substring of the error message
  long line = -1;        // expected InputError::line(); -1 = not checked
};

// EXPECTED.tsv: file <TAB> expected substring [<TAB> line]; '#' starts a comment line.
std::vector<CorpusCase> loadCorpus() {
  std::vector<CorpusCase> cases;
  std::ifstream in(kCorpus + "/EXPECTED.tsv");
  std::string row;
  while (std::getline(in, row)) {
    if (row.empty() || row[0] == '#') continue;
    std::vector<std::string> cols;
    std::stringstream ss(row);
    std::string col;
    while (std::getline(ss, col, '\t')) cols.push_back(col);
    CorpusCase c;
    c.file = cols.at(0);
    c.expected = cols.size() > 1 ? cols[1] : "";
    if (cols.size() > 2 && !cols[2].empty()) c.line = std::stol(cols[2]);
    cases.push_back(c);
  }
  return cases;
}

void PrintTo(const CorpusCase& c, std::ostream* os) { *os << c.file; }

class io_MalformedCorpus : public ::testing::TestWithParam<CorpusCase> {};

TEST_P(io_MalformedCorpus, ReadThrowsAClearInputError) {
  const CorpusCase& c = GetParam();
  const std::string path = kCorpus + "/" + c.file;
  ASSERT_TRUE(fs::exists(path)) << path;
  EXPECT_LT(fs::file_size(path), 10u * 1024u) << "corpus files must stay small";
  try {
    const LoadedMesh m = readMesh(path);
    FAIL() << c.file << " was accepted (" << m.mesh.triangleCount() << " triangles)";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_EQ(e.file(), path);
    EXPECT_NE(what.find(c.file), std::string::npos) << what;
    EXPECT_NE(what.find(c.expected), std::string::npos) << "expected '" << c.expected << "' in: " << what;
    if (c.line >= 0) {
      EXPECT_EQ(e.line(), c.line) << what;
    }
  } catch (const std::exception& e) {
    FAIL() << c.file << ": wrong exception type: " << e.what();
  }
}

INSTANTIATE_TEST_SUITE_P(Files, io_MalformedCorpus, ::testing::ValuesIn(loadCorpus()), [](const auto& info) {
  std::string name = info.param.file;
  for (char& ch : name)
    if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
  return name;
});

TEST(io_MalformedCorpusIndex, CoversEveryFileAndEveryFormat) {
  const std::vector<CorpusCase> cases = loadCorpus();
  EXPECT_GE(cases.size(), 18u);
  std::set<std::string> listed;
  for (const CorpusCase& c : cases) listed.insert(c.file);
  for (const auto& entry : fs::directory_iterator(kCorpus)) {
    const std::string name = entry.path().filename().string();
    if (name == "EXPECTED.tsv" || name == "README.md") continue;
    EXPECT_TRUE(listed.count(name)) << name << " is not listed in EXPECTED.tsv";
  }
  for (const char* prefix : {"stl_ascii_", "stl_binary_", "obj_", "ply_ascii_", "ply_binary_", "off_", "vtp_"}) {
    bool found = false;
    for (const std::string& f : listed) found |= f.rfind(prefix, 0) == 0;
    EXPECT_TRUE(found) << "no corpus file for " << prefix;
  }
}

// Metres scaled to millimetres must stay finite (fuzzing, session 26: 1e306 m became inf mm, unchecked).
TEST(io_Units, MetresThatOverflowWhenScaledAreAnInputError) {
  const fs::path file = fs::temp_directory_path() / ("reamsim_units_" + std::to_string(::getpid()) + ".obj");
  std::ofstream(file) << "v 0 0 0\nv 1e306 0 0\nv 0 1 0\nf 1 2 3\n";
  EXPECT_NO_THROW(readMesh(file.string(), ReadOptions{Units::Millimetres}));
  try {
    (void)readMesh(file.string(), ReadOptions{Units::Metres});
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("vertex 1 overflows when its metres are scaled"), std::string::npos) << e.what();
  }
  fs::remove(file);
}

}  // namespace
