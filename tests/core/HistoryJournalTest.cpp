// The history journal (crash recovery's undo history): every state read back is the surface that was written,
// whatever the slots did in between (freed and reused, changed by commitByDiff); branches, a torn tail and
// damaged records are handled; a damaged file gives InputError naming it, never a crash.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>

#include "MovedCornerEdit.h"
#include "TestMeshes.h"
#include "reamsim/core/HistoryJournal.h"
#include "reamsim/mesh/MeshError.h"

namespace reamsim::test {
namespace {

namespace fs = std::filesystem;

struct TempFile {
  std::string path;
  explicit TempFile(const std::string& name) : path((fs::temp_directory_path() / ("reamsim_journal_" + name)).string()) {
    fs::remove(path);
  }
  ~TempFile() { fs::remove(path); }
};

// A dent at a live vertex: its fan goes, and a vertex pushed along -z takes its place (the old vertex's slot is
// freed and, as applyDelta frees orphans before it allocates, taken again with other coordinates).
BoneState dent(const BoneState& s, std::uint32_t vertex, double depth) {
  MeshDelta d;
  d.addedVertices.push_back(s.vertex(vertex) + Vec3{0.1, 0.05, -depth});
  s.forEachLiveTriangle([&](std::uint32_t slot, const Triangle& t) {
    if (t[0] != vertex && t[1] != vertex && t[2] != vertex) return;
    d.removedTriangles.push_back(slot);
    Triangle moved = t;
    for (std::uint32_t& v : moved)
      if (v == vertex) v = MeshDelta::newVertex(0);
    d.addedTriangles.push_back(moved);
  });
  return s.applyDelta(d);
}

std::uint32_t someLiveVertex(const BoneState& s, std::mt19937& rng) {
  for (;;) {
    const std::uint32_t v = std::uniform_int_distribution<std::uint32_t>(0, std::uint32_t(s.vertexSlotCount() - 1))(rng);
    if (s.isVertexLive(v)) return v;
  }
}

// A history of dents and whole-mesh commits (commitByDiff), with the redo branch of an undo left in it.
BoneHistory sampleHistory(std::mt19937& rng, int steps) {
  TriangleMesh opened = grid(60);
  for (int i = 0; i < 40; ++i) opened.vertices.push_back({-1.0 - i, 0, 0});  // unused: free slots among the live ones
  BoneHistory h(BoneState::fromMesh(opened), "opened");
  for (int i = 0; i < steps; ++i) {
    BoneState next = h.current();
    if (i % 4 == 3) {
      TriangleMesh m = next.toMesh();  // a whole-mesh engine's result: one corner triangle gone
      m.triangles.erase(m.triangles.begin());
      next = BoneState::commitByDiff(next, m);
    } else {
      next = dent(next, someLiveVertex(next, rng), 0.01 * (i + 1));
    }
    h.commit(std::move(next), "cut " + std::to_string(i + 1));
  }
  return h;
}

std::vector<std::uint64_t> revisionsOf(const BoneHistory& h) {
  std::vector<std::uint64_t> out;
  for (const BoneHistory::Entry& e : h.entries()) out.push_back(e.revision);
  return out;
}

void expectSameStates(const BoneHistory& read, const BoneHistory& written) {
  ASSERT_EQ(read.size(), written.size());
  for (std::size_t k = 0; k < read.size(); ++k) {
    EXPECT_TRUE(sameSurface(read.entries()[k].state.toMesh(), written.entries()[k].state.toMesh())) << "state " << k;
    EXPECT_NEAR(read.entries()[k].state.volume(), written.entries()[k].state.volume(), 1e-9 * (1 + std::abs(written.entries()[k].state.volume())));
    EXPECT_EQ(read.entries()[k].label, written.entries()[k].label);
    EXPECT_NE(read.entries()[k].revision, written.entries()[k].revision);  // this process's new revisions
  }
}

std::string contents(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

void overwrite(const std::string& path, const std::string& data) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(data.data(), std::streamsize(data.size()));
}

TEST(HistoryJournal, EveryStateReadsBackAsWrittenWithTheCursor) {
  std::mt19937 rng(7);
  const BoneHistory h = sampleHistory(rng, 12);
  TempFile f("roundtrip");
  HistoryJournalWriter w(f.path);
  // Appended as the bone is cut: a few states at a time, each written once.
  std::vector<BoneHistory::Entry> prefix;
  for (const BoneHistory::Entry& e : h.entries()) {
    prefix.push_back(e);
    if (prefix.size() % 3 == 0) w.append(prefix);
  }
  w.append(h.entries());
  const std::uint64_t bytes = w.bytes();
  w.append(h.entries());  // nothing new
  EXPECT_EQ(w.bytes(), bytes);
  EXPECT_EQ(fs::file_size(f.path), bytes);

  const BoneHistory read = readHistoryJournal(f.path, revisionsOf(h), 5);
  expectSameStates(read, h);
  EXPECT_EQ(read.cursor(), 5u);
  // The restored states share storage as the written ones do: far less than twelve separate copies.
  std::vector<const BoneState*> states;
  for (const BoneHistory::Entry& e : read.entries()) states.push_back(&e.state);
  const StorageStats stats = measureStorage(states);
  EXPECT_LT(stats.uniqueBytes * 4, stats.logicalBytes);
}

// A journal written at once for one history (a save's) names its states in order: journalRevisions hands them to
// readHistoryJournal without the caller keeping them (SavedHistory.h). A file that is not a journal is named.
TEST(HistoryJournal, AJournalWrittenWholeListsItsStatesInOrder) {
  std::mt19937 rng(3);
  const BoneHistory h = sampleHistory(rng, 7);
  TempFile f("whole");
  HistoryJournalWriter(f.path).append(h.entries());
  EXPECT_EQ(journalRevisions(f.path), revisionsOf(h));
  expectSameStates(readHistoryJournal(f.path, journalRevisions(f.path), 6), h);
  TempFile other("not_a_journal");
  std::ofstream(other.path) << "solid x\n";
  EXPECT_THROW(journalRevisions(other.path), InputError);
}

// The edit changedTriangleSlots once missed: a triangle back in its own slot, one corner's slot given to a new
// vertex by the same edit. Read back, the moved corner is where it was written.
TEST(HistoryJournal, ATriangleBackInItsSlotWithAMovedCornerReadsBackMoved) {
  const MovedCornerEdit e = movedCornerEdit();
  BoneHistory h(e.before, "opened");
  h.commit(e.after, "moved");
  TempFile f("moved_corner");
  HistoryJournalWriter(f.path).append(h.entries());
  const BoneHistory read = readHistoryJournal(f.path, revisionsOf(h), 1);
  expectSameStates(read, h);
  EXPECT_EQ(read.current().toMesh().vertices.front().z, 1.0);
}

// The volume of an open surface depends on the point it is taken from: the first state's is written and taken.
TEST(HistoryJournal, AnOpenSurfaceKeepsItsVolumeOrigin) {
  TriangleMesh opened = grid(20);
  for (int i = 0; i < 10; ++i) opened.vertices.push_back({0, 0, -5.0 - i});  // unused, below: they move the centre
  BoneHistory h(BoneState::fromMesh(opened), "opened");
  std::mt19937 rng(5);
  for (int i = 0; i < 4; ++i) h.commit(dent(h.current(), someLiveVertex(h.current(), rng), 0.3), "cut");
  ASSERT_NE(h.current().volume(), 0.0);
  TempFile f("origin");
  HistoryJournalWriter(f.path).append(h.entries());
  const BoneHistory read = readHistoryJournal(f.path, revisionsOf(h), 4);
  for (std::size_t k = 0; k < h.size(); ++k)
    EXPECT_NEAR(read.entries()[k].state.volume(), h.entries()[k].state.volume(), 1e-12 * std::abs(h.entries()[k].state.volume()) + 1e-12);
}

TEST(HistoryJournal, AnAbandonedBranchStaysAndEitherChainReadsBack) {
  std::mt19937 rng(11);
  BoneHistory h = sampleHistory(rng, 6);
  TempFile f("branch");
  HistoryJournalWriter w(f.path);
  w.append(h.entries());
  const BoneHistory first = h;
  h.undo();
  h.undo();
  h.commit(dent(h.current(), someLiveVertex(h.current(), rng), 0.2), "cut after undo");  // drops two states
  w.append(h.entries());
  expectSameStates(readHistoryJournal(f.path, revisionsOf(h), h.cursor()), h);
  expectSameStates(readHistoryJournal(f.path, revisionsOf(first), first.cursor()), first);
  // A writer opened on the same file (another window after a restart of the writer) knows what is there.
  HistoryJournalWriter again(f.path);
  EXPECT_EQ(again.bytes(), w.bytes());
  again.append(h.entries());
  EXPECT_EQ(fs::file_size(f.path), w.bytes());
}

TEST(HistoryJournal, ATornTailIsDroppedAndTheWriterGoesOnFromTheCompleteRecords) {
  std::mt19937 rng(13);
  const BoneHistory h = sampleHistory(rng, 6);
  TempFile f("torn");
  std::vector<BoneHistory::Entry> firstFour(h.entries().begin(), h.entries().begin() + 4);
  std::uint64_t complete = 0;
  {
    HistoryJournalWriter w(f.path);
    w.append(firstFour);
    complete = w.bytes();
    w.append(h.entries());
  }
  fs::resize_file(f.path, complete + 30);  // a crash half way through the fifth record
  std::vector<std::uint64_t> four = revisionsOf(h);
  four.resize(4);
  BoneHistory firstFourHistory(firstFour[0].state, firstFour[0].label);
  for (std::size_t k = 1; k < 4; ++k) firstFourHistory.commit(firstFour[k].state, firstFour[k].label);
  expectSameStates(readHistoryJournal(f.path, four, 3), firstFourHistory);
  try {
    readHistoryJournal(f.path, revisionsOf(h), 0);
    FAIL() << "a state of the torn record was read";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), f.path);
    EXPECT_NE(std::string(e.what()).find("is not in the journal (4 complete records)"), std::string::npos) << e.what();
  }
  HistoryJournalWriter w(f.path);
  EXPECT_EQ(w.bytes(), complete);
  EXPECT_EQ(fs::file_size(f.path), complete);
  w.append(h.entries());
  expectSameStates(readHistoryJournal(f.path, revisionsOf(h), 6), h);
}

TEST(HistoryJournal, AChainInTheWrongOrderOrAnotherFileIsRefusedNamingTheFile) {
  std::mt19937 rng(17);
  const BoneHistory h = sampleHistory(rng, 3);
  TempFile f("order");
  HistoryJournalWriter(f.path).append(h.entries());
  std::vector<std::uint64_t> swapped = revisionsOf(h);
  std::swap(swapped[1], swapped[2]);
  EXPECT_THROW(readHistoryJournal(f.path, swapped, 0), InputError);
  EXPECT_THROW(readHistoryJournal(f.path, revisionsOf(h), 4), InputError);  // cursor past the end
  TempFile other("other");
  overwrite(other.path, "ply\nformat ascii 1.0\n");
  try {
    readHistoryJournal(other.path, revisionsOf(h), 0);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), other.path);
    EXPECT_NE(std::string(e.what()).find("not a ReamSim history journal"), std::string::npos) << e.what();
  }
  EXPECT_THROW(readHistoryJournal(other.path + ".missing", revisionsOf(h), 0), InputError);
  EXPECT_THROW(HistoryJournalWriter{other.path}, InputError);  // not ours: not appended to
  // A folder where the journal goes (it opens as a stream on Linux and fails only when read): named, as InputError.
  const std::string folder = other.path + ".d";
  ASSERT_TRUE(std::filesystem::create_directory(folder));
  for (int reader = 0; reader < 2; ++reader) try {
      if (reader)
        readHistoryJournal(folder, revisionsOf(h), 0);
      else
        HistoryJournalWriter{folder};
      ADD_FAILURE() << "a folder was taken for a journal";
    } catch (const InputError& e) {
      EXPECT_EQ(e.file(), folder);
      EXPECT_NE(std::string(e.what()).find("is a folder"), std::string::npos) << e.what();
    }
  std::filesystem::remove(folder);
}

// Damage inside records, with the checksum made to match (what a checksum cannot catch): every read either
// gives a history or InputError naming the file. Runs under ASan and UBSan in ./test.sh.
TEST(HistoryJournal, DamagedRecordsGiveAnErrorNeverACrash) {
  std::mt19937 rng(19);
  const BoneHistory h = sampleHistory(rng, 5);
  TempFile f("damaged");
  HistoryJournalWriter(f.path).append(h.entries());
  const std::string good = contents(f.path);
  // Record boundaries, to recompute the checksum of the damaged one.
  struct Span {
    std::size_t payload, size;
  };
  std::vector<Span> records;
  for (std::size_t at = 8; at + 20 <= good.size();) {
    std::uint64_t size;
    std::memcpy(&size, good.data() + at + 4, 8);
    records.push_back({at + 12, std::size_t(size)});
    at += 20 + size;
  }
  ASSERT_EQ(records.size(), h.size());
  auto fnv = [](const char* p, std::size_t n) {
    std::uint64_t x = 0xcbf29ce484222325ull;
    for (std::size_t i = 0; i < n; ++i) x = (x ^ static_cast<unsigned char>(p[i])) * 0x100000001b3ull;
    return x;
  };
  int errors = 0, read = 0;
  for (int trial = 0; trial < 600; ++trial) {
    std::string bad = good;
    const Span& r = records[std::uniform_int_distribution<std::size_t>(0, records.size() - 1)(rng)];
    const int flips = 1 + trial % 4;
    for (int i = 0; i < flips; ++i) {
      // Anywhere in the payload, the revision and parent fields included (a damaged one breaks the chain).
      const std::size_t at = r.payload + std::uniform_int_distribution<std::size_t>(0, r.size - 1)(rng);
      bad[at] = char(trial % 3 == 0 ? 0xff : bad[at] ^ (1 << (trial % 8)));
    }
    const std::uint64_t sum = fnv(bad.data() + r.payload, r.size);
    std::memcpy(bad.data() + r.payload + r.size, &sum, 8);
    overwrite(f.path, bad);
    try {
      const BoneHistory got = readHistoryJournal(f.path, revisionsOf(h), h.size() - 1);
      EXPECT_EQ(got.size(), h.size());
      ++read;
    } catch (const InputError& e) {
      EXPECT_EQ(e.file(), f.path);
      ++errors;
    }
  }
  EXPECT_GT(errors, 100);  // most damage is caught; what is not is a coordinate or a label, read as written
  EXPECT_EQ(errors + read, 600);
}

}  // namespace
}  // namespace reamsim::test
