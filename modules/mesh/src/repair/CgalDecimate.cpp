// CGAL translation unit: Garland–Heckbert decimation, accepted only when the result stays closed and
// free of self-intersections (edge collapse alone does not guarantee the latter).
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/Bounded_normal_change_filter.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/Count_stop_predicate.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/GarlandHeckbert_plane_policies.h>
#include <CGAL/Surface_mesh_simplification/edge_collapse.h>
#include <CGAL/boost/graph/helpers.h>

#include <algorithm>
#include <cmath>
#include <utility>

#include "CgalMeshBridge.h"
#include "reamsim/mesh/Validation.h"
#include "reamsim/mesh/VolumetricRemesh.h"

namespace reamsim {
namespace {
using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using Mesh = CGAL::Surface_mesh<K::Point_3>;
namespace SMS = CGAL::Surface_mesh_simplification;

// Count_stop_predicate that also stops when the user asks to, checked every few thousand collapses:
// edge_collapse has no other way out (the caller then throws). Reports `progress` as the edge count falls
// towards the target.
class StopAtCountOrWhenAsked {
 public:
  StopAtCountOrWhenAsked(std::size_t edges, StageProgress progress)
      : count_(edges), edges_(edges), progress_(std::move(progress)) {}
  template <class FT, class Profile>
  bool operator()(const FT& cost, const Profile& profile, std::size_t initialEdges, std::size_t currentEdges) const {
    if (count_(cost, profile, initialEdges, currentEdges)) return true;
    if (++calls_ % 4096 != 0) return false;
    const double done = double(initialEdges - std::min(initialEdges, currentEdges)) /
                        double(std::max<std::size_t>(1, initialEdges - std::min(initialEdges, edges_)));
    asked_ = asked_ || !progress_.keepGoing(std::min(1.0, done));
    return asked_;
  }
  bool asked() const { return asked_; }

 private:
  SMS::Count_stop_predicate<Mesh> count_;
  std::size_t edges_;
  StageProgress progress_;
  mutable std::size_t calls_ = 0;
  mutable bool asked_ = false;
};
}  // namespace

bool decimateWithoutSelfIntersections(TriangleMesh& mesh, std::size_t targetTriangles, const StageProgress& progress) {
  std::size_t target = targetTriangles;
  for (int attempt = 0; attempt < 5 && target < mesh.triangles.size(); ++attempt, target = target * 3 / 2) {
    // Attempt a's share of the stage is [1 - 2^-a, 1 - 2^-(a+1)] (most of it is the first, a later one is
    // rarer): its collapses the first four fifths, its self-intersection check the rest.
    const double begin = 1 - std::ldexp(1.0, -attempt), end = 1 - std::ldexp(1.0, -attempt - 1);
    const double collapsed = begin + 0.8 * (end - begin);
    progress.check(begin);
    Mesh m = cgal_bridge::toSurfaceMesh<K::Point_3>(mesh);
    SMS::GarlandHeckbert_plane_policies<Mesh, K> policies(m);
    // The stop predicate counts edges; a closed triangle mesh has 3F/2 edges.
    StopAtCountOrWhenAsked stop(target * 3 / 2, progress.part(begin, collapsed));
    SMS::edge_collapse(m, stop,
                       CGAL::parameters::get_cost(policies.get_cost())
                           .get_placement(policies.get_placement())
                           .filter(SMS::Bounded_normal_change_filter<>()));
    if (stop.asked()) throw RepairCancelled(progress.stage);
    m.collect_garbage();
    if (!CGAL::is_closed(m) || !CGAL::is_triangle_mesh(m)) continue;
    // The validation's count, stopped at the first pair: the same exact predicates as does_self_intersect,
    // but in slabs on both cores, and a cancel is seen between them (seconds at millions of triangles).
    TriangleMesh candidate = cgal_bridge::toTriangleMesh(m);
    if (countSelfIntersections(candidate, 1, progress.part(collapsed, end)) > 0) continue;
    mesh = std::move(candidate);
    return true;
  }
  return false;
}

}  // namespace reamsim
