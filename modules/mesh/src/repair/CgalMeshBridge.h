#pragma once
// Conversions between TriangleMesh and CGAL::Surface_mesh. Include only from CGAL translation units.
#include <CGAL/Surface_mesh.h>

#include "reamsim/mesh/TriangleMesh.h"

namespace reamsim::cgal_bridge {

template <class Point>
CGAL::Surface_mesh<Point> toSurfaceMesh(const TriangleMesh& in) {
  CGAL::Surface_mesh<Point> out;
  out.reserve(in.vertices.size(), in.triangles.size() * 3 / 2, in.triangles.size());
  std::vector<typename CGAL::Surface_mesh<Point>::Vertex_index> v;
  v.reserve(in.vertices.size());
  for (const Vec3& p : in.vertices) v.push_back(out.add_vertex(Point(p.x, p.y, p.z)));
  for (const Triangle& t : in.triangles) out.add_face(v[t[0]], v[t[1]], v[t[2]]);
  return out;
}

template <class Point>
TriangleMesh toTriangleMesh(const CGAL::Surface_mesh<Point>& in) {
  TriangleMesh out;
  std::vector<std::uint32_t> id(in.num_vertices() + in.number_of_removed_vertices(), 0);
  out.vertices.reserve(in.number_of_vertices());
  for (auto v : in.vertices()) {
    id[v.idx()] = static_cast<std::uint32_t>(out.vertices.size());
    const auto& p = in.point(v);
    out.vertices.push_back({CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())});
  }
  out.triangles.reserve(in.number_of_faces());
  for (auto f : in.faces()) {
    Triangle t{};
    int i = 0;
    for (auto v : CGAL::vertices_around_face(in.halfedge(f), in)) {
      if (i < 3) t[i] = id[v.idx()];
      ++i;
    }
    if (i == 3) out.triangles.push_back(t);
  }
  return out;
}

}  // namespace reamsim::cgal_bridge
