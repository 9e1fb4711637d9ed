// CGAL translation unit: whole-mesh exact Boolean difference (the reference path).
#include "ExactRationalFastPaths.h"  // before any CGAL kernel: see there
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/corefinement.h>
#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/helpers.h>

#include <chrono>
#include <stdexcept>

#include "reamsim/csg/ReferenceSubtractor.h"

namespace reamsim {
namespace {
using EK = CGAL::Exact_predicates_exact_constructions_kernel;
using ExactMesh = CGAL::Surface_mesh<EK::Point_3>;
using IK = CGAL::Exact_predicates_inexact_constructions_kernel;
using RoundedMesh = CGAL::Surface_mesh<IK::Point_3>;
namespace PMP = CGAL::Polygon_mesh_processing;

template <class Mesh>
Mesh build(const TriangleMesh& in) {
  Mesh out;
  std::vector<typename Mesh::Vertex_index> v;
  v.reserve(in.vertices.size());
  for (const Vec3& p : in.vertices) v.push_back(out.add_vertex(typename Mesh::Point(p.x, p.y, p.z)));
  for (const Triangle& t : in.triangles)
    if (out.add_face(v[t[0]], v[t[1]], v[t[2]]) == Mesh::null_face())
      throw std::invalid_argument("mesh is not a valid oriented 2-manifold (a face could not be added)");
  return out;
}

template <class Mesh>
TriangleMesh rounded(const Mesh& m) {
  TriangleMesh out;
  std::vector<std::uint32_t> id(m.num_vertices(), 0);
  for (auto v : m.vertices()) {
    id[v.idx()] = std::uint32_t(out.vertices.size());
    const auto& p = m.point(v);
    out.vertices.push_back({CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())});
  }
  for (auto f : m.faces()) {
    auto h = m.halfedge(f);
    out.triangles.push_back({id[m.target(h).idx()], id[m.target(m.next(h)).idx()], id[m.source(h).idx()]});
  }
  return out;
}

double roundedVolume(const ExactMesh& m) { return signedVolume(rounded(m)); }

// Collapses the lazy-evaluation history of every point into its exact value, so that the cost of the
// next cut does not grow with the number of cuts before it.
void settleExactCoordinates(ExactMesh& m) {
  for (auto v : m.vertices()) {
    const EK::Point_3& p = m.point(v);
    CGAL::exact(p.x());
    CGAL::exact(p.y());
    CGAL::exact(p.z());
  }
}

void requireSolid(const ExactMesh& m, const char* what) {
  if (!CGAL::is_triangle_mesh(m) || !CGAL::is_closed(m))
    throw std::invalid_argument(std::string(what) + " is not a closed triangle mesh");
  if (!PMP::is_outward_oriented(m)) throw std::invalid_argument(std::string(what) + " is not outward oriented");
}
}  // namespace

struct ReferenceSubtractor::Impl {
  ExactMesh bone;
  double volume = 0;
};

ReferenceSubtractor::ReferenceSubtractor(const TriangleMesh& bone) : impl_(std::make_unique<Impl>()) {
  impl_->bone = build<ExactMesh>(bone);
  requireSolid(impl_->bone, "bone");
  impl_->volume = signedVolume(bone);
}

ReferenceSubtractor::~ReferenceSubtractor() = default;
ReferenceSubtractor::ReferenceSubtractor(ReferenceSubtractor&&) noexcept = default;
ReferenceSubtractor& ReferenceSubtractor::operator=(ReferenceSubtractor&&) noexcept = default;

ReferenceCut ReferenceSubtractor::subtract(const TriangleMesh& toolMesh) {
  const auto start = std::chrono::steady_clock::now();
  ReferenceCut cut;
  cut.volumeBeforeMm3 = impl_->volume;
  ExactMesh tool = build<ExactMesh>(toolMesh);
  requireSolid(tool, "tool");
  ExactMesh boneCopy = impl_->bone;  // corefinement modifies its inputs; keep the state if it fails
  ExactMesh difference, intersection;
  std::array<boost::optional<ExactMesh*>, 4> outputs{};  // CGAL 5.5 takes boost::optional
  outputs[PMP::Corefinement::INTERSECTION] = &intersection;
  outputs[PMP::Corefinement::TM1_MINUS_TM2] = &difference;
  const auto ok = PMP::corefine_and_compute_boolean_operations(boneCopy, tool, outputs);
  if (!ok[PMP::Corefinement::TM1_MINUS_TM2] || !ok[PMP::Corefinement::INTERSECTION])
    throw std::runtime_error("CGAL could not compute the Boolean difference (non-manifold result)");

  cut.removedMm3 = intersection.is_empty() ? 0.0 : roundedVolume(intersection);
  cut.changed = intersection.number_of_faces() > 0;
  if (cut.changed) {
    settleExactCoordinates(difference);
    impl_->bone = std::move(difference);
    impl_->volume = roundedVolume(impl_->bone);
  }
  cut.volumeAfterMm3 = impl_->volume;
  cut.facesAfter = impl_->bone.number_of_faces();
  cut.milliseconds = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return cut;
}

TriangleMesh ReferenceSubtractor::mesh() const { return rounded(impl_->bone); }
double ReferenceSubtractor::volumeMm3() const { return impl_->volume; }
std::size_t ReferenceSubtractor::faceCount() const { return impl_->bone.number_of_faces(); }

BoneInvariants ReferenceSubtractor::checkInvariants() const {
  BoneInvariants inv;
  inv.closed = CGAL::is_closed(impl_->bone) && CGAL::is_triangle_mesh(impl_->bone);
  inv.outwardOriented = inv.closed && PMP::is_outward_oriented(impl_->bone);
  inv.selfIntersectsExact = PMP::does_self_intersect(impl_->bone);
  inv.selfIntersectsRounded = PMP::does_self_intersect(build<RoundedMesh>(mesh()));
  inv.newSelfIntersectionsExact = inv.selfIntersectsExact;
  inv.newSelfIntersectionsRounded = inv.selfIntersectsRounded;
  return inv;
}

}  // namespace reamsim
