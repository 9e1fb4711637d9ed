// The point of BoneState: keeping every committed cut must cost about the size of the cuts.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <unordered_map>

#include "TestMeshes.h"
#include "reamsim/core/BoneHistory.h"

using namespace reamsim;

namespace {

// A local "reaming" edit: the triangles whose centroid is within `radius` of (cx, cy) are replaced by
// the same patch with its interior vertices pushed down by `depth` (new vertices, same topology).
MeshDelta dimple(const BoneState& s, double cx, double cy, double radius, double depth) {
  MeshDelta d;
  std::unordered_map<std::uint32_t, std::uint32_t> usesInPatch;
  s.forEachLiveTriangle([&](std::uint32_t slot, const Triangle& t) {
    const Vec3 c = (s.vertex(t[0]) + s.vertex(t[1]) + s.vertex(t[2])) / 3.0;
    if (std::hypot(c.x - cx, c.y - cy) > radius) return;
    d.removedTriangles.push_back(slot);
    for (std::uint32_t v : t) ++usesInPatch[v];
  });
  std::unordered_map<std::uint32_t, std::uint32_t> moved;  // interior slot -> new vertex ref
  for (const auto& [v, uses] : usesInPatch) {
    if (uses != s.vertexUseCount(v)) continue;  // on the patch boundary: shared with kept triangles
    moved[v] = MeshDelta::newVertex(static_cast<std::uint32_t>(d.addedVertices.size()));
    d.addedVertices.push_back(s.vertex(v) - Vec3{0, 0, depth});
  }
  for (std::uint32_t slot : d.removedTriangles) {
    Triangle t = s.triangle(slot);
    for (auto& v : t)
      if (auto it = moved.find(v); it != moved.end()) v = it->second;
    d.addedTriangles.push_back(t);
  }
  return d;
}

}  // namespace

TEST(BoneMemory, FiftyLocalCutsCostLessThanThreeFullCopies) {
  const TriangleMesh mesh = test::grid(224);  // 100,352 triangles, 50,625 vertices
  ASSERT_GE(mesh.triangleCount(), 100000u);
  BoneHistory history(BoneState::fromMesh(mesh), "import");
  const std::size_t single = history.current().storageBytes();

  std::mt19937 rng(11);
  std::uniform_real_distribution<double> pos(15, 209);
  std::size_t editedTriangles = 0;
  for (int cut = 0; cut < 50; ++cut) {
    const MeshDelta d = dimple(history.current(), pos(rng), pos(rng), 8.9, 0.1 * (cut + 1));
    editedTriangles += d.removedTriangles.size();
    history.commit(history.current().applyDelta(d), "cut " + std::to_string(cut + 1));
  }
  EXPECT_NEAR(editedTriangles / 50.0, 500, 60);  // ~500 triangles per cut, as intended

  const StorageStats stats = history.storageStats();
  std::cout << "[ memory ] one copy " << single / 1024 << " KiB; 51 states hold " << stats.uniqueBytes / 1024
            << " KiB unique (" << double(stats.uniqueBytes) / single << "x), " << stats.sharedBytes / 1024
            << " KiB shared, " << stats.logicalBytes / 1024 << " KiB as independent copies\n";
  EXPECT_LT(stats.uniqueBytes, 3 * single);
  EXPECT_GT(stats.logicalBytes, 50 * single);  // what 51 full copies would have cost

  // Undoing all cuts gives back the imported mesh exactly.
  const TriangleMesh imported = history.entries().front().state.toMesh();
  while (history.undo()) {}
  const TriangleMesh back = history.current().toMesh();
  EXPECT_EQ(back.vertices, imported.vertices);
  EXPECT_EQ(back.triangles, imported.triangles);
  EXPECT_TRUE(test::sameSurface(back, mesh));
}

TEST(BoneMemory, CommitByDiffOfALocalCutSharesTheRest) {
  BoneHistory history(BoneState::fromMesh(test::grid(224)), "import");
  const std::size_t single = history.current().storageBytes();
  // Engine returns the whole mesh: apply the cut to a plain copy, then diff it back in.
  const BoneState cut = history.current().applyDelta(dimple(history.current(), 100, 100, 8.9, 1));
  const TriangleMesh engineOutput = cut.toMesh();
  history.commit(BoneState::commitByDiff(history.current(), engineOutput), "cut");
  EXPECT_TRUE(test::sameSurface(history.current().toMesh(), engineOutput));
  const std::size_t growth = history.uniqueBytes() - single;
  std::cout << "[ memory ] commitByDiff of a ~500-triangle cut added " << growth / 1024 << " KiB to "
            << single / 1024 << " KiB\n";
  EXPECT_LT(growth, single / 10);
}
