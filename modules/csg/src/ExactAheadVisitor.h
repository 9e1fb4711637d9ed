// A corefinement visitor that evaluates the intersection points exactly on a second thread while CGAL
// triangulates the split faces on the first. Include only from a CGAL unit (CgalLocalSubtractor.cpp).
//
// Why: nearly every intersection point of a reaming cut is evaluated exactly (the filters fail where the
// new cap's facets cross the old cavity's nearly coplanar ones), and that evaluation was a quarter of the
// corefinement, all on one thread while the other core idled. The points are lazy Epeck objects whose
// exact evaluation is thread-safe (std::call_once per object in CGAL's Lazy_rep; reference counts are
// atomic), so a helper can evaluate them ahead of the triangulation, which then finds them done.
//
// The helper walks the points from the back, the main thread (when it needs one) in the triangulation's
// order and, after triangulating, from the front: they meet somewhere in between. (Tried: the helper in the
// triangulation's own order, replaying CGAL's unordered_map of faces; no faster, since the main thread
// then waits for each point the helper is on.)
//
// Every collected point is evaluated before the corefinement returns, by whichever thread gets there
// first, so the outcome does not depend on timing: an exact evaluation tightens a point's interval, and
// the rounded coordinates downstream are read from that interval.
#pragma once

#include <CGAL/Polygon_mesh_processing/corefinement.h>

#include <atomic>
#include <cstddef>
#include <memory>
#include <vector>

#include "BackgroundTask.h"

namespace reamsim::csg_detail {

template <class Mesh>
class ExactAheadVisitor : public CGAL::Polygon_mesh_processing::Corefinement::Default_visitor<Mesh> {
 public:
  using Point = typename Mesh::Point;
  using Vertex = typename Mesh::Vertex_index;

  // Below this many points the thread costs more (~50 µs to start) than it saves.
  static constexpr std::size_t kMinimumPoints = 64;

  ExactAheadVisitor() : state_(std::make_shared<State>()) {}

  // CGAL copies the visitor; the copies share one state. CGAL calls these as const members.
  void new_vertex_added(std::size_t, Vertex v, const Mesh& mesh) const {
    State& s = *state_;
    // Vertices added while faces are triangulated are nodes already collected from the edge they split
    // (every intersection point lies on an edge of one of the meshes).
    if (!s.triangulating) s.points.push_back(mesh.point(v));
  }

  void start_triangulating_faces(std::size_t) const {
    State& s = *state_;
    s.triangulating = true;
    if (s.points.size() < kMinimumPoints) return;
    s.helper = csg::inBackground([&s] {
      for (std::size_t i = s.points.size(); i-- > 0;) {
        if (s.finishing.load(std::memory_order_relaxed)) break;
        (void)CGAL::exact(s.points[i]);
      }
    });
  }

  void end_triangulating_faces() const {
    State& s = *state_;
    s.finishing.store(true, std::memory_order_relaxed);
    // Whatever the helper has not reached is evaluated here; call_once makes a
    // point the helper did, or is doing, cost nothing more than a wait.
    for (const Point& p : s.points) (void)CGAL::exact(p);
    if (s.helper.valid()) s.helper.get();
  }

 private:
  struct State {
    std::vector<Point> points;  // every intersection point (twice if it split an edge of each mesh)
    bool triangulating = false;
    std::atomic<bool> finishing{false};
    csg::BackgroundTask<void> helper;
    ~State() {
      finishing.store(true);
      if (helper.valid()) helper.wait();  // an exception in the corefinement must not leave it running
    }
  };
  std::shared_ptr<State> state_;
};

}  // namespace reamsim::csg_detail
