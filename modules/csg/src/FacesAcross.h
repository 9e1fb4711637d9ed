#pragma once
// Internal: the face across each edge of a triangle mesh, found by its directed edges (each edge's twin runs
// the other way), for the tool check (closed, oriented) and the tool's facet sag estimate.
#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include "reamsim/mesh/TriangleMesh.h"

namespace reamsim::csg {

constexpr std::uint32_t kNoFaceAcross = std::numeric_limits<std::uint32_t>::max();

struct FacesAcross {
  std::vector<std::array<std::uint32_t, 3>> face;  // across edge i (t[i] -> t[i+1]) of each face, or kNoFaceAcross
  bool repeatedDirectedEdge = false;  // a directed edge of two faces: not an oriented 2-manifold
};

// The mesh's indices must be valid.
inline FacesAcross facesAcross(const TriangleMesh& m) {
  auto key = [](std::uint32_t a, std::uint32_t b) { return (std::uint64_t(a) << 32) | b; };
  std::vector<std::pair<std::uint64_t, std::uint32_t>> edges;  // directed edge, face
  edges.reserve(3 * m.triangles.size());
  for (std::uint32_t f = 0; f < m.triangles.size(); ++f)
    for (int i = 0; i < 3; ++i) edges.push_back({key(m.triangles[f][i], m.triangles[f][(i + 1) % 3]), f});
  std::sort(edges.begin(), edges.end());
  FacesAcross out;
  for (std::size_t k = 1; k < edges.size() && !out.repeatedDirectedEdge; ++k)
    out.repeatedDirectedEdge = edges[k].first == edges[k - 1].first;
  out.face.resize(m.triangles.size());
  for (std::uint32_t f = 0; f < m.triangles.size(); ++f)
    for (int i = 0; i < 3; ++i) {
      const std::uint64_t twin = key(m.triangles[f][(i + 1) % 3], m.triangles[f][i]);
      const auto it = std::lower_bound(edges.begin(), edges.end(), std::make_pair(twin, std::uint32_t(0)));
      out.face[f][std::size_t(i)] = it != edges.end() && it->first == twin ? it->second : kNoFaceAcross;
    }
  return out;
}

// toolFacetSagMm (reamsim/csg/ToolFacetSag.h) with the faces across already known.
double toolFacetSagMm(const TriangleMesh& tool, const std::vector<std::array<std::uint32_t, 3>>& across);

}  // namespace reamsim::csg
