// CGAL translation unit: the cheap, topological part of repair on import.
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/border.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/repair_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/triangulate_hole.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/helpers.h>

#include "CgalMeshBridge.h"
#include "SoupRepair.h"

namespace reamsim {
namespace {
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Mesh = CGAL::Surface_mesh<K::Point_3>;
namespace PMP = CGAL::Polygon_mesh_processing;

std::size_t cycleLength(const Mesh& m, Mesh::Halfedge_index h) {
  std::size_t n = 0;
  for (auto it : CGAL::halfedges_around_face(h, m)) { (void)it; ++n; }
  return n;
}
}  // namespace

SoupRepairResult repairSoupTopology(const TriangleMesh& input, std::size_t maxHoleBoundaryEdges) {
  SoupRepairResult r;
  std::vector<K::Point_3> points;
  points.reserve(input.vertices.size());
  for (const Vec3& p : input.vertices) points.emplace_back(p.x, p.y, p.z);
  std::vector<std::vector<std::size_t>> polygons;
  polygons.reserve(input.triangles.size());
  for (const Triangle& t : input.triangles) polygons.push_back({t[0], t[1], t[2]});

  // Merges exactly coincident points, drops degenerate and duplicate polygons and unused points.
  PMP::repair_polygon_soup(points, polygons);
  r.verticesRemoved = input.vertices.size() - points.size();
  r.facesRemoved = input.triangles.size() - polygons.size();
  // Returns false when vertices had to be duplicated (non-manifold or non-orientable input).
  r.orientableWithoutSplitting = PMP::orient_polygon_soup(points, polygons);

  r.orientedSoup.vertices.reserve(points.size());
  for (const auto& p : points) r.orientedSoup.vertices.push_back({p.x(), p.y(), p.z()});
  for (const auto& poly : polygons)
    r.orientedSoup.triangles.push_back(
        {std::uint32_t(poly[0]), std::uint32_t(poly[1]), std::uint32_t(poly[2])});

  Mesh mesh;
  PMP::polygon_soup_to_polygon_mesh(points, polygons, mesh);
  std::vector<Mesh::Halfedge_index> borders;
  PMP::extract_boundary_cycles(mesh, std::back_inserter(borders));
  for (auto h : borders) {
    if (cycleLength(mesh, h) <= maxHoleBoundaryEdges) {
      std::vector<Mesh::Face_index> added;
      PMP::triangulate_hole(mesh, h, std::back_inserter(added));
      ++r.holesClosed;
    } else {
      ++r.holesLeftOpen;
    }
  }
  if (CGAL::is_closed(mesh) && !PMP::is_outward_oriented(mesh)) {
    PMP::reverse_face_orientations(mesh);
    r.flippedToOutward = true;
  }
  r.mesh = cgal_bridge::toTriangleMesh(mesh);
  return r;
}

}  // namespace reamsim
