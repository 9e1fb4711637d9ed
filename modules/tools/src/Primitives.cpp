#include "reamsim/tools/Primitives.h"

#include <map>
#include <stdexcept>
#include <tuple>

namespace reamsim {

TriangleMesh buildBox(const Bounds& box, int n) {
  if (box.empty() || n < 1) throw std::invalid_argument("buildBox needs a non-empty box and divisions >= 1");
  TriangleMesh m;
  std::map<std::tuple<int, int, int>, std::uint32_t> ids;  // lattice point -> vertex, shared between faces
  auto vertex = [&](int i, int j, int k) {
    auto [it, inserted] = ids.try_emplace({i, j, k}, std::uint32_t(m.vertices.size()));
    if (inserted) {
      const Vec3 s = box.size();
      m.vertices.push_back(box.min + Vec3{s.x * i / n, s.y * j / n, s.z * k / n});
    }
    return it->second;
  };
  // For each axis a and side, the face's lattice is spanned by the two other axes (b, c), ordered so
  // that the winding is outward.
  for (int a = 0; a < 3; ++a)
    for (int side = 0; side < 2; ++side) {
      const int b = (a + 1) % 3, c = (a + 2) % 3;
      for (int u = 0; u < n; ++u)
        for (int v = 0; v < n; ++v) {
          auto at = [&](int du, int dv) {
            int idx[3];
            idx[a] = side * n;
            idx[b] = u + du;
            idx[c] = v + dv;
            return vertex(idx[0], idx[1], idx[2]);
          };
          const std::uint32_t p00 = at(0, 0), p10 = at(1, 0), p11 = at(1, 1), p01 = at(0, 1);
          if (side == 1) {
            m.triangles.push_back({p00, p10, p11});
            m.triangles.push_back({p00, p11, p01});
          } else {
            m.triangles.push_back({p00, p11, p10});
            m.triangles.push_back({p00, p01, p11});
          }
        }
    }
  return m;
}

}  // namespace reamsim
