#pragma once
// Mouse as in the thesis: left rotates (trackball), wheel and middle zoom, right pans. Ctrl + left drag
// moves the reamer along its own axis. VTK's own key bindings are switched off: keys are the main
// window's (remappable) actions.
#include <vtkInteractorStyleTrackballCamera.h>

#include <functional>

#include "reamsim/mesh/Vec3.h"

namespace reamsim::ui {

class ThesisInteractorStyle : public vtkInteractorStyleTrackballCamera {
 public:
  static ThesisInteractorStyle* New();
  vtkTypeMacro(ThesisInteractorStyle, vtkInteractorStyleTrackballCamera)

  // Where the reamer is (for projecting its axis to the screen) and what to do with a drag (mm along
  // the axis, positive = feed).
  std::function<bool(Vec3& tip, Vec3& axis)> reamerAxis;
  std::function<void(double mm)> dragAlongAxis;
  // A left click at display point (x, y) (pixels, origin bottom left) offered first to a pick (a landmark
  // being placed): true when it took the click, which then neither rotates nor drags.
  std::function<bool(int x, int y)> pickAt;

  void OnLeftButtonDown() override;
  void OnLeftButtonUp() override;
  void OnMouseMove() override;
  void OnMiddleButtonDown() override;
  void OnMiddleButtonUp() override;
  void OnRightButtonDown() override;
  void OnRightButtonUp() override;
  void OnChar() override {}
  void OnKeyPress() override {}
  void OnKeyRelease() override {}

 private:
  bool dragging_ = false;
  int last_[2] = {0, 0};
};

}  // namespace reamsim::ui
