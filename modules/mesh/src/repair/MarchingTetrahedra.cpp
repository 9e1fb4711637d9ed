#include "MarchingTetrahedra.h"

#include <algorithm>
#include <unordered_map>

namespace reamsim {
namespace {

// Crossing points stay this fraction of an edge away from the grid points: it bounds how close two
// output triangles can come to each other, far above double rounding, so none can fold over another.
constexpr double kMinEdgeFraction = 1e-3;

class EdgePoints {
 public:
  EdgePoints(const ScalarGrid& grid, TriangleMesh& out) : grid_(grid), out_(out) {}

  std::uint32_t at(std::size_t a, std::size_t b) {
    if (a > b) std::swap(a, b);
    const std::uint64_t key = (std::uint64_t(a) << 32) | b;  // grid indices fit in 32 bits (maxGridPoints)
    auto [it, inserted] = ids_.try_emplace(key, 0u);
    if (inserted) {
      const double va = grid_.value[a], vb = grid_.value[b];
      const double t = std::clamp(va / (va - vb), kMinEdgeFraction, 1.0 - kMinEdgeFraction);
      const Vec3 pa = grid_.point(a), pb = grid_.point(b);
      it->second = static_cast<std::uint32_t>(out_.vertices.size());
      out_.vertices.push_back(pa + (pb - pa) * t);
    }
    return it->second;
  }

 private:
  const ScalarGrid& grid_;
  TriangleMesh& out_;
  std::unordered_map<std::uint64_t, std::uint32_t> ids_;
};

// Adds triangle (a, b, c), flipped if needed so that its normal points from `inside` to `outside`.
void addOriented(TriangleMesh& out, std::uint32_t a, std::uint32_t b, std::uint32_t c, const Vec3& inside,
                 const Vec3& outside) {
  const Vec3& pa = out.vertices[a];
  const Vec3 n = cross(out.vertices[b] - pa, out.vertices[c] - pa);
  if (dot(n, outside - inside) >= 0) out.triangles.push_back({a, b, c});
  else out.triangles.push_back({a, c, b});
}

}  // namespace

TriangleMesh marchingTetrahedra(const ScalarGrid& grid, const StageProgress& progress) {
  TriangleMesh out;
  EdgePoints edges(grid, out);
  // Cell corner c (bits x=1, y=2, z=4); the six tetrahedra are the monotone paths 0 → 7.
  static const int kTets[6][4] = {{0, 1, 3, 7}, {0, 1, 5, 7}, {0, 2, 3, 7}, {0, 2, 6, 7}, {0, 4, 5, 7}, {0, 4, 6, 7}};
  for (int k = 0; k + 1 < grid.n[2]; ++k) {
    progress.check(double(k) / double(grid.n[2]));
    for (int j = 0; j + 1 < grid.n[1]; ++j)
      for (int i = 0; i + 1 < grid.n[0]; ++i) {
        std::size_t corner[8];
        int insideCount = 0;
        for (int c = 0; c < 8; ++c) {
          corner[c] = grid.index(i + (c & 1), j + ((c >> 1) & 1), k + ((c >> 2) & 1));
          insideCount += grid.value[corner[c]] < 0;
        }
        if (insideCount == 0 || insideCount == 8) continue;
        for (const auto& tet : kTets) {
          std::size_t in[4], outs[4];
          int ni = 0, no = 0;
          for (int v : tet) {
            if (grid.value[corner[v]] < 0) in[ni++] = corner[v];
            else outs[no++] = corner[v];
          }
          if (ni == 0 || no == 0) continue;
          Vec3 cin{}, cout{};
          for (int q = 0; q < ni; ++q) cin += grid.point(in[q]);
          for (int q = 0; q < no; ++q) cout += grid.point(outs[q]);
          cin = cin / ni;
          cout = cout / no;
          if (ni == 1 || no == 1) {
            const bool loneInside = ni == 1;
            const std::size_t lone = loneInside ? in[0] : outs[0];
            const std::size_t* others = loneInside ? outs : in;
            addOriented(out, edges.at(lone, others[0]), edges.at(lone, others[1]), edges.at(lone, others[2]), cin, cout);
          } else {
            const std::uint32_t q0 = edges.at(in[0], outs[0]), q1 = edges.at(in[0], outs[1]);
            const std::uint32_t q2 = edges.at(in[1], outs[1]), q3 = edges.at(in[1], outs[0]);
            // Orient the quad as a whole (its vector area is robust even when it is far from planar).
            const Vec3 area = cross(out.vertices[q2] - out.vertices[q0], out.vertices[q3] - out.vertices[q1]);
            if (dot(area, cout - cin) >= 0) {
              out.triangles.push_back({q0, q1, q2});
              out.triangles.push_back({q0, q2, q3});
            } else {
              out.triangles.push_back({q0, q2, q1});
              out.triangles.push_back({q0, q3, q2});
            }
          }
        }
      }
  }
  return out;
}

}  // namespace reamsim
