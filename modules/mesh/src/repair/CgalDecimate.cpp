// CGAL translation unit: Garland–Heckbert decimation, accepted only when the result stays closed and
// free of self-intersections (edge collapse alone does not guarantee the latter).
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/Bounded_normal_change_filter.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/Count_stop_predicate.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/GarlandHeckbert_plane_policies.h>
#include <CGAL/Surface_mesh_simplification/edge_collapse.h>
#include <CGAL/boost/graph/helpers.h>

#include "CgalMeshBridge.h"
#include "reamsim/mesh/VolumetricRemesh.h"

namespace reamsim {
namespace {
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Mesh = CGAL::Surface_mesh<K::Point_3>;
namespace SMS = CGAL::Surface_mesh_simplification;
}  // namespace

bool decimateWithoutSelfIntersections(TriangleMesh& mesh, std::size_t targetTriangles) {
  std::size_t target = targetTriangles;
  for (int attempt = 0; attempt < 5 && target < mesh.triangles.size(); ++attempt, target = target * 3 / 2) {
    Mesh m = cgal_bridge::toSurfaceMesh<K::Point_3>(mesh);
    SMS::GarlandHeckbert_plane_policies<Mesh, K> policies(m);
    // The stop predicate counts edges; a closed triangle mesh has 3F/2 edges.
    SMS::Count_stop_predicate<Mesh> stop(target * 3 / 2);
    SMS::edge_collapse(m, stop,
                       CGAL::parameters::get_cost(policies.get_cost())
                           .get_placement(policies.get_placement())
                           .filter(SMS::Bounded_normal_change_filter<>()));
    m.collect_garbage();
    if (!CGAL::is_closed(m) || !CGAL::is_triangle_mesh(m)) continue;
    if (CGAL::Polygon_mesh_processing::does_self_intersect(m)) continue;
    mesh = cgal_bridge::toTriangleMesh(m);
    return true;
  }
  return false;
}

}  // namespace reamsim
