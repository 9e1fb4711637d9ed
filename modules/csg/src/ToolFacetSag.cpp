#include "reamsim/csg/ToolFacetSag.h"

#include "FacesAcross.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace reamsim {

double csg::toolFacetSagMm(const TriangleMesh& tool, const std::vector<std::array<std::uint32_t, 3>>& across) {
  const std::size_t nf = tool.triangles.size();
  std::vector<Vec3> normal(nf);
  std::vector<double> area2(nf);  // twice the area
  for (std::size_t f = 0; f < nf; ++f) {
    const Triangle& t = tool.triangles[f];
    const Vec3 n = cross(tool.vertices[t[1]] - tool.vertices[t[0]], tool.vertices[t[2]] - tool.vertices[t[0]]);
    area2[f] = norm(n);
    normal[f] = area2[f] > 0 ? n / area2[f] : Vec3{};
  }
  const double sharp = 30 * M_PI / 180;
  double worst = 0;
  for (std::uint32_t f = 0; f < nf; ++f) {
    if (area2[f] == 0) continue;
    double sag = 0;
    for (int i = 0; i < 3; ++i) {
      const std::uint32_t g = across[f][std::size_t(i)];
      if (g == kNoFaceAcross || area2[g] == 0) continue;
      const double turn = std::acos(std::clamp(dot(normal[f], normal[g]), -1.0, 1.0));
      if (turn >= sharp) continue;
      const double edgeLength = norm(tool.vertices[tool.triangles[f][(i + 1) % 3]] - tool.vertices[tool.triangles[f][i]]);
      if (edgeLength > 0) sag += turn * (area2[f] / edgeLength) / 8;
    }
    worst = std::max(worst, sag);
  }
  return worst;
}

double toolFacetSagMm(const TriangleMesh& tool) { return csg::toolFacetSagMm(tool, csg::facesAcross(tool).face); }

}  // namespace reamsim
