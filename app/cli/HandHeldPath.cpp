#include "HandHeldPath.h"

#include <cmath>
#include <random>

namespace reamsim::cli {
namespace {

constexpr double kPi = 3.14159265358979323846;

}  // namespace

std::vector<HandHeldTick> handHeldPath(const BoneCollider& bone, const ReamerModel& reamer, const Vec3& sitePoint,
                                       const Vec3& siteOutward, const HandHeldPathOptions& o) {
  std::mt19937_64 rng(o.seed);
  std::uniform_real_distribution<double> u(0, 1);
  const Vec3 n = normalized(siteOutward), e1 = anyPerpendicular(n), e2 = cross(n, e1);
  std::vector<HandHeldTick> ticks;
  for (int k = 0; k < o.approaches; ++k) {
    // Each approach from its own side (azimuths spread evenly, tilt and aim drawn).
    const double azimuth = 2 * kPi * (k + u(rng)) / o.approaches, tilt = o.maxTiltDeg * kPi / 180 * u(rng);
    const Vec3 across = e1 * std::cos(azimuth) + e2 * std::sin(azimuth);
    Pose aim;
    aim.axis = normalized(-n * std::cos(tilt) + across * std::sin(tilt));
    aim.tip = sitePoint + (e1 * (u(rng) - 0.5) + e2 * (u(rng) - 0.5)) * (2 * o.maxAimOffsetMm);
    aim.rollDeg = 360 * u(rng);
    // Where a straight feed along the axis first touches the bone, from well outside.
    const double reach = 20;
    const Pose far = advancedAlongAxis(aim, -reach);
    const FirstContactResult c = bone.firstContact(reamer, toTransform(far), toTransform(advancedAlongAxis(aim, reach)));
    if (!c.hit || c.t == 0) continue;
    const Pose contact = advancedAlongAxis(far, 2 * reach * c.t);
    // Depth along the axis relative to the contact: approach, press, hold, back off.
    std::vector<double> depth;
    for (double d = -o.startGapMm; d < o.pressMm; d += o.feedMmPerTick) depth.push_back(d);
    for (int i = 0; i < o.holdTicks; ++i) depth.push_back(o.pressMm);
    for (double d = o.pressMm; d > -o.startGapMm; d -= 2 * o.feedMmPerTick) depth.push_back(d);
    const Vec3 a1 = anyPerpendicular(contact.axis), a2 = cross(contact.axis, a1);
    const double phase = 2 * kPi * u(rng);
    auto poseAt = [&](std::size_t i) {
      const double t = double(i) * 1e-3;  // seconds at 1 kHz
      const double w1 = std::sin(2 * kPi * 8.0 * t + phase), w2 = std::cos(2 * kPi * 6.3 * t + phase);
      const double r1 = std::sin(2 * kPi * 5.1 * t + phase), r2 = std::cos(2 * kPi * 9.7 * t);
      Pose p = advancedAlongAxis(contact, depth[i]);
      p.tip += (a1 * w1 + a2 * w2) * o.tremorMm;
      const double turn = std::tan(o.tremorDeg * kPi / 180);
      p.axis = normalized(p.axis + (a1 * r1 + a2 * r2) * turn);
      return toTransform(p);
    };
    RigidTransform previous = poseAt(0);
    for (std::size_t i = 1; i < depth.size(); ++i) {
      const RigidTransform current = poseAt(i);
      ticks.push_back({previous, current});
      previous = current;
    }
  }
  return ticks;
}

}  // namespace reamsim::cli
