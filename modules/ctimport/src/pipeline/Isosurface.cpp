// Flying edges (VTK, multithreaded) on the padded field at 0, in index space; vertices are then placed
// in patient space with the volume's spacing, direction and origin (VTK 9.1's filters ignore direction).
#include <vtkCellArray.h>
#include <vtkCellArrayIterator.h>
#include <vtkFlyingEdges3D.h>
#include <vtkFloatArray.h>
#include <vtkImageData.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include <stdexcept>

#include "Stages.h"

namespace reamsim::ct::detail {

TriangleMesh extractIsosurface(const PaddedField& field, const CtVolume& volume, const Tick& tick) {
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(field.dims[0], field.dims[1], field.dims[2]);
  auto scalars = vtkSmartPointer<vtkFloatArray>::New();
  // Borrow the field's memory (save = 1: VTK must not free it).
  scalars->SetArray(const_cast<float*>(field.values.data()), vtkIdType(field.values.size()), 1);
  image->GetPointData()->SetScalars(scalars);

  auto fe = vtkSmartPointer<vtkFlyingEdges3D>::New();
  fe->SetInputData(image);
  fe->SetValue(0, 0.0);
  fe->ComputeNormalsOff();
  fe->ComputeGradientsOff();
  fe->ComputeScalarsOff();
  fe->InterpolateAttributesOff();
  fe->Update();
  if (tick) tick(0.7);
  vtkPolyData* out = fe->GetOutput();

  TriangleMesh mesh;
  vtkPoints* points = out->GetPoints();
  const vtkIdType np = points ? points->GetNumberOfPoints() : 0;
  if (np == 0) throw std::runtime_error("the isosurface is empty");
  mesh.vertices.resize(std::size_t(np));
  for (vtkIdType i = 0; i < np; ++i) {
    double p[3];
    points->GetPoint(i, p);
    mesh.vertices[std::size_t(i)] = volume.indexToWorld(p[0] - 1, p[1] - 1, p[2] - 1);
  }
  vtkCellArray* polys = out->GetPolys();
  mesh.triangles.reserve(std::size_t(polys->GetNumberOfCells()));
  auto it = vtk::TakeSmartPointer(polys->NewIterator());
  for (it->GoToFirstCell(); !it->IsDoneWithTraversal(); it->GoToNextCell()) {
    vtkIdType n;
    const vtkIdType* ids;
    it->GetCurrentCell(n, ids);
    if (n != 3) throw std::runtime_error("flying edges produced a non-triangle cell");
    mesh.triangles.push_back({std::uint32_t(ids[0]), std::uint32_t(ids[1]), std::uint32_t(ids[2])});
  }
  // Orientation depends on the handedness of the volume's axes: make it outward.
  if (signedVolume(mesh) < 0)
    for (Triangle& t : mesh.triangles) std::swap(t[1], t[2]);
  if (tick) tick(1.0);
  return mesh;
}

}  // namespace reamsim::ct::detail
