#pragma once
// The bone's planning in the main view: a small sphere at each placed landmark (glenoid centre red,
// trigonum scapulae green, inferior angle blue), the planned reaming axis as a thin yellow rod through the
// glenoid centre and the glenoid face's own direction (as opened, reamsim/ream/GlenoidFace.h) as a thinner cyan
// rod out of it, in the bone's renderer so that they are hidden by the bone and the reamer as the bone is.
#include <vtkSmartPointer.h>

#include <array>

#include <optional>

#include "reamsim/core/Pose.h"
#include "reamsim/core/ScapulaLandmarks.h"

class vtkActor;
class vtkRenderer;
class vtkLineSource;
class vtkSphereSource;
class vtkTubeFilter;

namespace reamsim::ui {

class LandmarksLayer {
 public:
  explicit LandmarksLayer(vtkRenderer* renderer);
  ~LandmarksLayer();
  LandmarksLayer(const LandmarksLayer&) = delete;
  LandmarksLayer& operator=(const LandmarksLayer&) = delete;

  // Shows the placed points with spheres of `radiusMm` (the others hidden), the planned axis, if any, as a
  // rod of a fifth of that radius from 40 mm out of the bone to 10 mm into it, and the glenoid face's outward
  // direction, if given (and the glenoid centre placed), as a rod of a seventh of it from the centre 30 mm out.
  void show(const ScapulaLandmarks& landmarks, const std::optional<Pose>& plannedAxis,
            const std::optional<Vec3>& glenoidOutward, double radiusMm);
  bool shown(ScapulaLandmark which) const;
  bool plannedAxisShown() const;
  std::optional<Vec3> glenoidAxisShown() const;  // the direction drawn, if drawn

 private:
  void addRod(vtkSmartPointer<vtkLineSource>& line, vtkSmartPointer<vtkTubeFilter>& tube, vtkSmartPointer<vtkActor>& actor,
              double r, double g, double b);

  vtkRenderer* renderer_;
  std::array<vtkSmartPointer<vtkSphereSource>, 3> spheres_;
  std::array<vtkSmartPointer<vtkActor>, 3> actors_;
  vtkSmartPointer<vtkLineSource> axisLine_;
  vtkSmartPointer<vtkTubeFilter> axisTube_;
  vtkSmartPointer<vtkActor> axisActor_;
  vtkSmartPointer<vtkLineSource> glenoidLine_;
  vtkSmartPointer<vtkTubeFilter> glenoidTube_;
  vtkSmartPointer<vtkActor> glenoidActor_;
  std::optional<Vec3> glenoidShown_;
};

}  // namespace reamsim::ui
