#pragma once
// A TriangleMesh as VTK polydata (double points, triangle cells), for the views of the application and of
// its plugins. Header only: plugins link VTK themselves.
#include <vtkCellArray.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include "reamsim/mesh/TriangleMesh.h"

namespace reamsim::ui {

inline vtkSmartPointer<vtkPolyData> toPolyData(const TriangleMesh& m) {
  auto points = vtkSmartPointer<vtkPoints>::New();
  points->SetDataTypeToDouble();
  points->Allocate(static_cast<vtkIdType>(m.vertices.size()));
  for (const Vec3& p : m.vertices) points->InsertNextPoint(p.x, p.y, p.z);
  auto cells = vtkSmartPointer<vtkCellArray>::New();
  cells->AllocateEstimate(static_cast<vtkIdType>(m.triangles.size()), 3);
  for (const Triangle& t : m.triangles) {
    const vtkIdType ids[3] = {t[0], t[1], t[2]};
    cells->InsertNextCell(3, ids);
  }
  auto poly = vtkSmartPointer<vtkPolyData>::New();
  poly->SetPoints(points);
  poly->SetPolys(cells);
  return poly;
}

}  // namespace reamsim::ui
