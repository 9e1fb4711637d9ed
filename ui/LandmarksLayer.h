#pragma once
// The scapular landmarks in the main view: a small sphere at each placed point (glenoid centre red,
// trigonum scapulae green, inferior angle blue), in the bone's renderer so that they are hidden by the
// bone and the reamer as the bone itself is.
#include <vtkSmartPointer.h>

#include <array>

#include "reamsim/core/ScapulaLandmarks.h"

class vtkActor;
class vtkRenderer;
class vtkSphereSource;

namespace reamsim::ui {

class LandmarksLayer {
 public:
  explicit LandmarksLayer(vtkRenderer* renderer);
  ~LandmarksLayer();
  LandmarksLayer(const LandmarksLayer&) = delete;
  LandmarksLayer& operator=(const LandmarksLayer&) = delete;

  // Shows the placed points with spheres of `radiusMm`; the others are hidden.
  void show(const ScapulaLandmarks& landmarks, double radiusMm);
  bool shown(ScapulaLandmark which) const;

 private:
  vtkRenderer* renderer_;
  std::array<vtkSmartPointer<vtkSphereSource>, 3> spheres_;
  std::array<vtkSmartPointer<vtkActor>, 3> actors_;
};

}  // namespace reamsim::ui
