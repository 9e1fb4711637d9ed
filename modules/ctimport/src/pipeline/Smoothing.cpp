// Windowed-sinc surface smoothing (Taubin's non-shrinking low-pass, VTK), an exact volume correction by a
// common normal offset, and the local undo of any self-intersection the smoothing created in thin bone.
#include <vtkCellArray.h>
#include <vtkDoubleArray.h>
#include <vtkIdTypeArray.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkWindowedSincPolyDataFilter.h>

#include <cmath>

#include "Stages.h"
#include "reamsim/ctimport/SelfIntersections.h"

namespace reamsim::ct::detail {

TriangleMesh windowedSincSmooth(const TriangleMesh& mesh, int iterations, double passBand, const Tick& tick) {
  if (iterations <= 0) return mesh;
  auto coords = vtkSmartPointer<vtkDoubleArray>::New();
  coords->SetNumberOfComponents(3);
  coords->SetNumberOfTuples(vtkIdType(mesh.vertices.size()));
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    const Vec3& p = mesh.vertices[i];
    coords->SetTypedTuple(vtkIdType(i), std::array<double, 3>{p.x, p.y, p.z}.data());
  }
  auto points = vtkSmartPointer<vtkPoints>::New();
  points->SetData(coords);
  auto offsets = vtkSmartPointer<vtkIdTypeArray>::New();
  auto conn = vtkSmartPointer<vtkIdTypeArray>::New();
  offsets->SetNumberOfValues(vtkIdType(mesh.triangles.size() + 1));
  conn->SetNumberOfValues(vtkIdType(mesh.triangles.size() * 3));
  for (std::size_t t = 0; t <= mesh.triangles.size(); ++t) offsets->SetValue(vtkIdType(t), vtkIdType(3 * t));
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
    for (int k = 0; k < 3; ++k) conn->SetValue(vtkIdType(3 * t + std::size_t(k)), vtkIdType(mesh.triangles[t][std::size_t(k)]));
  auto cells = vtkSmartPointer<vtkCellArray>::New();
  cells->SetData(offsets, conn);
  auto poly = vtkSmartPointer<vtkPolyData>::New();
  poly->SetPoints(points);
  poly->SetPolys(cells);

  auto sinc = vtkSmartPointer<vtkWindowedSincPolyDataFilter>::New();
  sinc->SetInputData(poly);
  sinc->SetNumberOfIterations(iterations);
  sinc->SetPassBand(passBand);
  sinc->NormalizeCoordinatesOn();  // recommended: keeps the filter stable independent of scale
  sinc->BoundarySmoothingOff();
  sinc->FeatureEdgeSmoothingOff();
  sinc->NonManifoldSmoothingOn();
  sinc->Update();
  vtkPoints* out = sinc->GetOutput()->GetPoints();
  TriangleMesh smoothed = mesh;
  if (!out || out->GetNumberOfPoints() != vtkIdType(mesh.vertices.size())) return smoothed;
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    double p[3];
    out->GetPoint(vtkIdType(i), p);
    smoothed.vertices[i] = {p[0], p[1], p[2]};
  }
  if (tick) tick(1.0);
  return smoothed;
}

double restoreVolume(TriangleMesh& mesh, double targetVolume) {
  // Area-weighted vertex normals; d(volume)/d(offset) = area, so offset = ΔV / A (repeated for accuracy).
  double total = 0;
  for (int round = 0; round < 2; ++round) {
    const double volume = signedVolume(mesh), area = surfaceArea(mesh);
    if (!(area > 0)) return total;
    const double delta = (targetVolume - volume) / area;
    if (std::abs(delta) < 1e-12) break;
    std::vector<Vec3> normals(mesh.vertices.size());
    for (const Triangle& t : mesh.triangles) {
      const Vec3 n = cross(mesh.vertices[t[1]] - mesh.vertices[t[0]], mesh.vertices[t[2]] - mesh.vertices[t[0]]);
      for (int k = 0; k < 3; ++k) normals[t[std::size_t(k)]] += n;
    }
    for (std::size_t i = 0; i < mesh.vertices.size(); ++i) mesh.vertices[i] += normalized(normals[i]) * delta;
    total += delta;
  }
  return total;
}

std::size_t restoreWhereSelfIntersecting(TriangleMesh& mesh, const TriangleMesh& reference, bool& everything,
                                         SelfIntersectionResult& finalCheck, const Tick& tick) {
  everything = false;
  SelfIntersectionResult r = findSelfIntersections(mesh, 100000);
  if (r.pairs.empty() && r.degenerateFaces.empty()) {
    finalCheck = std::move(r);
    return 0;
  }
  // Vertex → faces, to grow the restored region by one ring and to find the faces to re-check.
  const std::size_t nv = mesh.vertices.size(), nt = mesh.triangles.size();
  std::vector<std::uint32_t> start(nv + 1, 0), faces(nt * 3);
  for (const Triangle& t : mesh.triangles)
    for (std::uint32_t v : t) ++start[v + 1];
  for (std::size_t v = 0; v < nv; ++v) start[v + 1] += start[v];
  {
    std::vector<std::uint32_t> fill(start.begin(), start.end() - 1);
    for (std::size_t f = 0; f < nt; ++f)
      for (std::uint32_t v : mesh.triangles[f]) faces[fill[v]++] = std::uint32_t(f);
  }
  std::vector<std::uint8_t> restored(nv, 0);
  std::size_t count = 0;
  for (int pass = 0; pass < 12; ++pass) {
    // Degenerate faces (a sliver crushed flat by smoothing) are treated like intersecting ones.
    std::vector<std::uint32_t> bad = r.degenerateFaces;
    for (const auto& [a, b] : r.pairs) {
      bad.push_back(a);
      bad.push_back(b);
    }
    if (bad.empty()) {
      // Complete: every pair not re-searched involves two unchanged faces, clean in the first full search
      // (the faces of its bad pairs were all re-searched); degenerate faces are always searched in full.
      finalCheck = std::move(r);
      return count;
    }
    // The vertices of the bad faces and one ring around them, one more ring each further pass.
    std::vector<std::uint8_t> mark(nv, 0);
    for (std::uint32_t f : bad)
      for (std::uint32_t v : mesh.triangles[f]) mark[v] = 1;
    for (int ring = 0; ring < std::min(pass + 1, 4); ++ring) {
      std::vector<std::uint8_t> grown = mark;
      for (std::size_t v = 0; v < nv; ++v)
        if (mark[v])
          for (std::uint32_t k = start[v]; k < start[v + 1]; ++k)
            for (std::uint32_t w : mesh.triangles[faces[k]]) grown[w] = 1;
      mark.swap(grown);
    }
    std::vector<std::uint8_t> recheck(nt, 0);
    for (std::size_t v = 0; v < nv; ++v) {
      if (!mark[v]) continue;
      if (!restored[v]) {
        restored[v] = 1;
        ++count;
        mesh.vertices[v] = reference.vertices[v];
      }
      for (std::uint32_t k = start[v]; k < start[v + 1]; ++k) recheck[faces[k]] = 1;
    }
    r = findSelfIntersections(mesh, 100000, &recheck);
    if (tick) tick(std::min(1.0, (pass + 1) / 12.0));
  }
  mesh.vertices = reference.vertices;
  everything = true;
  finalCheck = findSelfIntersections(mesh, 100000);
  return nv;
}

}  // namespace reamsim::ct::detail
