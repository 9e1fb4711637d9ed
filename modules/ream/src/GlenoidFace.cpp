#include "reamsim/ream/GlenoidFace.h"

#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <unordered_map>
#include <vector>

#include "reamsim/mesh/ClosestPoints.h"

namespace reamsim {
namespace {

constexpr double kPi = 3.14159265358979323846;

struct Candidate {
  std::array<std::uint32_t, 3> corners;  // position numbers (PositionNumbers), for the shared edges
  Vec3 vectorArea;   // half the cross product: area times unit normal
  double gap;        // from the centre to the triangle's closest point
};

std::string mm(double v) {
  std::ostringstream s;
  s.precision(3);
  s << v << " mm";
  return s.str();
}

void checkPreconditions(const BoneState& bone, const Vec3& centre, const GlenoidFaceOptions& o) {
  if (!isFinite(centre)) throw std::invalid_argument("the glenoid centre is not a finite point");
  if (!(o.radiusMm >= 2 && o.radiusMm <= 40))
    throw std::invalid_argument("the glenoid face is measured within 2 to 40 mm of its centre, not " + mm(o.radiusMm));
  if (!(o.maxTurnDeg >= 1 && o.maxTurnDeg <= 89))
    throw std::invalid_argument("the glenoid face's normals may turn 1 to 89 degrees from its mean, not " +
                                std::to_string(o.maxTurnDeg));
  if (bone.empty()) throw std::invalid_argument("the bone has no surface to measure the glenoid face on");
}

// One number per distinct position: triangles meet along an edge whose corners lie at the same two positions,
// whether or not they share vertex slots (a mesh read with its coincident vertices apart, a seam of a commit).
class PositionNumbers {
 public:
  std::uint32_t of(const Vec3& p) { return numbers_.try_emplace(p, std::uint32_t(numbers_.size())).first->second; }

 private:
  std::unordered_map<Vec3, std::uint32_t, Vec3PositionHash> numbers_;
};

// The triangles whose centroids lie within the radius, and the gap to the nearest surface point.
std::vector<Candidate> trianglesWithin(const BoneState& bone, const Vec3& centre, double radius, double& nearestCentroid) {
  std::vector<Candidate> near;
  PositionNumbers positions;
  double nearest2 = std::numeric_limits<double>::infinity();
  const double r2 = radius * radius;
  bone.forEachLiveTriangle([&](std::uint32_t, const Triangle& t) {
    const Vec3& a = bone.vertex(t[0]);
    const Vec3& b = bone.vertex(t[1]);
    const Vec3& c = bone.vertex(t[2]);
    const double d2 = squaredNorm((a + b + c) * (1.0 / 3.0) - centre);
    if (d2 < nearest2) nearest2 = d2;  // seldom taken: a branch, not a chain of minima through every triangle
    if (d2 > r2) return;
    near.push_back({{positions.of(a), positions.of(b), positions.of(c)}, cross(b - a, c - a) * 0.5,
                    norm(closestPointOnTriangle(centre, a, b, c) - centre)});
  });
  nearestCentroid = std::sqrt(nearest2);
  return near;
}

constexpr const char* kNoSingleWay =
    "the surface at the glenoid centre faces no single way (its triangles' areas cancel out)";

std::uint64_t edgeKey(std::uint32_t u, std::uint32_t v) {
  return u < v ? (std::uint64_t(u) << 32) | v : (std::uint64_t(v) << 32) | u;
}

}  // namespace

GlenoidFace measureGlenoidFace(const BoneState& bone, const Vec3& centre, const GlenoidFaceOptions& o) {
  checkPreconditions(bone, centre, o);
  double nearestCentroid = 0;
  const std::vector<Candidate> near = trianglesWithin(bone, centre, o.radiusMm, nearestCentroid);
  if (near.empty())
    throw std::invalid_argument("no bone surface lies within " + mm(o.radiusMm) + " of the glenoid centre (the nearest " +
                                "triangle's centre is " + mm(nearestCentroid) + " away): place it on the glenoid face");

  double gap = std::numeric_limits<double>::infinity();
  for (const Candidate& c : near) gap = std::min(gap, c.gap);
  // The mean normal near the centre: triangles within a third of the radius beyond the nearest point. A reamed
  // glenoid lies below the centre placed on the bone before it, hence "beyond the nearest point".
  const double core = gap + o.radiusMm / 3;
  Vec3 reference{};
  for (const Candidate& c : near)
    if (c.gap <= core) reference += c.vectorArea;
  if (!(norm(reference) > 0))
    throw std::invalid_argument(kNoSingleWay);
  reference = normalized(reference);

  // The face grows from the triangles near the centre that face the reference's way, over shared edges, to the
  // triangles within the radius that do too.
  const double minCos = std::cos(o.maxTurnDeg * kPi / 180);
  // A triangle of no area faces no way: it joins its neighbours (a sliver on a seam) and adds nothing.
  auto faces = [&](const Candidate& c) { return dot(c.vectorArea, reference) >= minCos * norm(c.vectorArea); };
  std::unordered_multimap<std::uint64_t, std::size_t> byEdge;
  byEdge.reserve(near.size() * 3);
  for (std::size_t i = 0; i < near.size(); ++i)
    for (int k = 0; k < 3; ++k) byEdge.emplace(edgeKey(near[i].corners[k], near[i].corners[(k + 1) % 3]), i);
  std::vector<char> taken(near.size(), 0);
  std::vector<std::size_t> stack;
  for (std::size_t i = 0; i < near.size(); ++i)
    if (near[i].gap <= core && norm(near[i].vectorArea) > 0 && faces(near[i])) {
      taken[i] = 1;
      stack.push_back(i);
    }
  GlenoidFace face;
  Vec3 sum{};
  while (!stack.empty()) {
    const std::size_t i = stack.back();
    stack.pop_back();
    sum += near[i].vectorArea;
    face.areaMm2 += norm(near[i].vectorArea);
    ++face.triangles;
    for (int k = 0; k < 3; ++k) {
      const auto [from, to] = byEdge.equal_range(edgeKey(near[i].corners[k], near[i].corners[(k + 1) % 3]));
      for (auto it = from; it != to; ++it)
        if (!taken[it->second] && faces(near[it->second])) {
          taken[it->second] = 1;
          stack.push_back(it->second);
        }
    }
  }
  if (!(norm(sum) > 0))
    throw std::invalid_argument(kNoSingleWay);
  face.outward = normalized(sum);
  face.radiusMm = o.radiusMm;
  face.centreGapMm = gap;
  return face;
}

}  // namespace reamsim
