#pragma once
// The document's other bones (CT import "beside the current one") in the main view. They are shown
// only: the reamer cuts the session's bone. Kept apart from BoneView, which draws the cut bone.
#include <QPointer>
#include <cstddef>
#include <cstdint>
#include <unordered_map>
#include <vtkSmartPointer.h>

#include "reamsim/core/Document.h"

class vtkActor;

namespace reamsim::ui {

class BoneView;

class OtherBonesLayer {
 public:
  // `mainBone`: the session's bone, drawn by BoneView itself.
  OtherBonesLayer(Document& document, NodeId mainBone, BoneView& view);
  ~OtherBonesLayer();
  OtherBonesLayer(const OtherBonesLayer&) = delete;
  OtherBonesLayer& operator=(const OtherBonesLayer&) = delete;

  std::size_t shownBones() const { return shown_.size(); }
  std::size_t shownTriangles() const;
  void fitViewToAll();  // camera around every bone, e.g. after adding one beside

 private:
  void sync();

  struct Shown {
    vtkSmartPointer<vtkActor> actor;
    std::uint64_t revision = 0;
    std::size_t triangles = 0;
  };
  Document& document_;
  NodeId mainBone_;
  QPointer<BoneView> view_;
  std::unordered_map<NodeId, Shown> shown_;
  Subscription subscription_;
};

}  // namespace reamsim::ui
