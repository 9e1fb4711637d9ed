#include "reamsim/mesh/Validation.h"

#include <cstdio>
#include "ReportJson.h"
#include <sstream>

namespace reamsim {

ValidationReport validateMesh(const TriangleMesh& mesh, const ValidationOptions& options) {
  ValidationReport r;
  r.vertices = mesh.vertices.size();
  r.triangles = mesh.triangles.size();
  r.topology = analyzeEdges(mesh);
  r.closed = r.topology.closed() && !mesh.empty();
  r.consistentlyOriented = r.topology.consistentlyOriented();
  r.areaMm2 = surfaceArea(mesh);
  r.bounds = computeBounds(mesh);
  if (r.closed && r.consistentlyOriented) {
    const double v = signedVolume(mesh);
    r.outwardOriented = v > 0;
    r.volumeMm3 = std::abs(v);
  }
  r.coincidentVertices = countCoincidentVertices(mesh);
  // With coincident vertices the count runs twice (as read, then merged): each gets half the progress.
  const bool twice = r.coincidentVertices > 0;
  const StageProgress first = options.progress.part(0, twice ? 0.5 : 1), second = options.progress.part(0.5, 1);
  if (options.checkSelfIntersections)
    r.selfIntersectingPairs = countSelfIntersections(mesh, options.maxSelfIntersectionPairs, first);
  if (r.coincidentVertices > 0) {
    const TriangleMesh merged = mergeCoincidentVertices(mesh);
    const EdgeTopology t = analyzeEdges(merged);
    ValidationReport::AfterMerging a;
    a.boundaryEdges = t.boundaryEdges;
    a.nonManifoldEdges = t.nonManifoldEdges;
    if (options.checkSelfIntersections)
      a.selfIntersectingPairs = countSelfIntersections(merged, options.maxSelfIntersectionPairs, second);
    r.afterMergingCoincident = a;
  }
  return r;
}

std::string toText(const ValidationReport& r) {
  std::ostringstream out;
  const auto yesNo = [](bool b) { return b ? "yes" : "no"; };
  out << "vertices:               " << r.vertices << "\n"
      << "triangles:              " << r.triangles << "\n"
      << "closed:                 " << yesNo(r.closed) << "\n"
      << "boundary edges:         " << r.topology.boundaryEdges << "\n"
      << "non-manifold edges:     " << r.topology.nonManifoldEdges << "\n"
      << "consistently oriented:  " << yesNo(r.consistentlyOriented) << " (" << r.topology.inconsistentEdges
      << " edges with mismatched orientation)\n"
      << "outward oriented:       " << yesNo(r.outwardOriented) << "\n"
      << "self-intersecting pairs: "
      << (r.selfIntersectingPairs ? std::to_string(*r.selfIntersectingPairs) : std::string("not checked")) << "\n"
      << "degenerate faces:       " << r.topology.degenerateFaces << "\n"
      << "connected components:   " << r.topology.connectedComponents << "\n"
      << "isolated vertices:      " << r.topology.isolatedVertices << "\n"
      << "coincident vertices:    " << r.coincidentVertices;
  if (r.afterMergingCoincident) {
    const auto& a = *r.afterMergingCoincident;
    out << " (same position, another index); merged: " << a.boundaryEdges << " boundary edges, "
        << a.nonManifoldEdges << " non-manifold edges, "
        << (a.selfIntersectingPairs ? std::to_string(*a.selfIntersectingPairs) : std::string("unchecked"))
        << " self-intersecting pairs (`repair` merges them)";
  }
  out << "\n";
  char buf[256];
  if (r.volumeMm3) {
    std::snprintf(buf, sizeof buf, "volume:                 %.3f mm3 (%.3f cm3)\n", *r.volumeMm3, *r.volumeMm3 / 1000);
    out << buf;
  } else {
    out << "volume:                 undefined (not a closed, consistently oriented surface)\n";
  }
  std::snprintf(buf, sizeof buf, "area:                   %.3f mm2\n", r.areaMm2);
  out << buf;
  if (!r.bounds.empty()) {
    std::snprintf(buf, sizeof buf, "bounds (mm):            x %.3f..%.3f  y %.3f..%.3f  z %.3f..%.3f\n", r.bounds.min.x,
                  r.bounds.max.x, r.bounds.min.y, r.bounds.max.y, r.bounds.min.z, r.bounds.max.z);
    out << buf;
  }
  return out.str();
}

nlohmann::json toJsonValue(const ValidationReport& r) {
  nlohmann::json j;
  j["vertices"] = r.vertices;
  j["triangles"] = r.triangles;
  j["closed"] = r.closed;
  j["boundary_edges"] = r.topology.boundaryEdges;
  j["non_manifold_edges"] = r.topology.nonManifoldEdges;
  j["consistently_oriented"] = r.consistentlyOriented;
  j["inconsistent_edges"] = r.topology.inconsistentEdges;
  j["outward_oriented"] = r.outwardOriented;
  j["self_intersecting_pairs"] =
      r.selfIntersectingPairs ? nlohmann::json(*r.selfIntersectingPairs) : nlohmann::json(nullptr);
  j["degenerate_faces"] = r.topology.degenerateFaces;
  j["connected_components"] = r.topology.connectedComponents;
  j["isolated_vertices"] = r.topology.isolatedVertices;
  j["coincident_vertices"] = r.coincidentVertices;
  if (r.afterMergingCoincident) {
    const auto& a = *r.afterMergingCoincident;
    j["after_merging_coincident"] = {
        {"boundary_edges", a.boundaryEdges},
        {"non_manifold_edges", a.nonManifoldEdges},
        {"self_intersecting_pairs",
         a.selfIntersectingPairs ? nlohmann::json(*a.selfIntersectingPairs) : nlohmann::json(nullptr)}};
  }
  j["volume_mm3"] = r.volumeMm3 ? nlohmann::json(*r.volumeMm3) : nlohmann::json(nullptr);
  j["area_mm2"] = r.areaMm2;
  if (!r.bounds.empty())
    j["bounds_mm"] = {{"min", {r.bounds.min.x, r.bounds.min.y, r.bounds.min.z}},
                      {"max", {r.bounds.max.x, r.bounds.max.y, r.bounds.max.z}}};
  return j;
}

std::string toJson(const ValidationReport& r, int indent) { return toJsonValue(r).dump(indent); }

}  // namespace reamsim
