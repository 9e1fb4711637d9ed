#include "reamsim/csg/ToolFacetSag.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

namespace reamsim {

double toolFacetSagMm(const TriangleMesh& tool) {
  const std::size_t nf = tool.triangles.size();
  std::vector<Vec3> normal(nf);
  std::vector<double> area2(nf);  // twice the area
  for (std::size_t f = 0; f < nf; ++f) {
    const Triangle& t = tool.triangles[f];
    const Vec3 n = cross(tool.vertices[t[1]] - tool.vertices[t[0]], tool.vertices[t[2]] - tool.vertices[t[0]]);
    area2[f] = norm(n);
    normal[f] = area2[f] > 0 ? n / area2[f] : Vec3{};
  }
  // Directed edge (a, b) of face f; its twin (b, a) is the face across.
  std::vector<std::pair<std::uint64_t, std::uint32_t>> edges;
  edges.reserve(3 * nf);
  auto key = [](std::uint32_t a, std::uint32_t b) { return (std::uint64_t(a) << 32) | b; };
  for (std::uint32_t f = 0; f < nf; ++f)
    for (int i = 0; i < 3; ++i) edges.push_back({key(tool.triangles[f][i], tool.triangles[f][(i + 1) % 3]), f});
  std::sort(edges.begin(), edges.end());
  const double sharp = 30 * M_PI / 180;
  double worst = 0;
  for (std::uint32_t f = 0; f < nf; ++f) {
    if (area2[f] == 0) continue;
    double sag = 0;
    for (int i = 0; i < 3; ++i) {
      const std::uint32_t a = tool.triangles[f][i], b = tool.triangles[f][(i + 1) % 3];
      const auto it = std::lower_bound(edges.begin(), edges.end(), std::make_pair(key(b, a), std::uint32_t(0)));
      if (it == edges.end() || it->first != key(b, a) || area2[it->second] == 0) continue;
      const double turn = std::acos(std::clamp(dot(normal[f], normal[it->second]), -1.0, 1.0));
      if (turn >= sharp) continue;
      const double edgeLength = norm(tool.vertices[b] - tool.vertices[a]);
      if (edgeLength > 0) sag += turn * (area2[f] / edgeLength) / 8;
    }
    worst = std::max(worst, sag);
  }
  return worst;
}

}  // namespace reamsim
