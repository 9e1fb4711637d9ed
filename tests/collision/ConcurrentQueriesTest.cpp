// One BoneCollider queried from two threads at once (a haptic device's thread and the reaming worker could
// share one; first contact, face distance, overlap and axial penetration): every query is const on the tree and keeps its scratch per thread, so each thread gets exactly
// what it gets alone. `scripts/tsan-csg.sh build-tsan reamsim_collision_tests 'collisionConcurrency.*'` runs
// it under ThreadSanitizer.
#include <gtest/gtest.h>

#include <random>
#include <thread>
#include <utility>
#include <vector>

#include "CollisionFixtures.h"
#include "reamsim/collision/BoneCollider.h"

namespace reamsim {
namespace {

struct Answer {
  bool hit = false;
  double t = 0, distance = 0;
  bool overlap = false;
  std::size_t touched = 0;
  double depth = 0;  // the axial penetration at the end pose (the parametric reamer's face path)
  bool operator==(const Answer& o) const {
    return hit == o.hit && t == o.t && distance == o.distance && overlap == o.overlap && touched == o.touched &&
           depth == o.depth;
  }
};

TEST(collisionConcurrency, TwoThreadsGetWhatOneThreadGets) {
  const TriangleMesh bone = test::defaultScapula();
  const BoneCollider collider(bone);
  const ReamerModel reamer = ReamerModel::fromSpec(test::smallSpec(false));
  std::mt19937_64 rng(29);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<std::pair<RigidTransform, RigidTransform>> motions;
  for (int i = 0; i < 300; ++i) {
    const Pose start = test::poseNearSurface(bone, rng, 0.3, 3, 30);
    Pose end = start;
    end.tip = start.tip + start.axis * (4 * u(rng));
    motions.emplace_back(toTransform(start), toTransform(end));
  }
  auto answer = [&](const std::pair<RigidTransform, RigidTransform>& m) {
    Answer a;
    const FirstContactResult f = collider.firstContact(reamer, m.first, m.second);
    a.hit = f.hit;
    a.t = f.t;
    a.distance = collider.faceDistance(reamer, m.first).distanceMm;
    const OverlapResult o = collider.overlap(reamer, m.second);
    a.overlap = o.overlap;
    a.touched = o.touchedSlots.size();
    a.depth = collider.axialPenetration(reamer, m.second).depthMm;
    return a;
  };
  std::vector<Answer> alone;
  for (const auto& m : motions) alone.push_back(answer(m));
  std::vector<Answer> forward(motions.size()), backward(motions.size());
  std::thread first([&] {
    for (std::size_t i = 0; i < motions.size(); ++i) forward[i] = answer(motions[i]);
  });
  std::thread second([&] {
    for (std::size_t i = motions.size(); i-- > 0;) backward[i] = answer(motions[i]);
  });
  first.join();
  second.join();
  std::size_t hits = 0, pressed = 0;
  for (std::size_t i = 0; i < motions.size(); ++i) {
    EXPECT_TRUE(forward[i] == alone[i]) << i;
    EXPECT_TRUE(backward[i] == alone[i]) << i;
    hits += alone[i].hit;
    pressed += alone[i].depth > 0;
  }
  EXPECT_GT(hits, 50u);  // the motions meet the bone often enough for the search to go deep
  EXPECT_GT(pressed, 30u);
  EXPECT_LT(hits, motions.size());
}

}  // namespace
}  // namespace reamsim
