#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <numeric>
#include <random>

#include "MovedCornerEdit.h"
#include "TestMeshes.h"
#include "reamsim/core/BoneState.h"

using namespace reamsim;
using test::sameSurface;

namespace {
// Replaces the top face of test::box(2,2,2) by an inward pyramid of height 0.5 (volume 2/3).
MeshDelta dentTopOfBox(const BoneState& s) {
  MeshDelta d;
  s.forEachLiveTriangle([&](std::uint32_t slot, const Triangle& t) {
    if (s.vertex(t[0]).z == 2 && s.vertex(t[1]).z == 2 && s.vertex(t[2]).z == 2) d.removedTriangles.push_back(slot);
  });
  auto slotAt = [&](Vec3 p) {
    for (std::uint32_t v = 0; v < s.vertexSlotCount(); ++v)
      if (s.isVertexLive(v) && s.vertex(v) == p) return v;
    return BoneState::kBadSlot;
  };
  const std::uint32_t a = slotAt({0, 0, 2}), b = slotAt({2, 0, 2}), c = slotAt({2, 2, 2}), e = slotAt({0, 2, 2});
  d.addedVertices.push_back({1, 1, 1.5});
  const std::uint32_t apex = MeshDelta::newVertex(0);
  d.addedTriangles = {{a, b, apex}, {b, c, apex}, {c, e, apex}, {e, a, apex}};
  return d;
}
}  // namespace

TEST(BoneState, RoundTripKeepsTheSurface) {
  const TriangleMesh m = test::grid(9);
  for (auto ordering : {BoneState::Ordering::Spatial, BoneState::Ordering::Preserve}) {
    const BoneState s = BoneState::fromMesh(m, ordering);
    EXPECT_EQ(s.liveTriangleCount(), m.triangleCount());
    EXPECT_EQ(s.liveVertexCount(), m.vertexCount());
    EXPECT_TRUE(sameSurface(s.toMesh(), m));
  }
  // Preserve really preserves.
  const TriangleMesh same = BoneState::fromMesh(m, BoneState::Ordering::Preserve).toMesh();
  EXPECT_EQ(same.triangles, m.triangles);
}

TEST(BoneState, VolumeAndBounds) {
  const BoneState s = BoneState::fromMesh(test::box(2, 3, 4));
  EXPECT_NEAR(s.volume(), 24, 1e-12);
  EXPECT_EQ(s.bounds().min, (Vec3{0, 0, 0}));
  EXPECT_EQ(s.bounds().max, (Vec3{2, 3, 4}));
  EXPECT_TRUE(BoneState().bounds().empty());
  EXPECT_EQ(BoneState().volume(), 0);
}

TEST(BoneState, UnusedInputVerticesAreFreeSlots) {
  TriangleMesh m = test::box(1, 1, 1);
  m.vertices.push_back({9, 9, 9});
  const BoneState s = BoneState::fromMesh(m, BoneState::Ordering::Preserve);
  EXPECT_EQ(s.liveVertexCount(), 8u);
  EXPECT_FALSE(s.isVertexLive(8));
  EXPECT_EQ(s.bounds().max, (Vec3{1, 1, 1}));
  EXPECT_EQ(s.toMesh().vertexCount(), 8u);
}

TEST(BoneState, FromMeshRejectsBadInput) {
  TriangleMesh m = test::box(1, 1, 1);
  m.triangles.push_back({0, 1, 8});
  EXPECT_THROW(BoneState::fromMesh(m), std::invalid_argument);
  m = test::box(1, 1, 1);
  m.vertices[0].x = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(BoneState::fromMesh(m), std::invalid_argument);
}

TEST(BoneState, ApplyDeltaProducesExactlyTheExpectedMesh) {
  const TriangleMesh m = test::grid(4);
  const BoneState s0 = BoneState::fromMesh(m, BoneState::Ordering::Preserve);
  // Replace quad (1,1) (triangles 10, 11; corners 6, 7, 12, 11) by a fan around a lowered centre.
  MeshDelta d;
  d.removedTriangles = {10, 11};
  d.addedVertices = {{1.5, 1.5, -1}};
  const std::uint32_t c = MeshDelta::newVertex(0);
  d.addedTriangles = {{6, 7, c}, {7, 12, c}, {12, 11, c}, {11, 6, c}};
  DeltaPlacement placed;
  const BoneState s1 = s0.applyDelta(d, &placed);

  TriangleMesh expected = m;
  expected.triangles.erase(expected.triangles.begin() + 10, expected.triangles.begin() + 12);
  expected.vertices.push_back({1.5, 1.5, -1});
  const std::uint32_t e = 25;
  expected.triangles.insert(expected.triangles.end(), {{6, 7, e}, {7, 12, e}, {12, 11, e}, {11, 6, e}});
  EXPECT_TRUE(sameSurface(s1.toMesh(), expected));
  EXPECT_EQ(s1.liveTriangleCount(), 34u);
  EXPECT_EQ(s1.liveVertexCount(), 26u);
  EXPECT_EQ(s1.bounds().min.z, -1);

  // The freed slots 10 and 11 are reused before the array grows.
  ASSERT_EQ(placed.triangleSlots.size(), 4u);
  std::vector<std::uint32_t> slots = placed.triangleSlots;
  std::sort(slots.begin(), slots.end());
  EXPECT_EQ(slots, (std::vector<std::uint32_t>{10, 11, 32, 33}));
  EXPECT_EQ(placed.vertexSlots, (std::vector<std::uint32_t>{25}));
  // The parent is untouched.
  EXPECT_TRUE(sameSurface(s0.toMesh(), m));
  EXPECT_EQ(s0.liveTriangleCount(), 32u);
}

TEST(BoneState, ApplyDeltaUpdatesVolumeIncrementally) {
  const BoneState s0 = BoneState::fromMesh(test::box(2, 2, 2));
  const BoneState s1 = s0.applyDelta(dentTopOfBox(s0));
  EXPECT_NEAR(s1.volume(), 8 - 2.0 / 3.0, 1e-12);
  EXPECT_NEAR(s1.volume(), signedVolume(s1.toMesh()), 1e-12);
  EXPECT_NEAR(s0.volume(), 8, 1e-12);
}

TEST(BoneState, OrphanedVerticesAreFreedAndReused) {
  const BoneState s0 = BoneState::fromMesh(test::grid(2), BoneState::Ordering::Preserve);
  // Remove the six triangles around the centre vertex 4: vertices 4, 0 and 8 lose all their triangles.
  MeshDelta hole;
  s0.forEachLiveTriangle([&](std::uint32_t slot, const Triangle& t) {
    if (std::count(t.begin(), t.end(), 4u)) hole.removedTriangles.push_back(slot);
  });
  ASSERT_EQ(hole.removedTriangles.size(), 6u);
  const BoneState s1 = s0.applyDelta(hole);
  for (std::uint32_t v : {0u, 4u, 8u}) EXPECT_FALSE(s1.isVertexLive(v)) << v;
  EXPECT_EQ(s1.liveVertexCount(), 6u);
  EXPECT_EQ(s1.toMesh().vertexCount(), 6u);
  // A new vertex then lands in one of the freed slots instead of growing the array.
  MeshDelta fill;
  fill.addedVertices = {{1, 1, 5}};
  fill.addedTriangles = {{1, 2, MeshDelta::newVertex(0)}};
  DeltaPlacement placed;
  const BoneState s2 = s1.applyDelta(fill, &placed);
  const std::uint32_t slot = placed.vertexSlots[0];
  EXPECT_TRUE(slot == 0 || slot == 4 || slot == 8) << slot;
  EXPECT_EQ(s2.vertexSlotCount(), 9u);
  EXPECT_EQ(s2.vertex(slot), (Vec3{1, 1, 5}));
  EXPECT_EQ(s1.vertex(slot), s0.vertex(slot));  // older states keep the old coordinates
}

TEST(BoneState, VertexKeptAliveByAnAddedTriangleIsNotFreed) {
  // Remove every triangle using vertex 4 and re-add one that uses it, in one delta.
  const BoneState s0 = BoneState::fromMesh(test::grid(2), BoneState::Ordering::Preserve);
  MeshDelta d;
  s0.forEachLiveTriangle([&](std::uint32_t slot, const Triangle& t) {
    if (std::count(t.begin(), t.end(), 4u)) d.removedTriangles.push_back(slot);
  });
  d.addedVertices = {{7, 7, 7}};  // must not take slot 4
  d.addedTriangles = {{0, 4, MeshDelta::newVertex(0)}};
  DeltaPlacement placed;
  const BoneState s1 = s0.applyDelta(d, &placed);
  EXPECT_TRUE(s1.isVertexLive(4));
  EXPECT_EQ(s1.vertex(4), (Vec3{1, 1, 0}));
  EXPECT_NE(placed.vertexSlots[0], 4u);
}

TEST(BoneState, BoundsShrinkWhenExtremeVerticesGo) {
  const BoneState s0 = BoneState::fromMesh(test::grid(3));
  MeshDelta d;  // drop the last column of quads
  s0.forEachLiveTriangle([&](std::uint32_t slot, const Triangle& t) {
    if (s0.vertex(t[0]).x + s0.vertex(t[1]).x + s0.vertex(t[2]).x > 6) d.removedTriangles.push_back(slot);
  });
  const BoneState s1 = s0.applyDelta(d);
  EXPECT_EQ(s1.bounds().max.x, 2);
  EXPECT_EQ(s0.bounds().max.x, 3);
  // Removing everything leaves an empty state.
  MeshDelta all;
  s1.forEachLiveTriangle([&](std::uint32_t slot, const Triangle&) { all.removedTriangles.push_back(slot); });
  const BoneState s2 = s1.applyDelta(all);
  EXPECT_TRUE(s2.empty());
  EXPECT_EQ(s2.liveVertexCount(), 0u);
  EXPECT_TRUE(s2.bounds().empty());
  EXPECT_NEAR(s2.volume(), 0, 1e-12);
}

TEST(BoneState, InvalidDeltasThrowAndChangeNothing) {
  const BoneState s0 = BoneState::fromMesh(test::grid(2), BoneState::Ordering::Preserve);
  MeshDelta twice;
  twice.removedTriangles = {1, 1};
  EXPECT_THROW(s0.applyDelta(twice), std::invalid_argument);
  MeshDelta outOfRange;
  outOfRange.removedTriangles = {8};
  EXPECT_THROW(s0.applyDelta(outOfRange), std::invalid_argument);
  MeshDelta badNew;
  badNew.addedTriangles = {{0, 1, MeshDelta::newVertex(0)}};
  EXPECT_THROW(s0.applyDelta(badNew), std::invalid_argument);
  MeshDelta deadVertex;
  deadVertex.addedTriangles = {{0, 1, 9}};
  EXPECT_THROW(s0.applyDelta(deadVertex), std::invalid_argument);
  EXPECT_EQ(s0.toMesh().triangles, test::grid(2).triangles);
}

// Random edits checked against a plain slot -> coordinate-triangle model; every old state must
// still read exactly as it did when it was made.
TEST(BoneState, RandomDeltasMatchAReferenceModel) {
  std::mt19937 rng(7);
  const TriangleMesh m = test::grid(12);
  BoneState state = BoneState::fromMesh(m);
  std::map<std::uint32_t, Triangle> model;  // slot -> triangle in vertex slots
  state.forEachLiveTriangle([&](std::uint32_t slot, const Triangle& t) { model[slot] = t; });
  std::vector<std::pair<BoneState, TriangleMesh>> snapshots{{state, state.toMesh()}};

  for (int step = 0; step < 150; ++step) {
    MeshDelta d;
    std::vector<std::uint32_t> live;
    for (const auto& [slot, t] : model) live.push_back(slot);
    std::shuffle(live.begin(), live.end(), rng);
    const std::size_t nRemove = std::min<std::size_t>(live.size(), rng() % 12);
    d.removedTriangles.assign(live.begin(), live.begin() + nRemove);
    for (std::size_t i = 0; i < nRemove; ++i) model.erase(live[i]);
    // Existing vertices still used after removal (safe to reference), plus a few new ones.
    std::vector<std::uint32_t> usable;
    for (const auto& [slot, t] : model) usable.insert(usable.end(), t.begin(), t.end());
    const std::uint32_t nNew = rng() % 4;
    for (std::uint32_t i = 0; i < nNew; ++i) d.addedVertices.push_back({double(rng() % 100), double(step), -1.0 * i});
    const std::size_t nAdd = rng() % 12;
    for (std::size_t i = 0; i < nAdd; ++i) {
      Triangle t;
      for (auto& ref : t) {
        const bool useNew = nNew > 0 && (usable.empty() || rng() % 3 == 0);
        ref = useNew ? MeshDelta::newVertex(rng() % nNew) : usable[rng() % usable.size()];
      }
      d.addedTriangles.push_back(t);
    }
    DeltaPlacement placed;
    const BoneState next = state.applyDelta(d, &placed);
    for (std::size_t i = 0; i < nAdd; ++i) {
      Triangle t = d.addedTriangles[i];
      for (auto& ref : t)
        if (MeshDelta::isNewVertex(ref)) ref = placed.vertexSlots[MeshDelta::newVertexIndex(ref)];
      ASSERT_EQ(model.count(placed.triangleSlots[i]), 0u);
      model[placed.triangleSlots[i]] = t;
    }
    // Expected surface from the model, with coordinates read from the new state.
    TriangleMesh expected;
    expected.vertices.resize(next.vertexSlotCount());
    for (std::uint32_t v = 0; v < next.vertexSlotCount(); ++v) expected.vertices[v] = next.vertex(v);
    for (const auto& [slot, t] : model) expected.triangles.push_back(t);
    const TriangleMesh got = next.toMesh();
    ASSERT_TRUE(sameSurface(got, expected)) << "step " << step;
    ASSERT_EQ(next.liveTriangleCount(), model.size());
    ASSERT_EQ(next.liveVertexCount(), got.vertexCount());
    removeUnusedVertices(expected);
    ASSERT_EQ(got.vertexCount(), expected.vertexCount());
    const Bounds b = computeBounds(got);
    ASSERT_EQ(next.bounds().empty(), b.empty());
    if (!b.empty()) {
      ASSERT_EQ(next.bounds().min, b.min);
      ASSERT_EQ(next.bounds().max, b.max);
    }
    state = next;
    snapshots.push_back({state, got});
  }
  for (const auto& [s, mesh] : snapshots) {
    const TriangleMesh now = s.toMesh();
    EXPECT_EQ(now.vertices, mesh.vertices);
    EXPECT_EQ(now.triangles, mesh.triangles);
  }
}

TEST(BoneState, CommitByDiffKeepsUnchangedTrianglesInTheirSlots) {
  const BoneState s0 = BoneState::fromMesh(test::grid(8));
  // Engine output: s0's mesh with the 2x2 quads [2,4]x[2,4] replaced by a lowered fan, scrambled.
  TriangleMesh next = s0.toMesh();
  std::vector<Triangle> kept;
  for (const Triangle& t : next.triangles) {
    const Vec3 c = (next.vertices[t[0]] + next.vertices[t[1]] + next.vertices[t[2]]) / 3.0;
    if (c.x > 2 && c.x < 4 && c.y > 2 && c.y < 4) continue;  // 4 quads = 8 triangles go
    kept.push_back(t);
  }
  ASSERT_EQ(kept.size(), next.triangles.size() - 8);
  auto at = [&](double x, double y) {
    for (std::uint32_t i = 0; i < next.vertices.size(); ++i)
      if (next.vertices[i] == Vec3{x, y, 0}) return i;
    return 0u;
  };
  next.vertices.push_back({3, 3, -2});
  const std::uint32_t apex = static_cast<std::uint32_t>(next.vertices.size() - 1);
  const std::vector<std::uint32_t> r{at(2, 2), at(3, 2), at(4, 2), at(4, 3), at(4, 4), at(3, 4), at(2, 4), at(2, 3)};
  for (std::size_t i = 0; i < r.size(); ++i) kept.push_back({r[i], r[(i + 1) % r.size()], apex});
  // Scramble: rotate each triangle, shuffle triangles and vertices.
  std::mt19937 rng(3);
  for (Triangle& t : kept) std::rotate(t.begin(), t.begin() + rng() % 3, t.end());
  std::shuffle(kept.begin(), kept.end(), rng);
  std::vector<std::uint32_t> perm(next.vertices.size());
  std::iota(perm.begin(), perm.end(), 0u);
  std::shuffle(perm.begin(), perm.end(), rng);
  TriangleMesh scrambled;
  scrambled.vertices.resize(perm.size());
  for (std::size_t i = 0; i < perm.size(); ++i) scrambled.vertices[perm[i]] = next.vertices[i];
  for (const Triangle& t : kept) scrambled.triangles.push_back({perm[t[0]], perm[t[1]], perm[t[2]]});

  const BoneState s1 = BoneState::commitByDiff(s0, scrambled);
  EXPECT_TRUE(sameSurface(s1.toMesh(), scrambled));
  // Every triangle of s0 outside the edit is still in its slot.
  std::size_t same = 0, changed = 0;
  s0.forEachLiveTriangle([&](std::uint32_t slot, const Triangle& t) {
    (s1.isTriangleLive(slot) && s1.triangle(slot) == t) ? ++same : ++changed;
  });
  EXPECT_EQ(changed, 8u);
  EXPECT_EQ(same, s0.liveTriangleCount() - 8);
  EXPECT_EQ(s1.liveVertexCount(), s0.liveVertexCount());  // centre (3,3) left, apex arrived
}

TEST(BoneState, CommitByDiffOfAnIdenticalMeshSharesEverything) {
  const BoneState s0 = BoneState::fromMesh(test::grid(40));
  const BoneState s1 = BoneState::commitByDiff(s0, s0.toMesh());
  const StorageStats stats = measureStorage({&s0, &s1});
  EXPECT_EQ(stats.uniqueBytes, s0.storageBytes());
  EXPECT_EQ(stats.sharedBytes, s0.storageBytes());
  EXPECT_EQ(stats.logicalBytes, 2 * s0.storageBytes());
}

TEST(BoneState, CommitByDiffKeepsCoincidentVerticesDistinct) {
  // Two triangles touching at one position through two different vertices (a pinch).
  TriangleMesh m;
  m.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 0}, {-1, 0, 0}, {0, -1, 0}};
  m.triangles = {{0, 1, 2}, {3, 4, 5}};
  const BoneState s0 = BoneState::fromMesh(m);
  TriangleMesh next = m;
  next.vertices.push_back({5, 5, 5});
  next.triangles.push_back({1, 6, 2});
  const BoneState s1 = BoneState::commitByDiff(s0, next);
  EXPECT_EQ(s1.liveVertexCount(), 7u);
  EXPECT_TRUE(sameSurface(s1.toMesh(), next));
  EXPECT_THROW(BoneState::commitByDiff(s0, TriangleMesh{{}, {{0, 1, 2}}}), std::invalid_argument);
}

namespace {
SlotChanges changedSlotBySlot(const BoneState& prev, const BoneState& next) {
  SlotChanges out;
  const std::size_t n = std::max(prev.triangleSlotCount(), next.triangleSlotCount());
  for (std::uint32_t s = 0; s < n; ++s) {
    const bool wasLive = prev.isTriangleLive(s), isLive = next.isTriangleLive(s);
    if (wasLive && isLive && prev.triangle(s) == next.triangle(s)) continue;
    if (wasLive) out.removed.push_back(s);
    if (isLive) out.added.push_back(s);
  }
  return out;
}
}  // namespace

// The chunk-skipping diff (what the collider follows cuts with) against a slot-by-slot comparison: states
// several deltas apart in both directions, a commitByDiff state, and unrelated states.
TEST(BoneState, ChangedTriangleSlotsMatchASlotBySlotComparison) {
  std::mt19937 rng(11);
  const TriangleMesh m = test::grid(40);  // 3,200 triangles: 13 chunks
  std::vector<BoneState> states{BoneState::fromMesh(m)};
  for (int step = 0; step < 60; ++step) {
    const BoneState& s = states.back();
    std::vector<std::uint32_t> live;
    s.forEachLiveTriangle([&](std::uint32_t slot, const Triangle&) { live.push_back(slot); });
    std::shuffle(live.begin(), live.end(), rng);
    MeshDelta d;
    // Split a few triangles at their centroid, and re-add one rotated (same face, other slot contents).
    const std::size_t splits = 1 + rng() % 5;
    for (std::size_t i = 0; i < splits; ++i) {
      const Triangle& t = s.triangle(live[i]);
      d.removedTriangles.push_back(live[i]);
      d.addedVertices.push_back((s.vertex(t[0]) + s.vertex(t[1]) + s.vertex(t[2])) * (1.0 / 3));
      const std::uint32_t c = MeshDelta::newVertex(std::uint32_t(d.addedVertices.size() - 1));
      d.addedTriangles.insert(d.addedTriangles.end(), {{t[0], t[1], c}, {t[1], t[2], c}, {t[2], t[0], c}});
    }
    const Triangle& r = s.triangle(live[splits]);
    d.removedTriangles.push_back(live[splits]);
    d.addedTriangles.push_back({r[1], r[2], r[0]});
    states.push_back(s.applyDelta(d));
  }
  auto expectSame = [](const BoneState& a, const BoneState& b, const std::string& what) {
    const SlotChanges fast = BoneState::changedTriangleSlots(a, b), slow = changedSlotBySlot(a, b);
    EXPECT_EQ(fast.removed, slow.removed) << what;
    EXPECT_EQ(fast.added, slow.added) << what;
  };
  for (std::size_t i = 0; i + 1 < states.size(); ++i) {
    const std::string at = "state " + std::to_string(i);
    expectSame(states[i], states[i + 1], at + " -> next");
    expectSame(states[i + 1], states[i], at + " <- next");
    if (i + 7 < states.size()) expectSame(states[i], states[i + 7], at + " -> 7 later");
    EXPECT_TRUE(BoneState::changedTriangleSlots(states[i], states[i]).added.empty());
  }
  const SlotChanges step = BoneState::changedTriangleSlots(states[0], states[1]);
  EXPECT_LE(step.added.size(), 16u);  // a local edit lists only its own slots
  TriangleMesh moved = states.back().toMesh();
  moved.triangles.resize(moved.triangles.size() - 50);
  expectSame(states.back(), BoneState::commitByDiff(states.back(), moved), "commitByDiff");
  expectSame(states.back(), BoneState::fromMesh(m), "unrelated");
  expectSame(BoneState::fromMesh(m), BoneState::fromMesh(test::grid(7)), "smaller, unrelated");
}

// One edit can free a vertex slot, give it to a new vertex and put a triangle with the same corner slots back in
// the slot it left: same slots, a moved corner. It is a changed triangle (the collider and the history journal
// would otherwise keep its old corners).
TEST(BoneState, ATriangleBackInItsSlotWithAMovedCornerIsChanged) {
  const test::MovedCornerEdit e = test::movedCornerEdit();
  const SlotChanges changes = BoneState::changedTriangleSlots(e.before, e.after);
  EXPECT_EQ(changes.removed, std::vector<std::uint32_t>{0u});
  EXPECT_EQ(changes.added, std::vector<std::uint32_t>{0u});
}
