// The axial penetration's face path (modules/collision/src/CapShadow.h, CapBounds.h): a parametric reamer's
// cutting face as a height field across its axis. Checked against the pair-by-pair intervals the general path
// computes (AxialEvents.h): a bone triangle's interval from the height field is the union of its intervals
// with every face triangle, and the bounds the sweep prunes with hold every triangle's exact interval, for
// one triangle and for every node of a tree over many.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "AxialEvents.h"
#include "CapBounds.h"
#include "CapShadow.h"
#include "CollisionFixtures.h"
#include "PoseFrame.h"
#include "PropertyBones.h"
#include "reamsim/collision/ReamerModel.h"
#include "reamsim/collision/TriangleBvh.h"

namespace reamsim {
namespace {

using detail::CapShadow;

ReamerSpec glenoidLikeSpec() {  // the default glenoid reamer's shape: 36 mm, sphere radius 30, fine facets
  ReamerSpec s = test::smallSpec(false, 128, 16);
  s.name = "test-36-R30";
  s.diameterMm = 36;
  s.sphereRadiusMm = 30;
  return s;
}

// The three face shapes: a coarse cap, a fine wide one, a flat disc.
std::vector<ReamerModel> reamers() {
  return {ReamerModel::fromSpec(test::smallSpec(false, 24, 6)), ReamerModel::fromSpec(glenoidLikeSpec()),
          ReamerModel::fromSpec(test::smallSpec(true, 24, 6))};
}

// The union of the triangle's intervals with every face triangle (reamer frame, backing out along +z
// relative to the bone), as the general path would find them one pair at a time.
bool unionOfPairs(const ReamerModel& reamer, const Vec3 (&q)[3], double& lo, double& hi) {
  lo = std::numeric_limits<double>::infinity();
  hi = -lo;
  const BvhTriangle bone{q[0], q[1], q[2]};
  for (std::uint32_t f : reamer.faceTriangles()) {
    const Triangle& t = reamer.solid().triangles[f];
    const Vec3 x[3] = {reamer.solid().vertices[t[0]], reamer.solid().vertices[t[1]], reamer.solid().vertices[t[2]]};
    const detail::AxialInterval iv = detail::axialInterval(x, bone, Vec3{0, 0, 1});
    if (!iv.valid) continue;
    lo = std::min(lo, iv.lo);
    hi = std::max(hi, iv.hi);
  }
  return lo <= hi;
}

// A random triangle near the face (reamer frame): its middle within the face's shadow (a little beyond it at
// times) and near the face's height, sizes from 0.02 to 4 mm, any orientation but along the axis.
void randomTriangle(const ReamerModel& reamer, std::mt19937_64& rng, Vec3 (&q)[3]) {
  std::uniform_real_distribution<double> u(-1, 1);
  const double radius = reamer.capShadow()->rimRadius();
  for (;;) {
    const double r = 1.1 * radius * std::sqrt(std::abs(u(rng))), a = 3.14159265358979 * u(rng);
    const Vec3 c{r * std::cos(a), r * std::sin(a), 0};
    const ReamerModel::IdealSolid& id = reamer.idealSolid();
    const double top = id.flat ? 0.0 : id.sphereCentreZ + std::sqrt(std::max(0.0, id.sphereRadius * id.sphereRadius - r * r));
    const Vec3 middle{c.x, c.y, top + 1.5 * u(rng)};
    const double size = 0.02 * std::pow(200.0, std::abs(u(rng)));
    for (Vec3& v : q) v = middle + Vec3{u(rng), u(rng), 0.5 * u(rng)} * size;
    if (CapShadow::steep(q)) return;
  }
}

TEST(collisionCapBounds, HeightFieldIntervalIsTheUnionOfThePairIntervals) {
  std::mt19937_64 rng(61);
  std::size_t compared = 0;
  for (const ReamerModel& reamer : reamers()) {
    ASSERT_NE(reamer.capShadow(), nullptr);
    for (int i = 0; i < 1500; ++i) {
      Vec3 q[3];
      randomTriangle(reamer, rng, q);
      double lo, hi, rlo, rhi;
      Vec3 point;
      const bool got = reamer.capShadow()->interval(q, lo, hi, point);
      const bool ref = unionOfPairs(reamer, q, rlo, rhi);
      ASSERT_EQ(got, ref) << "triangle " << i;
      if (!got) continue;
      EXPECT_NEAR(lo, rlo, 1e-9) << "triangle " << i;
      EXPECT_NEAR(hi, rhi, 1e-9) << "triangle " << i;
      // The point where it last touches lies on the bone triangle at the face's height less hi.
      const Vec3 n = normalized(cross(q[1] - q[0], q[2] - q[0]));
      EXPECT_NEAR(dot(n, point - q[0]), 0, 1e-9) << "triangle " << i;
      if (::testing::Test::HasFailure()) return;
      ++compared;
    }
  }
  EXPECT_GT(compared, 3000u);  // most of them lie over the face
}

TEST(collisionCapBounds, TriangleBoundsHoldTheExactInterval) {
  std::mt19937_64 rng(62);
  for (const ReamerModel& reamer : reamers()) {
    const detail::PoseFrame frame(RigidTransform{});
    const detail::CapBounds bounds(reamer, frame);
    // One triangle: the bounds hold its exact interval; their slack (NaN when it lies off the face).
    auto check = [&](const Vec3 (&q)[3], const std::string& what) {
      double lo, hi, blo, bhi;
      Vec3 point;
      if (!reamer.capShadow()->interval(q, lo, hi, point)) return std::numeric_limits<double>::quiet_NaN();
      bounds.triangle(q, blo, bhi);
      EXPECT_LE(blo, lo) << what;
      EXPECT_GE(bhi, hi) << what;
      return bhi - hi + (lo - blo);
    };
    std::vector<double> slack;
    for (int i = 0; i < 3000; ++i) {
      Vec3 q[3];
      randomTriangle(reamer, rng, q);
      const double s = check(q, "triangle " + std::to_string(i));
      if (::testing::Test::HasFailure()) return;
      if (s == s && std::max({std::abs(q[0].x - q[1].x), std::abs(q[0].y - q[2].y)}) < 0.5) slack.push_back(s);
    }
    // Tiny triangles about the face's vertices, where the face meets the ideal sphere: the upper bound has
    // next to no slack there.
    for (std::size_t v = 0; v < reamer.solid().vertices.size(); v += 7) {
      const Vec3 c = reamer.solid().vertices[v] - Vec3{0, 0, 0.1};
      const Vec3 q[3] = {c + Vec3{1e-5, 0, 0}, c + Vec3{-5e-6, 9e-6, 1e-6}, c + Vec3{-5e-6, -9e-6, -1e-6}};
      check(q, "vertex " + std::to_string(v));
      if (::testing::Test::HasFailure()) return;
    }
    // Tight where the sweep needs them: small triangles within a few facet sags of the exact interval.
    ASSERT_FALSE(slack.empty());
    std::nth_element(slack.begin(), slack.begin() + slack.size() / 2, slack.end());
    EXPECT_LT(slack[slack.size() / 2], 0.2) << reamer.solid().triangles.size() << " reamer triangles";
  }
}

// A bone patch beside the face: a sphere of nearly the cap's curvature, dented at random, seen from random
// poses; every node's bounds hold the exact intervals of all its triangles over the face.
TEST(collisionCapBounds, NodeBoundsHoldEveryTriangleOfTheNode) {
  std::mt19937_64 rng(63);
  std::uniform_real_distribution<double> u(-1, 1);
  std::size_t checkedNodes = 0;
  for (const ReamerModel& reamer : reamers()) {
    TriangleMesh bone = test::icosphere(5, 17, {0, 0, 0});
    for (Vec3& v : bone.vertices) v = v * (1 + 0.004 * u(rng));
    const TriangleBvh bvh = TriangleBvh::fromMesh(bone);
    for (int trial = 0; trial < 6; ++trial) {
      Pose p;
      p.axis = test::randomUnit(rng);
      p.tip = p.axis * (17 + 0.3 * u(rng)) + test::randomUnit(rng) * (2 * std::abs(u(rng)));
      p.rollDeg = 180 * u(rng);
      const RigidTransform T = toTransform(p);
      const detail::PoseFrame frame(T);
      const detail::CapBounds bounds(reamer, frame);
      // Post-order: each node's exact union from its children's.
      const auto& nodes = bvh.nodes();
      std::vector<double> lo(nodes.size(), std::numeric_limits<double>::infinity()), hi(nodes.size(), -std::numeric_limits<double>::infinity());
      std::vector<std::pair<std::int32_t, bool>> stack{{bvh.root(), false}};
      while (!stack.empty()) {
        auto [n, done] = stack.back();
        stack.pop_back();
        const BvhNode& N = nodes[n];
        if (!N.isLeaf() && !done) {
          stack.push_back({n, true});
          stack.push_back({N.left, false});
          stack.push_back({N.right, false});
          continue;
        }
        if (N.isLeaf()) {
          const std::uint32_t* slots = bvh.leafSlots(N);
          for (int i = 0; i < N.count; ++i) {
            const BvhTriangle& t = bvh.triangle(slots[i]);
            const Vec3 q[3] = {frame.toLocal(t.a), frame.toLocal(t.b), frame.toLocal(t.c)};
            double a, b;
            Vec3 point;
            if (!CapShadow::steep(q) || !reamer.capShadow()->interval(q, a, b, point)) continue;
            lo[n] = std::min(lo[n], a);
            hi[n] = std::max(hi[n], b);
          }
        } else {
          lo[n] = std::min(lo[N.left], lo[N.right]);
          hi[n] = std::max(hi[N.left], hi[N.right]);
        }
        if (!(lo[n] <= hi[n])) continue;  // no triangle of it over the face
        double blo, bhi;
        ASSERT_TRUE(bounds.node(N.lo, N.hi, bvh.slab(n), blo, bhi)) << "node " << n;
        EXPECT_LE(blo, lo[n]) << "node " << n;
        EXPECT_GE(bhi, hi[n]) << "node " << n;
        if (::testing::Test::HasFailure()) return;
        ++checkedNodes;
      }
    }
  }
  EXPECT_GT(checkedNodes, 10000u);
}

}  // namespace
}  // namespace reamsim
