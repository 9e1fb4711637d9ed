#include "ThesisInteractorStyle.h"

#include <vtkCallbackCommand.h>
#include <vtkCamera.h>
#include <vtkInteractorObserver.h>
#include <vtkObjectFactory.h>
#include <vtkRenderWindowInteractor.h>
#include <vtkRenderer.h>

namespace reamsim::ui {

vtkStandardNewMacro(ThesisInteractorStyle);

void ThesisInteractorStyle::OnLeftButtonDown() {
  if (pickAt && pickAt(Interactor->GetEventPosition()[0], Interactor->GetEventPosition()[1])) return;
  Vec3 tip, axis;
  if (Interactor->GetControlKey() && reamerAxis && dragAlongAxis && reamerAxis(tip, axis)) {
    FindPokedRenderer(Interactor->GetEventPosition()[0], Interactor->GetEventPosition()[1]);
    if (CurrentRenderer) {
      dragging_ = true;
      Interactor->GetEventPosition(last_);
      return;
    }
  }
  Superclass::OnLeftButtonDown();
}

void ThesisInteractorStyle::OnLeftButtonUp() {
  if (dragging_) {
    dragging_ = false;
    return;
  }
  Superclass::OnLeftButtonUp();
}

// The drag is projected on the reamer axis as drawn on screen: moving the mouse along the drawn axis
// by the axis's on-screen length of 1 mm moves the reamer 1 mm. When the axis points at the viewer,
// vertical mouse motion is used with the view's scale.
void ThesisInteractorStyle::OnMouseMove() {
  if (!dragging_) {
    Superclass::OnMouseMove();
    return;
  }
  int now[2];
  Interactor->GetEventPosition(now);
  const double dx = now[0] - last_[0], dy = now[1] - last_[1];
  last_[0] = now[0];
  last_[1] = now[1];
  Vec3 tip, axis;
  if (!CurrentRenderer || !reamerAxis(tip, axis)) return;
  double a[3], b[3];
  vtkInteractorObserver::ComputeWorldToDisplay(CurrentRenderer, tip.x, tip.y, tip.z, a);
  vtkInteractorObserver::ComputeWorldToDisplay(CurrentRenderer, tip.x + axis.x, tip.y + axis.y, tip.z + axis.z, b);
  const double ax = b[0] - a[0], ay = b[1] - a[1], len2 = ax * ax + ay * ay;
  double mm = 0;
  if (len2 > 0.25) {
    mm = (dx * ax + dy * ay) / len2;
  } else {
    const int* size = CurrentRenderer->GetSize();
    mm = -dy * 2 * CurrentRenderer->GetActiveCamera()->GetParallelScale() / std::max(1, size[1]);
  }
  if (mm != 0) dragAlongAxis(mm);
}

void ThesisInteractorStyle::OnMiddleButtonDown() {
  FindPokedRenderer(Interactor->GetEventPosition()[0], Interactor->GetEventPosition()[1]);
  if (!CurrentRenderer) return;
  GrabFocus(EventCallbackCommand);
  StartDolly();
}

void ThesisInteractorStyle::OnMiddleButtonUp() {
  EndDolly();
  if (Interactor) ReleaseFocus();
}

void ThesisInteractorStyle::OnRightButtonDown() {
  FindPokedRenderer(Interactor->GetEventPosition()[0], Interactor->GetEventPosition()[1]);
  if (!CurrentRenderer) return;
  GrabFocus(EventCallbackCommand);
  StartPan();
}

void ThesisInteractorStyle::OnRightButtonUp() {
  EndPan();
  if (Interactor) ReleaseFocus();
}

}  // namespace reamsim::ui
