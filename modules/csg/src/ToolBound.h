#pragma once
// A tighter bound of the tool than its axis-aligned box: the intersection of half-spaces {x : n·x ≤ h}
// along a few directions spread over the tool's face normals, each pushed out to the tool's farthest vertex
// (a discrete-orientation polytope, "k-DOP", that holds the tool whatever its shape). A reamer's spinning
// cap placed at a tilt fills a fraction of its box (at the glenoid of a 400k-face scapula the box held
// 14,000 bone faces, of which about 1,100 met the cap); bone faces beyond one of these planes cannot meet
// the tool, so the engine never looks at them. The test is conservative: a face is dropped only when all
// its corners lie beyond one plane by more than `slack`, far above the rounding of the dot products.
#include <cstdint>
#include <vector>

#include "TriangleGrid.h"
#include "reamsim/mesh/TriangleMesh.h"

namespace reamsim::csg {

class ToolBound {
 public:
  // Picks `count` faces of the tool whose normals are spread over the sphere (farthest-point sampling on
  // the unit normals, starting from the largest face). The choice depends only on the tool's shape, not on
  // its placement, so it is made once per tool and reused for every placement of it.
  static std::vector<std::uint32_t> spreadFaces(const TriangleMesh& tool, std::size_t count);

  // The bound of the placed tool: the normals of `faces` (as placed), each with its support value over all
  // the tool's vertices.
  void fit(const TriangleMesh& tool, const std::vector<std::uint32_t>& faces, double slack);

  // False when the triangle lies wholly beyond one plane (it cannot meet the tool). The plane that rejected
  // the last face is tried first: neighbouring faces are mostly rejected by the same plane. (Not for
  // concurrent use.)
  bool mayMeet(const Vec3& a, const Vec3& b, const Vec3& c) {
    const std::size_t n = normal_.size();
    for (std::size_t i = 0; i < n; ++i) {
      const std::size_t k = i == 0 ? last_ : (i == last_ ? 0 : i);
      const Vec3& u = normal_[k];
      const double limit = support_[k];
      if (dot(u, a) > limit && dot(u, b) > limit && dot(u, c) > limit) {
        last_ = k;
        return false;
      }
    }
    return true;
  }
  // False when the box lies wholly beyond one plane.
  bool mayMeet(const Box3& box) const;
  std::size_t planeCount() const { return normal_.size(); }

 private:
  std::vector<Vec3> normal_;     // unit
  std::vector<double> support_;  // max over the tool's vertices of normal · v, plus the slack
  std::size_t last_ = 0;         // the plane that rejected the last face
};

}  // namespace reamsim::csg
