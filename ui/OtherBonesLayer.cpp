#include "OtherBonesLayer.h"

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkPolyDataNormals.h>
#include <vtkProperty.h>
#include <vtkRenderer.h>

#include "BoneView.h"
#include "reamsim/core/BoneNode.h"
#include "reamsim/ui/MeshPolyData.h"

namespace reamsim::ui {
namespace {

vtkSmartPointer<vtkActor> makeActor(const BoneState& state) {
  auto normals = vtkSmartPointer<vtkPolyDataNormals>::New();
  normals->SetInputData(toPolyData(state.toMesh()));
  normals->SplittingOff();
  normals->ConsistencyOff();  // imported bones are outward oriented already
  normals->Update();
  auto mapper = vtkSmartPointer<vtkPolyDataMapper>::New();
  mapper->SetInputData(normals->GetOutput());
  mapper->ScalarVisibilityOff();
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  // A cool tint, unlike the cut bone's colour: these bones are references, not cut.
  actor->GetProperty()->SetColor(0.62, 0.74, 0.88);
  actor->GetProperty()->SetSpecular(0.2);
  return actor;
}

}  // namespace

OtherBonesLayer::OtherBonesLayer(Document& document, NodeId mainBone, BoneView& view)
    : document_(document), mainBone_(mainBone), view_(&view) {
  subscription_ = document_.subscribe([this](const DocumentEvent& e) {
    if (e.id.kind() == NodeKind::Bone && e.id != mainBone_) sync();
  });
  sync();
}

OtherBonesLayer::~OtherBonesLayer() {
  subscription_.reset();
  if (view_)
    for (auto& [id, shown] : shown_) view_->renderer()->RemoveActor(shown.actor);
}

std::size_t OtherBonesLayer::shownTriangles() const {
  std::size_t n = 0;
  for (const auto& [id, shown] : shown_) n += shown.triangles;
  return n;
}

void OtherBonesLayer::sync() {
  if (!view_) return;
  vtkRenderer* renderer = view_->renderer();
  bool changed = false;
  for (auto it = shown_.begin(); it != shown_.end();) {  // removed from the document
    if (document_.findAs<BoneNode>(it->first)) {
      ++it;
      continue;
    }
    renderer->RemoveActor(it->second.actor);
    it = shown_.erase(it);
    changed = true;
  }
  for (BoneNode* bone : document_.nodesOf<BoneNode>()) {
    if (bone->id() == mainBone_) continue;
    Shown& s = shown_[bone->id()];
    if (s.actor && s.revision == bone->currentRevision()) continue;
    if (s.actor) renderer->RemoveActor(s.actor);
    s.actor = makeActor(bone->current());
    s.revision = bone->currentRevision();
    s.triangles = bone->current().liveTriangleCount();
    renderer->AddActor(s.actor);
    changed = true;
  }
  // Adding or removing an actor modifies the renderer's prop collection, which makes BoneView's reused bone
  // picture (CachedBoneLayer) draw again.
  if (changed) view_->requestRender();
}

void OtherBonesLayer::fitViewToAll() {
  if (!view_) return;
  view_->renderer()->GetActiveCamera()->ParallelProjectionOn();
  view_->renderer()->ResetCamera();  // every visible prop: the cut bone, the reamer and these bones
  view_->render();
}

}  // namespace reamsim::ui
