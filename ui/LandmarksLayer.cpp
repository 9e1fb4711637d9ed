#include "LandmarksLayer.h"

#include <vtkActor.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderer.h>
#include <vtkLineSource.h>
#include <vtkSphereSource.h>
#include <vtkTubeFilter.h>

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
  addRod(axisLine_, axisTube_, axisActor_, 0.95, 0.80, 0.10);
  addRod(glenoidLine_, glenoidTube_, glenoidActor_, 0.10, 0.80, 0.90);
}

void LandmarksLayer::addRod(vtkSmartPointer<vtkLineSource>& line, vtkSmartPointer<vtkTubeFilter>& tube,
                            vtkSmartPointer<vtkActor>& actor, double r, double g, double b) {
  line = vtkSmartPointer<vtkLineSource>::New();
  tube = vtkSmartPointer<vtkTubeFilter>::New();
  tube->SetInputConnection(line->GetOutputPort());
  tube->SetNumberOfSides(12);
  auto mapper = vtkSmartPointer<vtkPolyDataMapper>::New();
  mapper->SetInputConnection(tube->GetOutputPort());
  actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  actor->GetProperty()->SetColor(r, g, b);
  actor->SetVisibility(false);
  actor->PickableOff();
  renderer_->AddActor(actor);
}

LandmarksLayer::~LandmarksLayer() {
  for (auto& actor : actors_) renderer_->RemoveActor(actor);
  renderer_->RemoveActor(axisActor_);
  renderer_->RemoveActor(glenoidActor_);
}

void LandmarksLayer::show(const ScapulaLandmarks& landmarks, const std::optional<Pose>& plannedAxis,
                          const std::optional<Vec3>& glenoidOutward, double radiusMm) {
  const std::optional<Vec3>& centre = landmarks[ScapulaLandmark::GlenoidCentre];
  glenoidShown_ = centre && glenoidOutward ? glenoidOutward : std::nullopt;
  glenoidActor_->SetVisibility(glenoidShown_.has_value());
  if (glenoidShown_) {
    const Vec3 out = *centre + *glenoidShown_ * 30.0;
    glenoidLine_->SetPoint1(centre->x, centre->y, centre->z);
    glenoidLine_->SetPoint2(out.x, out.y, out.z);
    glenoidTube_->SetRadius(radiusMm / 7);
    glenoidTube_->Update();
  }
  axisActor_->SetVisibility(plannedAxis.has_value());
  if (plannedAxis) {
    const Vec3 out = plannedAxis->tip - plannedAxis->axis * 40.0, in = plannedAxis->tip + plannedAxis->axis * 10.0;
    axisLine_->SetPoint1(out.x, out.y, out.z);
    axisLine_->SetPoint2(in.x, in.y, in.z);
    axisTube_->SetRadius(0.2 * radiusMm);
    axisTube_->Update();  // now, as the spheres below
  }
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

bool LandmarksLayer::plannedAxisShown() const { return axisActor_->GetVisibility(); }

std::optional<Vec3> LandmarksLayer::glenoidAxisShown() const { return glenoidShown_; }

bool LandmarksLayer::shown(ScapulaLandmark which) const { return actors_[std::size_t(which)]->GetVisibility(); }

}  // namespace reamsim::ui
