// The local engine's broad phase (internal headers of modules/csg/src): the tool's bound never drops a bone
// face that meets the tool, the grid's block-filtered query never drops a face in a block it keeps, and the
// tool's packed grid finds exactly the boxes a query or a ray meets.
#include <gtest/gtest.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Side_of_triangle_mesh.h>
#include <CGAL/Surface_mesh.h>

#include <algorithm>
#include <limits>
#include <optional>
#include <random>

#include "LocalTestMeshes.h"
#include "PackedTriangleGrid.h"
#include "ToolBound.h"
#include "TriangleGrid.h"

namespace reamsim {
namespace {
using IK = CGAL::Exact_predicates_inexact_constructions_kernel;
using csg::Box3;
using test::capSpec;
using test::flatSpec;
using test::toolAt;

IK::Point_3 ip(const Vec3& v) { return {v.x, v.y, v.z}; }

// Exactly (predicates on the doubles): the triangle meets the closed solid `tool`.
class ExactTool {
 public:
  explicit ExactTool(const TriangleMesh& tool) : tool_(tool) {
    std::vector<CGAL::Surface_mesh<IK::Point_3>::Vertex_index> v;
    for (const Vec3& p : tool.vertices) v.push_back(mesh_.add_vertex(ip(p)));
    for (const Triangle& t : tool.triangles) mesh_.add_face(v[t[0]], v[t[1]], v[t[2]]);
    side_.emplace(mesh_);
  }
  bool meets(const Vec3& a, const Vec3& b, const Vec3& c) const {
    for (const Vec3& p : {a, b, c})
      if ((*side_)(ip(p)) != CGAL::ON_UNBOUNDED_SIDE) return true;
    const IK::Triangle_3 t(ip(a), ip(b), ip(c));
    for (const Triangle& f : tool_.triangles)
      if (CGAL::do_intersect(t, IK::Triangle_3(ip(tool_.vertices[f[0]]), ip(tool_.vertices[f[1]]),
                                               ip(tool_.vertices[f[2]]))))
        return true;
    return false;
  }

 private:
  const TriangleMesh& tool_;
  CGAL::Surface_mesh<IK::Point_3> mesh_;
  std::optional<CGAL::Side_of_triangle_mesh<CGAL::Surface_mesh<IK::Point_3>, IK>> side_;
};

// Random small triangles around tilted reamers (a spherical cap and a flat one): every triangle the tool
// meets is kept, including triangles touching its surface from outside; and most of those that lie in
// the tool's box but away from the tool are dropped (the bound is worth having).
TEST(ToolBound, NeverDropsAFaceThatMeetsTheTool) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(-1, 1), size(0.02, 2.0);
  std::size_t meeting = 0, apart = 0, droppedApart = 0;
  for (const ReamerSpec& spec : {capSpec(36, 30), flatSpec(24)}) {
    for (int poseIndex = 0; poseIndex < 4; ++poseIndex) {
      const Vec3 axis = normalized(Vec3{unit(rng), unit(rng), unit(rng)});
      const TriangleMesh tool = toolAt(spec, Pose{Vec3{10 * unit(rng), 10 * unit(rng), 10 * unit(rng)}, axis, 0});
      const std::vector<std::uint32_t> faces = csg::ToolBound::spreadFaces(tool, 32);
      ASSERT_GE(faces.size(), 3u);
      csg::ToolBound bound;
      bound.fit(tool, faces, 1e-6);
      const ExactTool exact(tool);
      const Bounds box = computeBounds(tool);
      for (int i = 0; i < 1500; ++i) {
        const Vec3 c{box.min.x + (box.max.x - box.min.x) * (0.5 + 0.6 * unit(rng)),
                     box.min.y + (box.max.y - box.min.y) * (0.5 + 0.6 * unit(rng)),
                     box.min.z + (box.max.z - box.min.z) * (0.5 + 0.6 * unit(rng))};
        Vec3 a = c + Vec3{unit(rng), unit(rng), unit(rng)} * size(rng);
        const Vec3 b = c + Vec3{unit(rng), unit(rng), unit(rng)} * size(rng);
        const Vec3 d = c + Vec3{unit(rng), unit(rng), unit(rng)} * size(rng);
        if (i % 3 == 0) a = tool.vertices[std::size_t(i) % tool.vertices.size()];  // touching the tool
        const bool meets = exact.meets(a, b, d);
        const bool kept = bound.mayMeet(a, b, d);
        if (meets) {
          ++meeting;
          EXPECT_TRUE(kept) << "a face meeting the tool was dropped (pose " << poseIndex << ", face " << i << ")";
        } else {
          ++apart;
          droppedApart += !kept;
        }
        // The box test agrees: a triangle's own box is kept whenever the triangle is.
        Box3 tb = Box3::empty();
        for (const Vec3& p : {a, b, d}) tb.add(p);
        if (kept) {
          EXPECT_TRUE(bound.mayMeet(tb));
        }
      }
    }
  }
  std::printf("%zu faces meet the tools, %zu do not; the bound drops %zu of those (%.0f%%)\n", meeting, apart,
              droppedApart, 100.0 * double(droppedApart) / double(apart));
  EXPECT_GT(meeting, 1000u);
  EXPECT_GT(droppedApart, apart / 3);
}

// The grid against brute force: plain and shared (const, stamp-free) queries return exactly the boxes that
// overlap, each once; block-filtered queries
// return every box that overlaps the query and meets the region the filter keeps (here a half-space), and
// nothing that does not overlap the query. Boxes beyond the domain (filed in border cells) are found too.
TEST(TriangleGrid, QueriesAgreeWithBruteForce) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> unit(0, 1);
  csg::TriangleGrid grid;
  const Bounds domain{{0, 0, 0}, {40, 30, 20}};
  grid.init(domain, 20000, 2.0, 20000 * 0.05);
  std::vector<Box3> boxes;
  auto randomBox = [&](double extent, double reach) {
    Box3 b;
    for (int a = 0; a < 3; ++a) {
      const double lo = -reach + (domain.max[a] + 2 * reach) * unit(rng);
      b.lo[a] = lo;
      b.hi[a] = lo + extent * unit(rng);
    }
    return b;
  };
  for (std::uint32_t s = 0; s < 20000; ++s) {
    boxes.push_back(randomBox(0.6, 2));
    grid.insert(s, boxes.back());
  }
  for (std::uint32_t s = 0; s < 20000; s += 3) grid.remove(s);  // removed slots must not come back
  const Vec3 n = normalized(Vec3{1, 2, -1});
  const double h = 18;
  auto meetsHalfSpace = [&](const Box3& b) {
    double nearest = 0;
    for (int a = 0; a < 3; ++a) nearest += n[a] * (n[a] > 0 ? b.lo[a] : b.hi[a]);
    return nearest <= h;
  };
  std::vector<std::uint32_t> out;
  for (int q = 0; q < 400; ++q) {
    // Large, middling, small and point queries (a point's query lies in one cell: the clean-up's vertex stars).
    const Box3 query = randomBox(q % 4 == 0 ? 25.0 : q % 4 == 1 ? 3.0 : q % 4 == 2 ? 0.2 : 0.0, 4);
    std::vector<std::uint32_t> expected, expectedFiltered;
    for (std::uint32_t s = 0; s < boxes.size(); ++s) {
      if (s % 3 == 0 || !boxes[s].overlaps(query)) continue;
      expected.push_back(s);
      if (meetsHalfSpace(boxes[s])) expectedFiltered.push_back(s);
    }
    grid.query(query, out);
    std::sort(out.begin(), out.end());
    EXPECT_EQ(out, expected) << "query " << q;
    grid.query(query, meetsHalfSpace, out);
    std::sort(out.begin(), out.end());
    EXPECT_TRUE(std::includes(out.begin(), out.end(), expectedFiltered.begin(), expectedFiltered.end())) << q;
    EXPECT_TRUE(std::includes(expected.begin(), expected.end(), out.begin(), out.end())) << q;
    grid.query(query, [](const Box3&) { return true; }, out);
    std::sort(out.begin(), out.end());
    EXPECT_EQ(out, expected) << "query " << q;
    grid.queryShared(query, out);
    std::sort(out.begin(), out.end());  // a duplicate would make it differ: `expected` has none
    EXPECT_EQ(out, expected) << "shared query " << q;
  }
}

// The tool's packed grid against brute force: box queries and axis-parallel rays (both directions, from
// inside and outside the domain) return exactly the boxes they meet, each once; boxes beyond the domain
// (filed in border cells) and an empty grid included.
TEST(PackedTriangleGrid, QueriesAndRaysAgreeWithBruteForce) {
  std::mt19937 rng(12);
  std::uniform_real_distribution<double> unit(0, 1);
  const Bounds domain{{-5, 0, 10}, {35, 30, 30}};
  auto randomBox = [&](double extent, double reach) {
    Box3 b;
    for (int a = 0; a < 3; ++a) {
      const double lo = domain.min[a] - reach + (domain.max[a] - domain.min[a] + 2 * reach) * unit(rng);
      b.lo[a] = lo;
      b.hi[a] = lo + extent * unit(rng);
    }
    return b;
  };
  std::vector<Box3> boxes;
  for (int s = 0; s < 3000; ++s) boxes.push_back(randomBox(s % 50 == 0 ? 12.0 : 1.5, 1));
  csg::PackedTriangleGrid grid;
  grid.build(domain, boxes, 4.0);
  auto expectedFor = [&](const Box3& query) {
    std::vector<std::uint32_t> expected;
    for (std::uint32_t s = 0; s < boxes.size(); ++s)
      if (boxes[s].overlaps(query)) expected.push_back(s);
    return expected;
  };
  std::vector<std::uint32_t> out;
  for (int q = 0; q < 400; ++q) {
    const Box3 query = randomBox(q % 4 == 0 ? 25.0 : q % 4 == 1 ? 3.0 : q % 4 == 2 ? 0.2 : 0.0, 4);
    grid.query(query, out);
    std::sort(out.begin(), out.end());  // a duplicate would make it differ: `expected` has none
    EXPECT_EQ(out, expectedFor(query)) << "query " << q;
    const int axis = q % 3, dir = q % 2 ? 1 : -1;
    Box3 ray{query.lo, query.lo};
    (dir > 0 ? ray.hi : ray.lo)[axis] = dir * std::numeric_limits<double>::infinity();
    grid.ray(query.lo, axis, dir, out);
    std::sort(out.begin(), out.end());
    EXPECT_EQ(out, expectedFor(ray)) << "ray " << q;
  }
  csg::PackedTriangleGrid empty;
  empty.build(domain, {}, 4.0);
  empty.query(randomBox(10, 0), out);
  EXPECT_TRUE(out.empty());
}

}  // namespace
}  // namespace reamsim
