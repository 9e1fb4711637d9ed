// Round trips through every writable format, unit handling, small valid files and API edge cases.
#include <gtest/gtest.h>

#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <sys/xattr.h>
#include <unistd.h>

#include <csignal>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <clocale>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "reamsim/mesh/FileReplace.h"
#include "reamsim/mesh/MeshError.h"
#include "reamsim/mesh/MeshIO.h"

namespace fs = std::filesystem;
using namespace reamsim;

namespace {

// Closed octahedron; `scale` and `offset` let tests choose exactly representable or awkward values.
TriangleMesh octahedron(double scale, Vec3 offset) {
  TriangleMesh m;
  m.vertices = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  for (Vec3& p : m.vertices) p = p * scale + offset;
  m.triangles = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4}, {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
  return m;
}

std::string good(const std::string& name) { return std::string(REAMSIM_IO_DATA_DIR) + "/good/" + name; }

class TempDir : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    std::string name = std::string(info->test_suite_name()) + "_" + info->name();
    for (char& c : name)
      if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
    dir_ = fs::temp_directory_path() / ("reamsim_io_" + std::to_string(::getpid()) + "_" + name);
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  std::string path(const std::string& file) const { return (dir_ / file).string(); }
  std::string writeText(const std::string& file, const std::string& text) const {
    std::ofstream(path(file), std::ios::binary) << text;
    return path(file);
  }
  fs::path dir_;
};

struct RoundTripCase {
  const char* ext;
  bool binary;
  const char* format;  // expected LoadedMesh::format
  bool indexed;        // keeps vertex order and triangles exactly (all but STL)
  bool floatPrecision; // binary STL stores float
};

void PrintTo(const RoundTripCase& c, std::ostream* os) { *os << c.format; }

class io_RoundTrip : public TempDir, public ::testing::WithParamInterface<RoundTripCase> {};

TEST_P(io_RoundTrip, WriteThenReadGivesTheSameMesh) {
  const RoundTripCase c = GetParam();
  // Binary STL stores float32: use exactly representable values there; elsewhere values like 0.1 + 1/3
  // check that %.17g text and double binary output round-trip bit-exactly.
  const TriangleMesh mesh = c.floatPrecision ? octahedron(12.5, {100.25, -40.5, 7.75})
                                             : octahedron(10.0 / 3.0, {0.1 + 1.0 / 3.0, -123.456789012345678, 1e-3});
  const std::string file = path(std::string("mesh") + c.ext);
  WriteOptions wo;
  wo.binary = c.binary;
  writeMesh(mesh, file, wo);

  ReadOptions ro;
  ro.units = Units::Millimetres;
  const LoadedMesh loaded = readMesh(file, ro);
  EXPECT_EQ(loaded.format, c.format);
  EXPECT_EQ(loaded.scaleToMillimetres, 1.0);
  EXPECT_TRUE(loaded.notes.empty()) << loaded.notes.front();
  ASSERT_EQ(loaded.mesh.vertexCount(), mesh.vertexCount());
  ASSERT_EQ(loaded.mesh.triangleCount(), mesh.triangleCount());
  if (c.indexed) {
    for (std::size_t i = 0; i < mesh.vertices.size(); ++i) EXPECT_EQ(loaded.mesh.vertices[i], mesh.vertices[i]) << i;
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) EXPECT_EQ(loaded.mesh.triangles[t], mesh.triangles[t]) << t;
  } else {
    // STL is a triangle soup: compare every triangle's corners by position.
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
      for (int k = 0; k < 3; ++k)
        EXPECT_EQ(loaded.mesh.vertices[loaded.mesh.triangles[t][k]], mesh.vertices[mesh.triangles[t][k]]) << t;
  }
  EXPECT_NEAR(signedVolume(loaded.mesh), signedVolume(mesh), 1e-9 * std::abs(signedVolume(mesh)));
}

// Qt sets the C library's locale from the user's environment (the GUI writes these files too): in a
// decimal-comma locale the text formats must still be written with decimal points, the same bytes as here.
TEST_P(io_RoundTrip, WritesTheSameFileInADecimalCommaLocale) {
  const RoundTripCase c = GetParam();
  const TriangleMesh mesh = octahedron(10.0 / 3.0, {0.1 + 1.0 / 3.0, -123.456789012345678, 1e-3});
  WriteOptions wo;
  wo.binary = c.binary;
  const std::string inC = path(std::string("c") + c.ext), inDe = path(std::string("de") + c.ext);
  writeMesh(mesh, inC, wo);
  const std::string previous = std::setlocale(LC_ALL, nullptr);
  if (!std::setlocale(LC_ALL, "de_DE.UTF-8") && !std::setlocale(LC_ALL, "de_DE.utf8"))
    GTEST_SKIP() << "no de_DE.UTF-8 locale here (scripts/install-deps.sh generates it)";
  char probe[16];
  std::snprintf(probe, sizeof probe, "%.1f", 1.5);
  try {
    writeMesh(mesh, inDe, wo);
  } catch (...) {
    std::setlocale(LC_ALL, previous.c_str());
    throw;
  }
  std::setlocale(LC_ALL, previous.c_str());
  EXPECT_EQ(std::string(probe), "1,5");  // the locale was in effect
  auto bytes = [](const std::string& file) {
    std::ifstream in(file, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
  };
  EXPECT_EQ(bytes(inDe), bytes(inC)) << c.format;
}

INSTANTIATE_TEST_SUITE_P(AllFormats, io_RoundTrip,
                         ::testing::Values(RoundTripCase{".stl", true, "stl-binary", false, true},
                                           RoundTripCase{".stl", false, "stl-ascii", false, false},
                                           RoundTripCase{".ply", true, "ply-binary", true, false},
                                           RoundTripCase{".ply", false, "ply-ascii", true, false},
                                           RoundTripCase{".obj", false, "obj", true, false},
                                           RoundTripCase{".off", false, "off", true, false},
                                           RoundTripCase{".vtp", true, "vtp", true, false}),
                         [](const auto& info) {
                           return std::string(info.param.ext + 1) + (info.param.binary ? "_binary" : "_ascii");
                         });

class io_MeshIO : public TempDir {};

// A write that fails half way (here a file size limit, as a full disk would) must leave the file that was
// there: writing in place truncated it first, and a failed save destroyed the user's earlier copy.
TEST_P(io_RoundTrip, AWriteThatFailsHalfWayLeavesTheFileThatWasThere) {
  const RoundTripCase c = GetParam();
  WriteOptions wo;
  wo.binary = c.binary;
  const std::string file = path(std::string("kept") + c.ext);
  const TriangleMesh small = octahedron(1, {});
  writeMesh(small, file, wo);
  TriangleMesh large;  // ~20,000 triangles: far over the limit below in every format
  for (int k = 0; k < 2500; ++k) {
    const TriangleMesh o = octahedron(1, {3.0 * k, 0, 0});
    const auto base = static_cast<std::uint32_t>(large.vertices.size());
    large.vertices.insert(large.vertices.end(), o.vertices.begin(), o.vertices.end());
    for (Triangle t : o.triangles) large.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
  }
  rlimit before{};
  ASSERT_EQ(getrlimit(RLIMIT_FSIZE, &before), 0);
  rlimit limit = before;
  limit.rlim_cur = 4096;
  auto* const previousHandler = std::signal(SIGXFSZ, SIG_IGN);  // the write fails with EFBIG instead
  ASSERT_EQ(setrlimit(RLIMIT_FSIZE, &limit), 0);
  std::string error;
  try {
    writeMesh(large, file, wo);
  } catch (const InputError& e) {
    error = e.what();
  }
  setrlimit(RLIMIT_FSIZE, &before);
  std::signal(SIGXFSZ, previousHandler);
  EXPECT_EQ(error.rfind(file + ": ", 0), 0u) << error;  // refused, naming the file
  ReadOptions ro;
  ro.units = Units::Millimetres;
  const LoadedMesh kept = readMesh(file, ro);  // the earlier file, whole
  EXPECT_EQ(kept.mesh.triangleCount(), small.triangleCount());
  std::size_t entries = 0;
  for (const auto& e : fs::directory_iterator(dir_)) entries += e.path().filename() != fs::path(file).filename();
  EXPECT_EQ(entries, 0u) << "the half-written file is left behind";
}

// A save can be cancelled (the GUI writes on a worker with a Cancel button): stopped at any of its checks,
// the file that was there stays whole and nothing is left beside it; let run, the progress it reports
// rises from 0 to 1 through every stage.
TEST_P(io_RoundTrip, ACancelledWriteLeavesTheFileThatWasThere) {
  const RoundTripCase c = GetParam();
  const std::string file = path(std::string("kept") + c.ext);
  WriteOptions wo;
  wo.binary = c.binary;
  const TriangleMesh small = octahedron(1, {});
  writeMesh(small, file, wo);
  TriangleMesh large;  // ~200,000 triangles: 4-8 MiB binary, more in ASCII (then more than one piece)
  for (int k = 0; k < 25000; ++k) {
    const TriangleMesh o = octahedron(1, {3.0 * k, 0, 0});
    const auto base = static_cast<std::uint32_t>(large.vertices.size());
    large.vertices.insert(large.vertices.end(), o.vertices.begin(), o.vertices.end());
    for (Triangle t : o.triangles) large.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
  }
  std::vector<std::pair<double, std::string>> heard;
  wo.progress = [&heard](double f, const std::string& stage) {
    heard.emplace_back(f, stage);
    return true;
  };
  writeMesh(large, path(std::string("whole") + c.ext), wo);
  ASSERT_GE(heard.size(), 5u);
  std::vector<std::string> stages;
  for (std::size_t i = 0; i < heard.size(); ++i) {
    if (i > 0) {
      EXPECT_GE(heard[i].first, heard[i - 1].first) << "at " << heard[i].second;
    }
    if (stages.empty() || stages.back() != heard[i].second) stages.push_back(heard[i].second);
  }
  EXPECT_EQ(stages, (std::vector<std::string>{"checking", "encoding", "writing", "flushing"}));
  EXPECT_EQ(heard.front().first, 0.0);
  EXPECT_EQ(heard.back().first, 1.0);
  fs::remove(path(std::string("whole") + c.ext));

  for (std::size_t stopAt = 0; stopAt < heard.size(); ++stopAt) {
    std::size_t calls = 0;
    wo.progress = [&calls, stopAt](double, const std::string&) { return calls++ < stopAt; };
    std::string stage;
    try {
      writeMesh(large, file, wo);
    } catch (const WriteCancelled& e) {
      stage = e.stage();
    }
    EXPECT_EQ(stage, heard[stopAt].second) << "stopped at check " << stopAt;
    const LoadedMesh kept = readMesh(file, ReadOptions{Units::Millimetres});
    EXPECT_EQ(kept.mesh.triangleCount(), small.triangleCount()) << "stopped at check " << stopAt;
    std::size_t entries = 0;
    for (const auto& e : fs::directory_iterator(dir_)) entries += e.path().filename() != fs::path(file).filename();
    EXPECT_EQ(entries, 0u) << "a new file is left behind after a cancel at check " << stopAt;
  }
}

// A read reports "reading" (the bytes) and then "parsing" (how far into them), the fraction never going back,
// and stops where its callback says so with ReadCancelled naming the stage: an import's Cancel does not wait for
// a large text file to be read whole.
TEST_P(io_RoundTrip, ACancelledReadStopsWhereItWasAsked) {
  const RoundTripCase c = GetParam();
  const std::string file = path(std::string("large") + c.ext);
  WriteOptions wo;
  wo.binary = c.binary;
  TriangleMesh large;  // 150,000 vertices and 200,000 triangles: several parse checks in every format
  for (int k = 0; k < 25000; ++k) {
    const TriangleMesh o = octahedron(1, {3.0 * k, 0, 0});
    const auto base = static_cast<std::uint32_t>(large.vertices.size());
    large.vertices.insert(large.vertices.end(), o.vertices.begin(), o.vertices.end());
    for (Triangle t : o.triangles) large.triangles.push_back({t[0] + base, t[1] + base, t[2] + base});
  }
  writeMesh(large, file, wo);
  std::vector<std::pair<double, std::string>> heard;
  ReadOptions ro{Units::Millimetres};
  ro.progress = [&heard](double f, const std::string& stage) {
    heard.emplace_back(f, stage);
    return true;
  };
  EXPECT_EQ(readMesh(file, ro).mesh.triangleCount(), large.triangleCount());
  ASSERT_GE(heard.size(), 4u);
  std::vector<std::string> stages;
  for (std::size_t i = 0; i < heard.size(); ++i) {
    EXPECT_GE(heard[i].first, i ? heard[i - 1].first : 0.0) << "at " << heard[i].second;
    EXPECT_LE(heard[i].first, 1.0);
    if (stages.empty() || stages.back() != heard[i].second) stages.push_back(heard[i].second);
  }
  EXPECT_EQ(stages, (std::vector<std::string>{"reading", "parsing"}));
  EXPECT_EQ(heard.front().first, 0.0);
  EXPECT_GT(heard.back().first, 0.5);  // well into the parse

  const std::size_t firstParse = std::size_t(
      std::find_if(heard.begin(), heard.end(), [](const auto& h) { return h.second == "parsing"; }) - heard.begin());
  for (std::size_t stopAt : {std::size_t{0}, firstParse, heard.size() - 1}) {
    std::size_t calls = 0;
    ro.progress = [&calls, stopAt](double, const std::string&) { return calls++ < stopAt; };
    std::string stage;
    try {
      (void)readMesh(file, ro);
    } catch (const ReadCancelled& e) {
      stage = e.stage();
    }
    EXPECT_EQ(stage, heard[stopAt].second) << "stopped at check " << stopAt;
    EXPECT_EQ(calls, stopAt + 1) << "no check after the one that said stop";
  }
}

// The replaced file's extended attributes (its ACLs are some) stay with the new file: a rename over it would
// otherwise drop a clinic folder's access rules from the saved bone.
TEST_F(io_MeshIO, ReplacingAFileKeepsItsExtendedAttributes) {
  const std::string file = path("bone.ply");
  writeMesh(octahedron(1, {}), file);
  const std::string value = "reviewed by J. Doe";
  if (::setxattr(file.c_str(), "user.reamsim.note", value.data(), value.size(), 0) != 0)
    GTEST_SKIP() << "the file system here keeps no user attributes (" << std::strerror(errno) << ")";
  writeMesh(octahedron(2, {}), file);
  char back[64] = {};
  const ssize_t n = ::getxattr(file.c_str(), "user.reamsim.note", back, sizeof back);
  ASSERT_EQ(n, static_cast<ssize_t>(value.size())) << std::strerror(errno);
  EXPECT_EQ(std::string(back, static_cast<std::size_t>(n)), value);
  EXPECT_EQ(readMesh(file, ReadOptions{Units::Millimetres}).mesh.vertices[0], (Vec3{2, 0, 0}));
}

// A process that died between writing and renaming leaves its new file (".NAME.reamsim-PID-….part") beside the
// target; the next save of that target removes it once it is over an hour old. Those of live processes, young
// ones (perhaps another machine's, on a shared folder), other targets' and other names stay.
TEST_F(io_MeshIO, ASaveRemovesTheNewFileADeadProcessLeftBesideIt) {
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) ::_exit(0);
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);  // `child` names no process now
  const std::string pid = std::to_string(child);
  const std::string dead = ".bone.ply.reamsim-" + pid + "-5-0.part";
  const std::string young = ".bone.ply.reamsim-" + pid + "-6-0.part";  // minutes old: maybe another machine's
  const std::string live = ".bone.ply.reamsim-1-5-0.part";             // init: alive
  const std::string other = ".other.ply.reamsim-" + pid + "-5-0.part";
  const std::string notOurs[] = {".bone.ply.reamsim-x1-5-0.part", ".bone.ply.reamsim-" + pid + "-5.part",
                                 ".bone.ply.reamsim-" + pid + "-5-0a.part"};
  const auto twoHoursAgo = fs::file_time_type::clock::now() - std::chrono::hours(2);
  for (const std::string& name : {dead, young, live, other, notOurs[0], notOurs[1], notOurs[2]}) {
    writeText(name, "half a file");
    if (name != young) fs::last_write_time(path(name), twoHoursAgo);
  }
  writeMesh(octahedron(1, {}), path("bone.ply"));
  EXPECT_FALSE(fs::exists(path(dead)));
  for (const std::string& name : {young, live, other, notOurs[0], notOurs[1], notOurs[2]})
    EXPECT_TRUE(fs::exists(path(name))) << name;
  EXPECT_EQ(readMesh(path("bone.ply"), ReadOptions{Units::Millimetres}).mesh.triangleCount(), 8u);
}

// A file written beside another by other means (a bone's undo history) takes that one's mode and user
// attributes; nothing happens when either is missing.
TEST_F(io_MeshIO, KeepFileAttributesCopiesTheModeAndUserAttributes) {
  const std::string model = writeText("bone.ply", "a"), other = writeText("bone.ply.history.rsj", "b");
  ASSERT_EQ(::chmod(model.c_str(), 0600), 0);
  const bool xattrs = ::setxattr(model.c_str(), "user.reamsim.test", "kept", 4, 0) == 0;  // where the file system has them
  keepFileAttributes(model, other);
  EXPECT_EQ(fs::status(other).permissions() & fs::perms::all, fs::perms::owner_read | fs::perms::owner_write);
  if (xattrs) {
    char value[8] = {};
    EXPECT_EQ(::getxattr(other.c_str(), "user.reamsim.test", value, sizeof value), 4);
    EXPECT_EQ(std::string(value, 4), "kept");
  }
  keepFileAttributes(path("missing"), other);
  keepFileAttributes(model, path("missing too"));
  EXPECT_FALSE(fs::exists(path("missing too")));
}

TEST_F(io_MeshIO, ReplacingAFileKeepsItsPermissionsAndLinks) {
  const std::string file = path("bone.ply"), link = path("link.ply");
  writeMesh(octahedron(1, {}), file);
  ASSERT_EQ(::chmod(file.c_str(), 0640), 0);
  fs::create_symlink(file, link);
  writeMesh(octahedron(2, {}), link);  // through the link
  EXPECT_TRUE(fs::is_symlink(fs::symlink_status(link)));
  EXPECT_EQ(fs::status(file).permissions() & fs::perms::all,
            fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read);
  const LoadedMesh back = readMesh(file, ReadOptions{Units::Millimetres});
  EXPECT_EQ(back.mesh.vertices[0], (Vec3{2, 0, 0}));  // the target was replaced
  // A new file: as created directly (0666 less the umask).
  const mode_t mask = ::umask(022);
  ::umask(mask);
  replaceFile(path("new.txt"), "text");
  EXPECT_EQ(static_cast<unsigned>(fs::status(path("new.txt")).permissions() & fs::perms::all), 0666u & ~mask);
  // A relative link, and one whose target does not exist yet: the link stays, its target is written.
  fs::create_symlink("new.txt", path("relative.txt"));
  replaceFile(path("relative.txt"), "again");
  EXPECT_TRUE(fs::is_symlink(fs::symlink_status(path("relative.txt"))));
  fs::create_symlink("later.txt", path("dangling.txt"));
  replaceFile(path("dangling.txt"), "made");
  EXPECT_TRUE(fs::is_symlink(fs::symlink_status(path("dangling.txt"))));
  auto text = [](const std::string& file) {
    std::ifstream in(file, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
  };
  EXPECT_EQ(text(path("new.txt")), "again");
  EXPECT_EQ(text(path("later.txt")), "made");
  replaceFile("/dev/null", "to a device: written in place");  // no rename over a device
  EXPECT_TRUE(fs::is_character_file("/dev/null"));
  EXPECT_THROW(replaceFile(path("missing/x.txt"), "text"), InputError);
  EXPECT_THROW(replaceFile(dir_.string(), "text"), InputError);  // a folder
}

// A file with other names: every name sees the new content (the file is overwritten in place once the new content
// is safe beside it), the shorter content leaves no tail of the old, and nothing is left beside it.
TEST_F(io_MeshIO, ReplacingAHardLinkedFileWritesEveryName) {
  const std::string file = path("bone.txt"), other = path("other-name.txt");
  replaceFile(file, std::string(100, 'o'));
  fs::create_hard_link(file, other);
  struct stat before {};
  ASSERT_EQ(::stat(file.c_str(), &before), 0);
  replaceFile(other, "new content");
  auto text = [](const std::string& name) {
    std::ifstream in(name, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
  };
  EXPECT_EQ(text(file), "new content");
  EXPECT_EQ(text(other), "new content");
  struct stat after {};
  ASSERT_EQ(::stat(file.c_str(), &after), 0);
  EXPECT_EQ(after.st_ino, before.st_ino);
  EXPECT_EQ(after.st_nlink, 2u);
  int entries = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir_)) ++entries;
  EXPECT_EQ(entries, 2);  // the two names, no new file left
}

// Root saving another user's file gives the new file the old one's owner and group, so the user can still
// write it (a user without the privilege keeps the group only; see ReplacingAFileKeepsItsPermissionsAndLinks).
TEST_F(io_MeshIO, ReplacingAFileAsRootKeepsItsOwner) {
  if (::geteuid() != 0) GTEST_SKIP() << "only root may give a file to another user";
  const std::string file = path("users.txt");
  replaceFile(file, "theirs");
  ASSERT_EQ(::chown(file.c_str(), 4242, 4343), 0);
  replaceFile(file, "written by root");
  struct stat st {};
  ASSERT_EQ(::stat(file.c_str(), &st), 0);
  EXPECT_EQ(st.st_uid, 4242u);
  EXPECT_EQ(st.st_gid, 4343u);
}

// PLY keeps comment lines (the GUI stores the bone's patient frame there); a line break cannot end one early.
TEST_F(io_MeshIO, PlyCommentsRoundTripInBothEncodings) {
  for (bool binary : {true, false}) {
    WriteOptions o;
    o.binary = binary;
    o.comments = {"reamsim patient_frame LPS", "reamsim source CT volume\nhead.nrrd"};
    const std::string file = path(binary ? "c_bin.ply" : "c_ascii.ply");
    writeMesh(octahedron(1, {}), file, o);
    const LoadedMesh m = readMesh(file, ReadOptions{Units::Millimetres});
    EXPECT_EQ(m.mesh.triangles.size(), 8u);
    ASSERT_EQ(m.comments.size(), 3u);
    EXPECT_EQ(m.comments[0], "written by ReamSim");
    EXPECT_EQ(m.comments[1], "reamsim patient_frame LPS");
    EXPECT_EQ(m.comments[2], "reamsim source CT volume head.nrrd");
  }
}

// Every format with room for comments keeps them (the GUI stores the bone's patient frame there): OBJ and OFF
// as '#' lines, VTP as a field-data string array, binary STL in its 80-byte header (what fits).
TEST_F(io_MeshIO, CommentsRoundTripInEveryFormatWithRoomForThem) {
  const std::vector<std::string> written = {"reamsim patient_frame RAS", "reamsim source CT\nhead.nrrd"};
  const std::vector<std::string> expected = {"written by ReamSim", "reamsim patient_frame RAS", "reamsim source CT head.nrrd"};
  for (const char* name : {"c.obj", "c.off", "c.vtp", "c.stl", "c.ply"}) {
    WriteOptions o;
    o.comments = written;
    writeMesh(octahedron(1, {}), path(name), o);
    const LoadedMesh m = readMesh(path(name), ReadOptions{Units::Millimetres});
    EXPECT_EQ(m.mesh.triangles.size(), 8u) << name;
    EXPECT_EQ(m.comments, expected) << name;
  }
  // Without comments of its own a file still says who wrote it.
  for (const char* name : {"n.obj", "n.off", "n.vtp", "n.stl", "n.ascii.stl"}) {
    WriteOptions o;
    o.binary = std::string(name) != "n.ascii.stl";
    writeMesh(octahedron(1, {}), path(name), o);
    EXPECT_EQ(readMesh(path(name), ReadOptions{Units::Millimetres}).comments, std::vector<std::string>{"written by ReamSim"})
        << name;
  }
}

// A binary STL header has 80 bytes: the comments that fit are kept in order, a longer one is left out; ASCII STL
// keeps them all in its solid's name (a tab before each); another program's header or solid name gives none.
TEST_F(io_MeshIO, StlKeepsTheCommentsItsHeaderHasRoomFor) {
  WriteOptions o;
  o.comments = {"reamsim patient_frame LPS", std::string(70, 'x'), "short"};
  writeMesh(octahedron(1, {}), path("h.stl"), o);
  EXPECT_EQ(readMesh(path("h.stl"), ReadOptions{Units::Millimetres}).comments,
            (std::vector<std::string>{"written by ReamSim", "reamsim patient_frame LPS", "short"}));
  o.binary = false;
  o.comments.push_back("a\ttab");
  writeMesh(octahedron(1, {}), path("a.stl"), o);
  EXPECT_EQ(readMesh(path("a.stl"), ReadOptions{Units::Millimetres}).comments,
            (std::vector<std::string>{"written by ReamSim", "reamsim patient_frame LPS", std::string(70, 'x'), "short", "a tab"}));
  {
    std::ofstream f(path("other-ascii.stl"));
    f << "solid part\twith tabs\n facet normal 0 0 1\n  outer loop\n   vertex 0 0 0\n   vertex 1 0 0\n   vertex 0 1 0\n"
         "  endloop\n endfacet\nendsolid part\n";
  }
  EXPECT_TRUE(readMesh(path("other-ascii.stl"), ReadOptions{Units::Millimetres}).comments.empty());
  o.comments.pop_back();
  o.binary = true;
  writeMesh(octahedron(1, {}), path("other.stl"), o);
  {
    std::fstream f(path("other.stl"), std::ios::in | std::ios::out | std::ios::binary);
    f.write("Exported by another program", 27);
  }
  EXPECT_TRUE(readMesh(path("other.stl"), ReadOptions{Units::Millimetres}).comments.empty());
}

// A comment that fills the header to its last byte keeps its line break (the reader drops a line without one),
// so commentsKept, what a writer says it keeps, is what a reader gets back; one byte more and it is left out.
TEST_F(io_MeshIO, StlHeaderKeepsExactlyWhatCommentsKeptSays) {
  // "ReamSim binary STL" (18) + '\n' + comment + '\n' must fit in 80: a comment of 60 bytes fits, 61 does not.
  for (const std::size_t size : {59u, 60u, 61u}) {
    WriteOptions o;
    o.comments = {std::string(size, 'c')};
    writeMesh(octahedron(1, {}), path("fill.stl"), o);
    std::vector<std::string> read = readMesh(path("fill.stl"), ReadOptions{Units::Millimetres}).comments;
    read.erase(read.begin());  // "written by ReamSim"
    EXPECT_EQ(read, commentsKept(path("fill.stl"), o)) << size;
    EXPECT_EQ(read.size(), size <= 60 ? 1u : 0u) << size;
  }
  WriteOptions ply;
  ply.comments = {std::string(500, 'p'), "b"};
  EXPECT_EQ(commentsKept(path("any.ply"), ply), ply.comments);  // other formats keep them all
}

// Comments of files written elsewhere: whole-line '#' comments of OBJ and OFF (not those after data on a
// line), and a VTP's comment array written by VTK in ASCII (a string's bytes as numbers, each string ended by 0).
TEST_F(io_MeshIO, CommentsOfFilesWrittenElsewhere) {
  const LoadedMesh off = readMesh(good("cube_quads_comments.off"));
  EXPECT_EQ(off.comments, (std::vector<std::string>{"10 mm cube made of quads; counts on the keyword line", "vertices", "faces"}));
  EXPECT_EQ(readMesh(good("cube_mixed_faces.obj")).comments.at(0),
            "10 mm cube using every OBJ face form, negative indices, quads and ignored statements");
  std::string bytes;
  for (const std::string& c : {std::string("reamsim patient_frame LPS"), std::string("ab")}) {
    for (char ch : c) bytes += std::to_string(int(ch)) + ' ';
    bytes += "0 ";
  }
  {
    std::ofstream f(path("ascii.vtp"));
    f << "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
         "<PolyData>\n<FieldData>\n<Array type=\"String\" Name=\"ReamSimComments\" NumberOfTuples=\"2\" format=\"ascii\">\n"
      << bytes
      << "\n</Array>\n</FieldData>\n<Piece NumberOfPoints=\"3\" NumberOfPolys=\"1\">\n<Points>\n"
         "<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">0 0 0 10 0 0 0 10 0</DataArray>\n"
         "</Points>\n<Polys>\n<DataArray type=\"Int32\" Name=\"connectivity\" format=\"ascii\">0 1 2</DataArray>\n"
         "<DataArray type=\"Int32\" Name=\"offsets\" format=\"ascii\">3</DataArray>\n</Polys>\n</Piece>\n</PolyData>\n"
         "</VTKFile>\n";
  }
  EXPECT_EQ(readMesh(path("ascii.vtp"), ReadOptions{Units::Millimetres}).comments,
            (std::vector<std::string>{"reamsim patient_frame LPS", "ab"}));
}

TEST_F(io_MeshIO, UppercaseExtensionIsAccepted) {
  const std::string file = path("MESH.STL");
  writeMesh(octahedron(10, {}), file);
  EXPECT_EQ(readMesh(file).format, "stl-binary");
}

TEST_F(io_MeshIO, BinaryStlWhoseHeaderStartsWithSolidIsReadAsBinary) {
  const std::string file = path("solid.stl");
  writeMesh(octahedron(10, {}), file);
  {
    std::fstream f(file, std::ios::in | std::ios::out | std::ios::binary);
    f.write("solid trap", 10);
  }
  const LoadedMesh m = readMesh(file);
  EXPECT_EQ(m.format, "stl-binary");
  EXPECT_EQ(m.mesh.triangleCount(), 8u);
}

TEST_F(io_MeshIO, UnitsAutoScalesMetreSizedData) {
  const std::string file = path("small.ply");
  writeMesh(octahedron(0.05, {0.1, 0.2, 0.3}), file);  // diagonal 0.173: metres
  const LoadedMesh m = readMesh(file);
  EXPECT_EQ(m.scaleToMillimetres, 1000.0);
  ASSERT_EQ(m.notes.size(), 1u);
  EXPECT_NE(m.notes[0].find("coordinates look like metres (bounding box diagonal 0.1732 m)"), std::string::npos)
      << m.notes[0];
  EXPECT_NE(m.notes[0].find("pass --units mm"), std::string::npos);
  EXPECT_DOUBLE_EQ(m.mesh.vertices[0].x, 150.0);
  EXPECT_NEAR(computeBounds(m.mesh).diagonal(), 173.21, 0.01);
}

TEST_F(io_MeshIO, UnitsAutoKeepsMillimetreData) {
  const std::string file = path("big.ply");
  writeMesh(octahedron(20, {}), file);
  const LoadedMesh m = readMesh(file);
  EXPECT_EQ(m.scaleToMillimetres, 1.0);
  EXPECT_TRUE(m.notes.empty());
  EXPECT_EQ(m.mesh.vertices[0].x, 20.0);
}

TEST_F(io_MeshIO, UnitsAutoThresholdIsTwoFileUnits) {
  const std::string below = path("below.off"), above = path("above.off");
  writeMesh(octahedron(0.57, {}), below);  // diagonal 1.975
  writeMesh(octahedron(0.58, {}), above);  // diagonal 2.009
  EXPECT_EQ(readMesh(below).scaleToMillimetres, 1000.0);
  EXPECT_EQ(readMesh(above).scaleToMillimetres, 1.0);
}

TEST_F(io_MeshIO, UnitsMetresAlwaysScales) {
  const std::string file = path("m.obj");
  writeMesh(octahedron(20, {}), file);
  ReadOptions ro;
  ro.units = Units::Metres;
  const LoadedMesh m = readMesh(file, ro);
  EXPECT_EQ(m.scaleToMillimetres, 1000.0);
  EXPECT_EQ(m.mesh.vertices[0].x, 20000.0);
  EXPECT_TRUE(m.notes.empty());
}

TEST_F(io_MeshIO, UnitsMillimetresNeverScales) {
  const std::string file = path("mm.obj");
  writeMesh(octahedron(0.05, {}), file);
  ReadOptions ro;
  ro.units = Units::Millimetres;
  const LoadedMesh m = readMesh(file, ro);
  EXPECT_EQ(m.scaleToMillimetres, 1.0);
  EXPECT_EQ(m.mesh.vertices[0].x, 0.05);
  EXPECT_TRUE(m.notes.empty());
}

TEST(io_ParseUnits, AcceptsKnownSpellings) {
  EXPECT_EQ(parseUnits("auto"), Units::Auto);
  EXPECT_EQ(parseUnits("mm"), Units::Millimetres);
  EXPECT_EQ(parseUnits("MM"), Units::Millimetres);
  EXPECT_EQ(parseUnits("millimetres"), Units::Millimetres);
  EXPECT_EQ(parseUnits("m"), Units::Metres);
  EXPECT_EQ(parseUnits("meters"), Units::Metres);
  EXPECT_THROW(parseUnits("cm"), std::invalid_argument);
  EXPECT_THROW(parseUnits(""), std::invalid_argument);
}

TEST(io_SupportedExtensions, ListsEveryFormat) {
  EXPECT_EQ(supportedMeshExtensions(), (std::vector<std::string>{".stl", ".obj", ".ply", ".off", ".vtp"}));
}

TEST_F(io_MeshIO, MissingFileIsAnInputError) {
  const std::string file = path("does_not_exist.stl");
  try {
    readMesh(file);
    FAIL() << "no exception";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), file);
    EXPECT_NE(std::string(e.what()).find("file not found"), std::string::npos) << e.what();
  }
}

TEST_F(io_MeshIO, DirectoryIsAnInputError) {
  fs::create_directories(path("dir.obj"));
  EXPECT_THROW(readMesh(path("dir.obj")), InputError);
}

TEST_F(io_MeshIO, WritingIntoAMissingDirectoryNamesTheFile) {
  for (const char* ext : {".stl", ".ply", ".obj", ".off", ".vtp"}) {
    const std::string file = path(std::string("missing_dir/out") + ext);
    try {
      writeMesh(octahedron(10, {}), file);
      ADD_FAILURE() << "no exception for " << ext;
    } catch (const InputError& e) {
      EXPECT_EQ(e.file(), file);
      EXPECT_NE(std::string(e.what()).find(file), std::string::npos) << e.what();
    }
  }
}

TEST_F(io_MeshIO, WritingAnUnknownExtensionFails) {
  EXPECT_THROW(writeMesh(octahedron(10, {}), path("out.xyz")), InputError);
}

TEST_F(io_MeshIO, WritingAMeshWithBadIndicesFails) {
  TriangleMesh m = octahedron(10, {});
  m.triangles.push_back({0, 1, 99});
  EXPECT_THROW(writeMesh(m, path("bad.obj")), InputError);
}

// ---- small valid files with the less common syntax -----------------------------------------------------


TEST(io_GoodFiles, ObjAllFaceFormsNegativeIndicesAndQuads) {
  const LoadedMesh m = readMesh(good("cube_mixed_faces.obj"));
  EXPECT_EQ(m.format, "obj");
  EXPECT_EQ(m.mesh.vertexCount(), 8u);
  EXPECT_EQ(m.mesh.triangleCount(), 12u);
  ASSERT_FALSE(m.notes.empty());
  EXPECT_EQ(m.notes[0], "4 polygons with >3 vertices were triangulated");
  EXPECT_NEAR(signedVolume(m.mesh), 1000.0, 1e-9);
}

TEST(io_GoodFiles, OffWithCommentsAndCountsOnTheKeywordLine) {
  const LoadedMesh m = readMesh(good("cube_quads_comments.off"));
  EXPECT_EQ(m.format, "off");
  EXPECT_EQ(m.mesh.vertexCount(), 8u);
  EXPECT_EQ(m.mesh.triangleCount(), 12u);
  EXPECT_EQ(m.notes.at(0), "6 polygons with >3 vertices were triangulated");
  EXPECT_NEAR(signedVolume(m.mesh), 1000.0, 1e-9);
}

TEST(io_GoodFiles, CoffWithVertexAndFaceColours) {
  const LoadedMesh m = readMesh(good("tetra_colours.coff.off"));
  EXPECT_EQ(m.mesh.vertexCount(), 4u);
  EXPECT_EQ(m.mesh.triangleCount(), 4u);
}

TEST(io_GoodFiles, NoffWithNormals) {
  const LoadedMesh m = readMesh(good("tetra_normals.noff.off"));
  EXPECT_EQ(m.mesh.triangleCount(), 4u);
}

TEST(io_GoodFiles, AsciiStlWithNamesCrlfAndExponents) {
  const LoadedMesh m = readMesh(good("tetra_named_crlf.stl"));
  EXPECT_EQ(m.format, "stl-ascii");
  EXPECT_EQ(m.mesh.vertexCount(), 4u);
  EXPECT_EQ(m.mesh.triangleCount(), 4u);
}

TEST(io_GoodFiles, AsciiPlyWithExtraElementsAndProperties) {
  const LoadedMesh m = readMesh(good("pyramid_extra_props_ascii.ply"));
  EXPECT_EQ(m.format, "ply-ascii");
  EXPECT_EQ(m.mesh.vertexCount(), 5u);
  EXPECT_EQ(m.mesh.triangleCount(), 6u);  // one quad base and four triangles
  EXPECT_EQ(m.mesh.vertices[4], (Vec3{5, 5, 10}));
  EXPECT_EQ(m.notes.at(0), "1 polygons with >3 vertices were triangulated");
  EXPECT_NEAR(signedVolume(m.mesh), 1000.0 / 3.0, 1e-9);
}

TEST(io_GoodFiles, BigEndianPlyWithOddTypes) {
  const LoadedMesh m = readMesh(good("tetra_be_types.ply"));
  EXPECT_EQ(m.format, "ply-binary");
  EXPECT_EQ(m.mesh.vertexCount(), 4u);
  EXPECT_EQ(m.mesh.triangleCount(), 4u);
  EXPECT_EQ(m.mesh.vertices[1], (Vec3{10, 0, 0}));
  EXPECT_EQ(m.mesh.triangles[3], (Triangle{1, 2, 3}));
}

TEST(io_GoodFiles, LittleEndianPlyWithVertexIndexAndSkippedLists) {
  const LoadedMesh m = readMesh(good("tetra_le_vertex_index.ply"));
  EXPECT_EQ(m.mesh.vertexCount(), 4u);
  EXPECT_EQ(m.mesh.triangleCount(), 4u);
  EXPECT_EQ(m.mesh.vertices[2], (Vec3{0, 10, 0}));
}

TEST(io_GoodFiles, VtpWithTriangleStripAndQuad) {
  const LoadedMesh m = readMesh(good("strip_and_quad.vtp"));
  EXPECT_EQ(m.format, "vtp");
  EXPECT_EQ(m.mesh.vertexCount(), 6u);
  EXPECT_EQ(m.mesh.triangleCount(), 6u);  // strip of 6 points -> 4 triangles, quad -> 2
  bool stripNote = false, quadNote = false;
  for (const std::string& n : m.notes) {
    stripNote |= n == "1 triangle strips were converted to 4 triangles";
    quadNote |= n == "1 polygons with >3 vertices were triangulated";
  }
  EXPECT_TRUE(stripNote);
  EXPECT_TRUE(quadNote);
  // Strip winding alternates so all strip triangles face +z like the first one.
  for (std::size_t t = 0; t < 4; ++t) {
    const auto& v = m.mesh.vertices;
    const Triangle& tri = m.mesh.triangles[2 + t];
    EXPECT_GT(cross(v[tri[1]] - v[tri[0]], v[tri[2]] - v[tri[0]]).z, 0) << t;
  }
}

}  // namespace
