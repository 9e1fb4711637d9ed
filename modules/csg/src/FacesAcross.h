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

// `triangles` index `vertexCount` vertices (the indices must be valid). Each directed edge's twin is looked
// for among the faces about its end vertex (a handful), not by sorting all the edges; where several faces
// hold the twin (not a manifold), the first by index.
inline FacesAcross facesAcross(const std::vector<Triangle>& triangles, std::size_t vertexCount) {
  // The faces about each vertex, by increasing face index: about[start[v] .. start[v + 1]).
  std::vector<std::uint32_t> start(vertexCount + 1, 0), about(3 * triangles.size());
  for (const Triangle& t : triangles)
    for (std::uint32_t v : t) ++start[v + 1];
  for (std::size_t v = 0; v < vertexCount; ++v) start[v + 1] += start[v];
  std::vector<std::uint32_t> fill(start.begin(), start.end() - 1);
  for (std::uint32_t f = 0; f < triangles.size(); ++f)
    for (std::uint32_t v : triangles[f]) about[fill[v]++] = f;
  // The first face about `v` other than `except` with the directed edge a -> b, or kNoFaceAcross.
  auto faceWith = [&](std::uint32_t v, std::uint32_t a, std::uint32_t b, std::uint32_t except) {
    for (std::uint32_t k = start[v]; k < start[v + 1]; ++k) {
      const std::uint32_t g = about[k];
      if (g == except) continue;
      const Triangle& t = triangles[g];
      for (int j = 0; j < 3; ++j)
        if (t[j] == a && t[(j + 1) % 3] == b) return g;
    }
    return kNoFaceAcross;
  };
  FacesAcross out;
  out.face.resize(triangles.size());
  for (std::uint32_t f = 0; f < triangles.size(); ++f)
    for (int i = 0; i < 3; ++i) {
      const std::uint32_t a = triangles[f][i], b = triangles[f][(i + 1) % 3];
      out.repeatedDirectedEdge = out.repeatedDirectedEdge || faceWith(a, a, b, f) != kNoFaceAcross;
      out.face[f][std::size_t(i)] = faceWith(b, b, a, kNoFaceAcross);
    }
  return out;
}

inline FacesAcross facesAcross(const TriangleMesh& m) { return facesAcross(m.triangles, m.vertices.size()); }

// toolFacetSagMm (reamsim/csg/ToolFacetSag.h) with the faces across already known.
double toolFacetSagMm(const TriangleMesh& tool, const std::vector<std::array<std::uint32_t, 3>>& across);

}  // namespace reamsim::csg
