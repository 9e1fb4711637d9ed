#pragma once
// BoneState → vtkPolyData for display, with what the views colour by:
//  - cell array "colour" (RGB): the bone colour, or the highlight colour on triangles the last cut made;
//  - point array "depth_mm": how far each vertex lies from the bone's initial surface (0 where the
//    initial surface is untouched), i.e. how deep the surface was removed there.
#include <vtkSmartPointer.h>

#include <QColor>
#include <cstddef>

#include "reamsim/core/BoneState.h"

class vtkPolyData;
class vtkStaticCellLocator;

namespace reamsim::ui {

class BoneSurfaceBuilder {
 public:
  BoneSurfaceBuilder();
  ~BoneSurfaceBuilder();
  void setInitial(const BoneState& initial);  // the reference for depth; call on every new bone

  struct Result {
    vtkSmartPointer<vtkPolyData> polyData;
    std::size_t freshTriangles = 0;
    double maxDepthMm = 0;
  };
  // `previous`: the state before the last cut (nullptr: nothing is highlighted).
  Result build(const BoneState& current, const BoneState* previous, const QColor& bone, const QColor& fresh,
               bool smoothNormals);

 private:
  BoneState initial_;
  vtkSmartPointer<vtkStaticCellLocator> locator_;  // on the initial surface, built on the first cut
};

}  // namespace reamsim::ui
