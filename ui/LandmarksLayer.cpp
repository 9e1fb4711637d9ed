#include "LandmarksLayer.h"

#include <vtkActor.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderer.h>
#include <vtkSphereSource.h>

namespace reamsim::ui {
namespace {

constexpr double kColours[3][3] = {{0.90, 0.15, 0.15}, {0.15, 0.70, 0.25}, {0.20, 0.35, 0.95}};

}  // namespace

LandmarksLayer::LandmarksLayer(vtkRenderer* renderer) : renderer_(renderer) {
  for (std::size_t i = 0; i < actors_.size(); ++i) {
    spheres_[i] = vtkSmartPointer<vtkSphereSource>::New();
    spheres_[i]->SetThetaResolution(24);
    spheres_[i]->SetPhiResolution(16);
    auto mapper = vtkSmartPointer<vtkPolyDataMapper>::New();
    mapper->SetInputConnection(spheres_[i]->GetOutputPort());
    actors_[i] = vtkSmartPointer<vtkActor>::New();
    actors_[i]->SetMapper(mapper);
    actors_[i]->GetProperty()->SetColor(kColours[i][0], kColours[i][1], kColours[i][2]);
    actors_[i]->GetProperty()->SetSpecular(0.3);
    actors_[i]->SetVisibility(false);
    actors_[i]->PickableOff();
    renderer_->AddActor(actors_[i]);
  }
}

LandmarksLayer::~LandmarksLayer() {
  for (auto& actor : actors_) renderer_->RemoveActor(actor);
}

void LandmarksLayer::show(const ScapulaLandmarks& landmarks, double radiusMm) {
  for (ScapulaLandmark which : kScapulaLandmarks) {
    const std::size_t i = std::size_t(which);
    const std::optional<Vec3>& p = landmarks[which];
    actors_[i]->SetVisibility(p.has_value());
    if (!p) continue;
    spheres_[i]->SetCenter(p->x, p->y, p->z);
    spheres_[i]->SetRadius(radiusMm);
    spheres_[i]->Update();  // now, not inside the next render: the view's bone picture cache compares times first
  }
}

bool LandmarksLayer::shown(ScapulaLandmark which) const { return actors_[std::size_t(which)]->GetVisibility(); }

}  // namespace reamsim::ui
