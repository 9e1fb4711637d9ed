#include "SurfacePreview.h"

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkCellArray.h>
#include <vtkGenericOpenGLRenderWindow.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkPolyDataNormals.h>
#include <vtkProperty.h>
#include <vtkRenderer.h>

#include <QTimer>

#include "reamsim/ui/MeshPolyData.h"

namespace reamsim::ui::ct_import {

SurfacePreview::SurfacePreview(QWidget* parent) : QVTKOpenGLNativeWidget(parent) {
  setObjectName("SurfacePreview");
  auto window = vtkSmartPointer<vtkGenericOpenGLRenderWindow>::New();
  window->SetMultiSamples(0);  // software rasterisers (llvmpipe) pay dearly for multisampling
  setRenderWindow(window);
  renderer_ = vtkSmartPointer<vtkRenderer>::New();
  renderer_->SetBackground(0.11, 0.12, 0.14);
  renderer_->GetActiveCamera()->ParallelProjectionOn();  // orthographic, as the main view: true sizes
  window->AddRenderer(renderer_);

  surfaceMapper_ = vtkSmartPointer<vtkPolyDataMapper>::New();
  surfaceMapper_->ScalarVisibilityOff();
  surface_ = vtkSmartPointer<vtkActor>::New();
  surface_->SetMapper(surfaceMapper_);
  surface_->GetProperty()->SetColor(0.93, 0.89, 0.80);
  surface_->SetVisibility(false);
  outlineMapper_ = vtkSmartPointer<vtkPolyDataMapper>::New();
  outline_ = vtkSmartPointer<vtkActor>::New();
  outline_->SetMapper(outlineMapper_);
  outline_->GetProperty()->SetColor(0.45, 0.65, 0.9);
  outline_->SetVisibility(false);
  renderer_->AddActor(surface_);
  renderer_->AddActor(outline_);
}

SurfacePreview::~SurfacePreview() = default;

void SurfacePreview::setVolume(const ct::CtVolume& v, ct::PatientSpace meshSpace) {
  space_ = meshSpace;
  // The box through the outer voxel centres, as the surface's caps sit there (docs/CT_IMPORT.md).
  auto points = vtkSmartPointer<vtkPoints>::New();
  for (int c = 0; c < 8; ++c) {
    const Vec3 w = v.indexToWorld(c & 1 ? v.dims[0] - 1 : 0, c & 2 ? v.dims[1] - 1 : 0, c & 4 ? v.dims[2] - 1 : 0);
    const Vec3 p = ct::convertPoint(w, v.space, meshSpace);
    points->InsertNextPoint(p.x, p.y, p.z);
  }
  auto lines = vtkSmartPointer<vtkCellArray>::New();
  for (int a = 0; a < 8; ++a)
    for (int bit : {1, 2, 4})
      if (!(a & bit)) {
        const vtkIdType ids[2] = {a, a | bit};
        lines->InsertNextCell(2, ids);
      }
  auto box = vtkSmartPointer<vtkPolyData>::New();
  box->SetPoints(points);
  box->SetLines(lines);
  outlineMapper_->SetInputData(box);
  outline_->SetVisibility(true);
  clearSurface();
  autoFit_ = true;
  resetCamera();
}

void SurfacePreview::setSurface(const TriangleMesh& mesh) {
  auto normals = vtkSmartPointer<vtkPolyDataNormals>::New();
  normals->SetInputData(toPolyData(mesh));
  normals->SplittingOff();
  normals->ConsistencyOff();  // the pipeline's surfaces are outward oriented
  normals->Update();
  surfaceMapper_->SetInputData(normals->GetOutput());
  surface_->SetVisibility(!mesh.triangles.empty());
  faces_ = mesh.triangles.size();
  renderLater();
}

void SurfacePreview::clearSurface() {
  surface_->SetVisibility(false);
  faces_ = 0;
  renderLater();
}

// From the front (the patient facing the viewer), superior up; a volume without a frame: along -k.
void SurfacePreview::resetCamera() {
  vtkCamera* cam = renderer_->GetActiveCamera();
  cam->SetFocalPoint(0, 0, 0);
  const double front = space_ == ct::PatientSpace::RAS ? 1 : -1;  // anterior: +y in RAS, -y in LPS
  if (space_ == ct::PatientSpace::Unspecified) {
    cam->SetPosition(0, 0, 1);
    cam->SetViewUp(0, 1, 0);
  } else {
    cam->SetPosition(0, front, 0);
    cam->SetViewUp(0, 0, 1);
  }
  renderer_->ResetCamera(outline_->GetBounds());
  renderLater();
}

// VTK fits the parallel scale to the aspect ratio of the moment: refit while the layout settles, until
// the user takes the camera.
void SurfacePreview::resizeEvent(QResizeEvent* e) {
  QVTKOpenGLNativeWidget::resizeEvent(e);
  if (autoFit_ && outline_->GetVisibility()) resetCamera();
}

void SurfacePreview::mousePressEvent(QMouseEvent* e) {
  autoFit_ = false;
  QVTKOpenGLNativeWidget::mousePressEvent(e);
}

void SurfacePreview::wheelEvent(QWheelEvent* e) {
  autoFit_ = false;
  QVTKOpenGLNativeWidget::wheelEvent(e);
}

void SurfacePreview::renderLater() {
  if (renderPending_) return;
  renderPending_ = true;
  QTimer::singleShot(0, this, [this] {
    renderPending_ = false;
    renderer_->ResetCameraClippingRange();
    renderWindow()->Render();
  });
}

}  // namespace reamsim::ui::ct_import
