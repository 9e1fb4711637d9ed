#pragma once
// The live surface preview: a low-resolution bone surface (ct::previewSurface) in an orthographic VTK
// view, with the volume's box for orientation. The camera is set when a volume comes in and then left
// to the user while the threshold moves.
#include <QVTKOpenGLNativeWidget.h>
#include <vtkSmartPointer.h>

#include "reamsim/ctimport/CtVolume.h"
#include "reamsim/mesh/TriangleMesh.h"

class vtkActor;
class vtkPolyDataMapper;
class vtkRenderer;

namespace reamsim::ui::ct_import {

class SurfacePreview : public QVTKOpenGLNativeWidget {
  Q_OBJECT
 public:
  explicit SurfacePreview(QWidget* parent = nullptr);
  ~SurfacePreview() override;

  // The volume's box, in `meshSpace` (the frame the surfaces will come in); views it from the front.
  void setVolume(const ct::CtVolume& volume, ct::PatientSpace meshSpace);
  void setSurface(const TriangleMesh& mesh);
  void clearSurface();
  std::size_t faces() const { return faces_; }

 protected:
  void resizeEvent(QResizeEvent* e) override;
  void mousePressEvent(QMouseEvent* e) override;
  void wheelEvent(QWheelEvent* e) override;

 private:
  void resetCamera();
  void renderLater();

  vtkSmartPointer<vtkRenderer> renderer_;
  vtkSmartPointer<vtkActor> surface_, outline_;
  vtkSmartPointer<vtkPolyDataMapper> surfaceMapper_, outlineMapper_;
  ct::PatientSpace space_ = ct::PatientSpace::Unspecified;
  std::size_t faces_ = 0;
  bool renderPending_ = false;
  bool autoFit_ = true;  // refit the camera on resize until the user moves it
};

}  // namespace reamsim::ui::ct_import
