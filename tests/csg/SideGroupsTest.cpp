// SideGroups / FarFaceGroups (modules/csg/src/SideGroups.h): far faces grouped before the near components
// exist, joined with them after, one side per group, conflicts reported.
#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <vector>

#include "SideGroups.h"

namespace reamsim::csg {
namespace {

// A strip of far faces 0-1-2 | 3-4 (two runs, split where face 2 and face 3 do not share an edge), each
// face with edges 0..2: edge 0 goes to the next face of its run, edge 1 to the previous one, edge 2 to a
// near face (given as a directed edge b -> a of "near vertices"), or to nothing.
struct Strip {
  std::vector<std::array<std::uint32_t, 2>> runNeighbours = {{1, FarFaceGroups<int>::kNoFace},
                                                            {2, 0},
                                                            {FarFaceGroups<int>::kNoFace, 1},
                                                            {4, FarFaceGroups<int>::kNoFace},
                                                            {FarFaceGroups<int>::kNoFace, 3}};
  // Face j's near neighbour across edge 2: the near edge (b, a), or b = -1 for none.
  std::vector<std::array<int, 2>> nearEdge = {{10, 11}, {-1, -1}, {-1, -1}, {-1, -1}, {20, 21}};
};

FarFaceGroups<int> grouped(const Strip& s) {
  FarFaceGroups<int> g;
  g.faces = {100, 101, 102, 103, 104};
  g.group([&](std::size_t j, int i) { return i < 2 ? s.runNeighbours[j][i] : FarFaceGroups<int>::kNoFace; },
          [&](std::size_t j, int i, int& b, int& a) {
            if (i != 2 || s.nearEdge[j][0] < 0) return false;
            b = s.nearEdge[j][0];
            a = s.nearEdge[j][1];
            return true;
          });
  return g;
}

TEST(SideGroups, FarFacesAcrossEdgesShareOneSideBeforeAnyNearComponentExists) {
  FarFaceGroups<int> g = grouped(Strip{});
  ASSERT_EQ(g.toNear.size(), 2u);  // faces 0 and 4 border near faces
  EXPECT_TRUE(g.groups.setSide(g.groups.far(1), kInside));
  EXPECT_EQ(g.groups.side(g.groups.far(0)), kInside);
  EXPECT_EQ(g.groups.side(g.groups.far(2)), kInside);
  EXPECT_EQ(g.groups.side(g.groups.far(3)), kUndecided);  // the other run
  EXPECT_TRUE(g.groups.anyFarUndecided());
  EXPECT_TRUE(g.groups.setSide(g.groups.far(4), kOutside));
  EXPECT_FALSE(g.groups.anyFarUndecided());
  EXPECT_FALSE(g.groups.setSide(g.groups.far(0), kOutside));  // a group has one side
  EXPECT_TRUE(g.groups.setSide(g.groups.far(0), kUndecided));  // which kUndecided does not change
  EXPECT_EQ(g.groups.side(g.groups.far(0)), kInside);
}

TEST(SideGroups, NearComponentsJoinedAfterwardsCarryTheirSideToTheFarFacesTheyBorder) {
  FarFaceGroups<int> g = grouped(Strip{});
  // Three near components; the near face with edge 10 -> 11 is in component 2, the one with 20 -> 21 has
  // no face (a border: -1), component 0 borders no far face.
  std::vector<std::array<int, 2>> asked;
  g.joinNear(3, [&](int b, int a) {
    asked.push_back({b, a});
    return b == 10 && a == 11 ? 2 : -1;
  });
  EXPECT_EQ(asked, (std::vector<std::array<int, 2>>{{10, 11}, {20, 21}}));
  EXPECT_TRUE(g.groups.setSide(g.groups.near(2), kOutside));
  EXPECT_EQ(g.groups.side(g.groups.far(0)), kOutside);
  EXPECT_EQ(g.groups.side(g.groups.far(2)), kOutside);
  EXPECT_EQ(g.groups.side(g.groups.far(4)), kUndecided);  // its near neighbour had no component
  EXPECT_EQ(g.groups.side(g.groups.near(0)), kUndecided);
  EXPECT_FALSE(g.groups.setSide(g.groups.far(1), kInside));  // contradicts component 2's side
  // Near components are numbered after the far faces: far(j) and near(c) never collide.
  EXPECT_EQ(g.groups.near(0), g.faces.size());
}

TEST(SideGroups, GroupingAgainStartsFromNothing) {
  FarFaceGroups<int> g = grouped(Strip{});
  g.groups.setSide(g.groups.far(0), kInside);
  Strip lonely;
  lonely.runNeighbours.assign(5, {FarFaceGroups<int>::kNoFace, FarFaceGroups<int>::kNoFace});
  lonely.nearEdge.assign(5, {-1, -1});
  g = grouped(lonely);
  EXPECT_TRUE(g.toNear.empty());
  for (std::size_t j = 0; j < 5; ++j) EXPECT_EQ(g.groups.side(g.groups.far(j)), kUndecided);
  EXPECT_TRUE(g.groups.setSide(g.groups.far(0), kInside));
  EXPECT_EQ(g.groups.side(g.groups.far(1)), kUndecided);
}

}  // namespace
}  // namespace reamsim::csg
