#include "ToolBound.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace reamsim::csg {

namespace {
Vec3 faceNormal(const TriangleMesh& mesh, std::uint32_t f) {
  const Triangle& t = mesh.triangles[f];
  const Vec3& a = mesh.vertices[t[0]];
  return cross(mesh.vertices[t[1]] - a, mesh.vertices[t[2]] - a);
}
}  // namespace

std::vector<std::uint32_t> ToolBound::spreadFaces(const TriangleMesh& tool, std::size_t count) {
  std::vector<std::uint32_t> chosen;
  const std::size_t n = tool.triangles.size();
  if (n == 0 || count == 0) return chosen;
  std::vector<Vec3> unit(n);
  std::uint32_t first = 0;
  double largest = -1;
  for (std::uint32_t f = 0; f < n; ++f) {
    const Vec3 v = faceNormal(tool, f);
    const double len = norm(v);
    unit[f] = len > 0 ? v / len : Vec3{};
    if (len > largest) {
      largest = len;
      first = f;
    }
  }
  // closest[f]: the largest cosine between f's normal and a chosen one (the next choice minimises it).
  std::vector<double> closest(n, -std::numeric_limits<double>::infinity());
  std::uint32_t next = first;
  while (chosen.size() < std::min(count, n)) {
    const Vec3 last = unit[next];
    chosen.push_back(next);
    double worst = std::numeric_limits<double>::infinity();
    for (std::uint32_t f = 0; f < n; ++f) {
      if (squaredNorm(unit[f]) == 0) continue;  // degenerate faces give no direction
      closest[f] = std::max(closest[f], dot(unit[f], last));
      if (closest[f] < worst) {
        worst = closest[f];
        next = f;
      }
    }
    if (worst > 0.999) break;  // every normal is within ~2.5° of a chosen one: more planes add nothing
  }
  return chosen;
}

void ToolBound::fit(const TriangleMesh& tool, const std::vector<std::uint32_t>& faces, double slack) {
  normal_.clear();
  support_.clear();
  last_ = 0;
  for (std::uint32_t f : faces) {
    if (f >= tool.triangles.size()) continue;
    const Vec3 v = faceNormal(tool, f);
    const double len = norm(v);
    if (!(len > 0)) continue;
    normal_.push_back(v / len);
  }
  support_.assign(normal_.size(), -std::numeric_limits<double>::infinity());
  for (const Vec3& p : tool.vertices)
    for (std::size_t k = 0; k < normal_.size(); ++k) support_[k] = std::max(support_[k], dot(normal_[k], p));
  for (double& s : support_) s += slack;
}

bool ToolBound::mayMeet(const Box3& box) const {
  const Vec3 centre{0.5 * (box.lo[0] + box.hi[0]), 0.5 * (box.lo[1] + box.hi[1]), 0.5 * (box.lo[2] + box.hi[2])};
  const Vec3 half{0.5 * (box.hi[0] - box.lo[0]), 0.5 * (box.hi[1] - box.lo[1]), 0.5 * (box.hi[2] - box.lo[2])};
  for (std::size_t k = 0; k < normal_.size(); ++k) {
    const Vec3& n = normal_[k];
    const double nearest = dot(n, centre) - (std::abs(n.x) * half.x + std::abs(n.y) * half.y + std::abs(n.z) * half.z);
    if (nearest > support_[k]) return false;
  }
  return true;
}

}  // namespace reamsim::csg
