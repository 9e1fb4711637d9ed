#include "BoneView.h"

#include <vtkActor.h>
#include <vtkCallbackCommand.h>
#include <vtkCamera.h>
#include <vtkGenericOpenGLRenderWindow.h>
#include <vtkLight.h>
#include <vtkLookupTable.h>
#include <vtkMatrix4x4.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderWindowInteractor.h>
#include <vtkRenderer.h>
#include <vtkScalarBarActor.h>
#include <vtkTextProperty.h>

#include <QElapsedTimer>
#include <QTimer>

#include <algorithm>
#include <cmath>

#include "CachedBoneLayer.h"
#include "LandmarksLayer.h"
#include "reamsim/ream/GlenoidFace.h"
#include "ReamSession.h"
#include "ThesisInteractorStyle.h"
#include "reamsim/collision/MeshRayCast.h"
#include "reamsim/ream/ScapularFrame.h"
#include "reamsim/ui/MeshPolyData.h"

namespace reamsim::ui {
namespace {

void setColour(vtkProperty* p, const QColor& c) { p->SetColor(c.redF(), c.greenF(), c.blueF()); }

}  // namespace

BoneView::BoneView(ReamSession& session, QWidget* parent) : QVTKOpenGLNativeWidget(parent), session_(session) {
  setObjectName("BoneView");
  auto window = vtkSmartPointer<vtkGenericOpenGLRenderWindow>::New();
  // No multisampling: with a software rasteriser (llvmpipe) 8x MSAA costs most of the frame.
  window->SetMultiSamples(0);
  setRenderWindow(window);
  renderer_ = vtkSmartPointer<vtkRenderer>::New();
  window->AddRenderer(renderer_);
  // The reamer is drawn over the bone by its own renderer, so that frames where only it moved can reuse the
  // bone's picture (CachedBoneLayer): same camera and lights, the bone's depth buffer kept.
  window->SetNumberOfLayers(2);
  reamerRenderer_ = vtkSmartPointer<vtkRenderer>::New();
  reamerRenderer_->SetLayer(1);
  reamerRenderer_->PreserveDepthBufferOn();
  reamerRenderer_->InteractiveOff();
  reamerRenderer_->AutomaticLightCreationOff();
  reamerRenderer_->SetActiveCamera(renderer_->GetActiveCamera());
  window->AddRenderer(reamerRenderer_);
  boneCache_ = std::make_unique<CachedBoneLayer>(window, renderer_, reamerRenderer_);
  beforeFrame_ = vtkSmartPointer<vtkCallbackCommand>::New();
  beforeFrame_->SetClientData(this);
  beforeFrame_->SetCallback([](vtkObject*, unsigned long, void* self, void*) {
    static_cast<BoneView*>(self)->prepareFrame();
  });
  window->AddObserver(vtkCommand::StartEvent, beforeFrame_);
  renderer_->GetActiveCamera()->ParallelProjectionOn();  // orthographic: true sizes
  renderer_->GradientBackgroundOn();
  renderer_->AutomaticLightCreationOff();

  boneMapper_ = vtkSmartPointer<vtkPolyDataMapper>::New();
  boneActor_ = vtkSmartPointer<vtkActor>::New();
  boneActor_->SetMapper(boneMapper_);
  reamerMapper_ = vtkSmartPointer<vtkPolyDataMapper>::New();
  reamerMapper_->ScalarVisibilityOff();
  reamerActor_ = vtkSmartPointer<vtkActor>::New();
  reamerActor_->SetMapper(reamerMapper_);
  renderer_->AddActor(boneActor_);
  reamerRenderer_->AddActor(reamerActor_);

  depthLut_ = vtkSmartPointer<vtkLookupTable>::New();
  depthLut_->SetHueRange(0.62, 0.0);  // blue (shallow) → red (deep)
  depthLut_->SetNumberOfTableValues(256);
  depthLut_->UseBelowRangeColorOn();   // the untouched surface keeps the bone colour
  depthLut_->Build();
  scalarBar_ = vtkSmartPointer<vtkScalarBarActor>::New();
  scalarBar_->SetLookupTable(depthLut_);
  scalarBar_->SetTitle("removed\ndepth (mm)");  // two lines: one overran the view's right edge
  scalarBar_->SetNumberOfLabels(5);
  scalarBar_->SetVerticalTitleSeparation(6);  // the title clear of the top label
  scalarBar_->SetMaximumWidthInPixels(70);
  scalarBar_->SetPosition(0.9, 0.15);
  scalarBar_->SetHeight(0.6);
  scalarBar_->SetWidth(0.08);
  scalarBar_->UnconstrainedFontSizeOn();
  scalarBar_->GetLabelTextProperty()->SetFontSize(12);
  scalarBar_->GetTitleTextProperty()->SetFontSize(12);
  scalarBar_->SetVisibility(false);
  renderer_->AddViewProp(scalarBar_);

  directional_ = vtkSmartPointer<vtkLight>::New();
  directional_->SetLightTypeToHeadlight();
  point_ = vtkSmartPointer<vtkLight>::New();
  point_->SetLightTypeToSceneLight();
  point_->SetPositional(true);
  point_->SetConeAngle(180);  // a point light, not a spot
  for (vtkRenderer* r : {renderer_.Get(), reamerRenderer_.Get()}) {
    r->AddLight(directional_);
    r->AddLight(point_);
  }

  style_ = vtkSmartPointer<ThesisInteractorStyle>::New();
  style_->reamerAxis = [this](Vec3& tip, Vec3& axis) {
    const ReamerNode* r = session_.reamer();
    if (!r || !r->cuttingVolume()) return false;
    tip = r->pose().tip;
    axis = r->pose().axis;
    return true;
  };
  style_->dragAlongAxis = [this](double mm) { Q_EMIT reamerDragged(mm); };
  style_->pickAt = [this](int x, int y) { return placeRequestedLandmark(x, y); };
  landmarksLayer_ = std::make_unique<LandmarksLayer>(renderer_);
  interactor()->SetInteractorStyle(style_);

  setRenderSettings(settings_);
  subscription_ = session_.document().subscribe([this](const DocumentEvent&) { onDocumentEvent(); });
  connect(&session_, &ReamSession::boneReplaced, this, &BoneView::onBoneReplaced);
  onBoneReplaced();
}

BoneView::~BoneView() {
  landmarksLayer_.reset();
  renderWindow()->RemoveObserver(beforeFrame_);
  makeCurrent();
  boneCache_->releaseGraphicsResources();
  doneCurrent();
}

vtkRenderer* BoneView::renderer() const { return renderer_; }

void BoneView::render() {
  renderPending_ = false;
  QElapsedTimer timer;
  timer.start();
  renderWindow()->Render();
  if (boneCache_->takeFailedFrame()) renderWindow()->Render();  // the cache switched itself off: draw in full
  lastRenderMs_ = timer.nsecsElapsed() / 1e6;
}

void BoneView::setBoneCacheEnabled(bool on) {
  boneCache_->setEnabled(on);
  render();
}

const CachedBoneLayer& BoneView::boneCache() const { return *boneCache_; }

// Before every frame, whoever asked for it (this view, the interactor style, Qt's repaint).
void BoneView::prepareFrame() {
  updateClippingRange();
  boneCache_->prepareFrame();
}

// The clipping range must hold the bone and the reamer. Resetting it modifies the camera (which would make
// the bone layer draw again), so it is reset only when the camera changed, the bone changed, or the reamer
// left a box kept around both with a margin.
void BoneView::updateClippingRange() {
  vtkCamera* camera = renderer_->GetActiveCamera();
  double bone[6], reamer[6];
  boneActor_->GetBounds(bone);
  const bool hasReamer = reamerActor_->GetVisibility() && reamerMapper_->GetInput();
  if (hasReamer) reamerActor_->GetBounds(reamer);
  bool inside = true;
  if (hasReamer)
    for (int i = 0; i < 3; ++i) inside = inside && reamer[2 * i] >= clipBox_[2 * i] && reamer[2 * i + 1] <= clipBox_[2 * i + 1];
  const bool boneMoved = !std::equal(bone, bone + 6, clipBone_);
  if (inside && !boneMoved && camera->GetMTime() == clipCameraTime_) return;
  std::copy(bone, bone + 6, clipBone_);
  double box[6];
  std::copy(bone, bone + 6, box);
  if (hasReamer)
    for (int i = 0; i < 3; ++i) {
      box[2 * i] = std::min(box[2 * i], reamer[2 * i]);
      box[2 * i + 1] = std::max(box[2 * i + 1], reamer[2 * i + 1]);
    }
  const double diagonal = std::sqrt((box[1] - box[0]) * (box[1] - box[0]) + (box[3] - box[2]) * (box[3] - box[2]) +
                                    (box[5] - box[4]) * (box[5] - box[4]));
  const double margin = std::max(10.0, 0.25 * diagonal);
  for (int i = 0; i < 3; ++i) {
    clipBox_[2 * i] = box[2 * i] - margin;
    clipBox_[2 * i + 1] = box[2 * i + 1] + margin;
  }
  renderer_->ResetCameraClippingRange(clipBox_);
  clipCameraTime_ = camera->GetMTime();
}

std::size_t BoneView::displayedTriangleCount() const {
  auto* poly = vtkPolyData::SafeDownCast(boneMapper_->GetInput());
  return poly ? static_cast<std::size_t>(poly->GetNumberOfPolys()) : 0;
}

void BoneView::onBoneReplaced() {
  shownBoneChange_ = UINT64_MAX;
  onDocumentEvent();
  placePointLight();
  resetView();
}

void BoneView::onDocumentEvent() {
  const BoneNode* bone = session_.bone();
  const ReamerNode* reamer = session_.reamer();
  bool changed = false;
  if (bone->modifiedCount() != shownBoneChange_) {
    shownBoneChange_ = bone->modifiedCount();
    if (bone->currentRevision() != shownRevision_ || displayedTriangleCount() == 0) rebuildBone();
    changed = true;
  }
  if (reamer->modifiedCount() != shownReamerChange_) {
    shownReamerChange_ = reamer->modifiedCount();
    const Pose& p = reamer->pose();
    const bool moved = !(p.tip == shownPose_.tip) || !(p.axis == shownPose_.axis) || p.rollDeg != shownPose_.rollDeg;
    if (reamer->cuttingVolume().get() != shownCuttingVolume_) {
      rebuildReamer();
      changed = true;
    }
    if (moved) {
      shownPose_ = p;
      placeReamer();
      changed = true;
    }
  }
  const bool glenoidChanged = measureGlenoidFace();
  if (BonePlanning planning = planningOf(*bone); planning != shownPlanning_ || glenoidChanged) {
    shownPlanning_ = std::move(planning);
    showLandmarks();
    changed = true;
  }
  if (changed) requestRender();
}

bool BoneView::measureGlenoidFace() {
  const BoneNode& bone = *session_.bone();
  const BoneHistory::Entry& opened = bone.history().entries().front();
  const std::optional<Vec3>& centre = bone.landmarks()[ScapulaLandmark::GlenoidCentre];
  if (opened.revision == glenoid_.openedRevision && centre == glenoid_.centre) return false;
  const std::optional<Vec3> before = glenoid_.outward;
  glenoid_ = {opened.revision, centre, std::nullopt};
  if (centre) try {
      glenoid_.outward = reamsim::measureGlenoidFace(opened.state, *centre).outward;
    } catch (const std::invalid_argument&) {  // no face there: nothing drawn (the Planning dock says why)
    }
  return glenoid_.outward != before;
}

// Spheres a little larger than a reamer step on the default bone, and visible on a whole-body CT bone.
void BoneView::showLandmarks() {
  const Bounds b = session_.bone()->current().bounds();
  const double diagonal = b.empty() ? 100.0 : norm(b.max - b.min);
  landmarksLayer_->show(shownPlanning_.landmarks, shownPlanning_.plannedAxis, glenoid_.outward,
                        std::clamp(0.008 * diagonal, 0.8, 4.0));
  boneCache_->invalidate();
}

std::optional<Vec3> BoneView::boneSurfaceAt(double x, double y) const {
  const BoneState& bone = session_.bone()->current();
  if (bone.empty()) return std::nullopt;
  // The view ray through the pixel, from the near to the far clipping plane (which hold the bone).
  double ends[2][3];
  for (int i = 0; i < 2; ++i) {
    renderer_->SetDisplayPoint(x, y, i);
    renderer_->DisplayToWorld();
    const double* w = renderer_->GetWorldPoint();
    if (!(w[3] != 0)) return std::nullopt;
    for (int k = 0; k < 3; ++k) ends[i][k] = w[k] / w[3];
  }
  const Vec3 origin{ends[0][0], ends[0][1], ends[0][2]};
  const Vec3 direction = Vec3{ends[1][0], ends[1][1], ends[1][2]} - origin;
  if (!(norm(direction) > 0)) return std::nullopt;
  // The thesis's Moeller-Trumbore over every live triangle, in place: a click, not a loop.
  const std::optional<MeshHit> hit = firstHit(bone, origin, normalized(direction));
  if (!hit) return std::nullopt;
  return hit->point;
}

// A click while a landmark is asked for places it where the click meets the bone, and ends the request; a
// click beside the bone does nothing (the request waits for the next click).
bool BoneView::placeRequestedLandmark(int x, int y) {
  InteractionNode* interaction = session_.interaction();
  if (!interaction->placeRequest()) return false;
  const std::optional<Vec3> point = boneSurfaceAt(x, y);
  if (!point) return true;
  const ScapulaLandmark which = *interaction->placeRequest();
  BoneNode& bone = *session_.bone();
  ScapulaLandmarks next = bone.landmarks();
  next[which] = *point;
  // A bone in a known patient frame (a CT bone) says which side it is once the scapular axis is placed.
  if (next.side == BodySide::Unspecified)
    if (const std::optional<BodySide> side = sideFromPatientFrame(bone.patientFrame(), next)) next.side = *side;
  Document::BatchScope batch(session_.document());
  bone.setLandmarks(next);
  interaction->setPlaceRequest(std::nullopt);
  return true;
}

// One render per turn of the event loop, however many document changes arrived (a key press and the
// worker's result for it often land together).
void BoneView::requestRender() {
  if (renderPending_) return;
  renderPending_ = true;
  QTimer::singleShot(0, this, [this] {
    if (renderPending_) render();
  });
}

void BoneView::rebuildBone() {
  const BoneNode& bone = *session_.bone();
  shownRevision_ = bone.currentRevision();
  const auto& entries = bone.history().entries();
  if (entries.front().revision != initialRevision_) {  // a new bone: new reference for depth
    initialRevision_ = entries.front().revision;
    surfaces_.setInitial(entries.front().state);
  }
  const std::size_t cursor = bone.history().cursor();
  // Highlight what the step into the current state made (nothing for the imported state).
  const BoneState* previous = cursor > 0 ? &entries[cursor - 1].state : nullptr;
  BoneSurfaceBuilder::Result r =
      surfaces_.build(bone.current(), previous, settings_.bone, settings_.freshCut, settings_.smoothShading);
  freshTriangles_ = r.freshTriangles;
  maxDepthMm_ = r.maxDepthMm;
  boneMapper_->SetInputData(r.polyData);
  applyColouring();
  boneCache_->invalidate();
}

void BoneView::rebuildReamer() {
  const auto& volume = session_.reamer()->cuttingVolume();
  shownCuttingVolume_ = volume.get();
  if (volume) reamerMapper_->SetInputData(toPolyData(*volume));
  reamerActor_->SetVisibility(volume != nullptr);
}

void BoneView::placeReamer() {
  const RigidTransform t = session_.reamer()->transform();
  auto m = vtkSmartPointer<vtkMatrix4x4>::New();
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) m->SetElement(i, j, t.rotation[3 * i + j]);
  m->SetElement(0, 3, t.translation.x);
  m->SetElement(1, 3, t.translation.y);
  m->SetElement(2, 3, t.translation.z);
  reamerActor_->SetUserMatrix(m);
}

void BoneView::applyColouring() {
  boneCache_->invalidate();
  boneMapper_->ScalarVisibilityOn();
  if (colourMode_ == ColourMode::Depth) {
    boneMapper_->SetScalarModeToUsePointFieldData();
    boneMapper_->SelectColorArray("depth_mm");
    boneMapper_->SetColorModeToMapScalars();
    const double top = std::max(0.1, maxDepthMm_);
    depthLut_->SetTableRange(0.02, top);  // below 0.02 mm: untouched
    const QColor& b = settings_.bone;
    depthLut_->SetBelowRangeColor(b.redF(), b.greenF(), b.blueF(), 1.0);
    boneMapper_->SetLookupTable(depthLut_);
    boneMapper_->UseLookupTableScalarRangeOn();
    scalarBar_->SetVisibility(true);
  } else {
    boneMapper_->SetScalarModeToUseCellFieldData();
    boneMapper_->SelectColorArray("colour");
    boneMapper_->SetColorModeToDirectScalars();
    scalarBar_->SetVisibility(false);
  }
}

// The point light sits one bone diagonal from the bone's centre, in the direction the settings give.
void BoneView::placePointLight() {
  if (!session_.bone()) return;
  const Bounds b = session_.bone()->current().bounds();
  if (b.empty()) return;
  const double az = settings_.pointAzimuthDeg * M_PI / 180, el = settings_.pointElevationDeg * M_PI / 180;
  const Vec3 c = b.center(), d{std::cos(el) * std::sin(az), std::sin(el), std::cos(el) * std::cos(az)};
  const Vec3 p = c + d * std::max(1.0, b.diagonal());
  point_->SetPosition(p.x, p.y, p.z);
  point_->SetFocalPoint(c.x, c.y, c.z);
}

void BoneView::applyLights() {
  directional_->SetIntensity(settings_.directionalIntensity);
  point_->SetIntensity(settings_.pointIntensity);
  placePointLight();
  const QColor& a = settings_.ambientLight;
  for (vtkRenderer* r : {renderer_.Get(), reamerRenderer_.Get()}) r->SetAmbient(a.redF(), a.greenF(), a.blueF());
  for (vtkActor* a : {boneActor_.Get(), reamerActor_.Get()}) {
    vtkProperty* p = a->GetProperty();
    p->SetAmbient(settings_.ambient);
    p->SetDiffuse(settings_.diffuse);
    p->SetSpecular(settings_.specular);
    p->SetSpecularPower(settings_.specularPower);
  }
}

void BoneView::setRenderSettings(const RenderSettings& s) {
  const bool recolour = s.bone != settings_.bone || s.freshCut != settings_.freshCut ||
                        s.smoothShading != settings_.smoothShading;
  settings_ = s;
  renderer_->SetBackground(s.background.redF(), s.background.greenF(), s.background.blueF());
  renderer_->SetBackground2(s.background2.redF(), s.background2.greenF(), s.background2.blueF());
  setColour(boneActor_->GetProperty(), s.bone);
  setColour(reamerActor_->GetProperty(), s.reamer);
  reamerActor_->GetProperty()->SetOpacity(s.reamerOpacity);
  applyLights();
  boneCache_->invalidate();
  if (recolour && displayedTriangleCount() > 0) rebuildBone();
  render();
}

void BoneView::setWireframe(bool on) {
  wireframe_ = on;
  if (on) {
    boneActor_->GetProperty()->SetRepresentationToWireframe();
  } else {
    boneActor_->GetProperty()->SetRepresentationToSurface();
  }
  boneCache_->invalidate();
  render();
}

void BoneView::setColourMode(ColourMode mode) {
  colourMode_ = mode;
  applyColouring();
  render();
}

void BoneView::resetView() {
  vtkCamera* cam = renderer_->GetActiveCamera();
  cam->ParallelProjectionOn();
  renderer_->ResetCamera(boneActor_->GetBounds());
  render();
}

// Bone frame as in the bundled OpenSim scapula: +X anterior, +Y superior, +Z lateral.
void BoneView::setStandardView(StandardView view) {
  const Bounds b = session_.bone()->current().bounds();
  if (b.empty()) return;
  Vec3 focus = b.center(), direction{0, 0, -1}, up{0, 1, 0};
  switch (view) {
    case StandardView::Anterior: direction = {-1, 0, 0}; break;  // looking from the front
    case StandardView::Posterior: direction = {1, 0, 0}; break;
    case StandardView::Superior: direction = {0, -1, 0}; up = {-1, 0, 0}; break;
    case StandardView::EnFace: {
      // Along the planned axis, onto the glenoid (where the plan starts, else the reamer).
      const PlanNode* plan = session_.plan();
      const Pose pose = plan && !plan->poses().empty() ? plan->poses().front() : session_.reamer()->pose();
      direction = normalized(pose.axis);
      focus = pose.tip;
      up = std::abs(direction.y) < 0.9 ? Vec3{0, 1, 0} : Vec3{1, 0, 0};
      break;
    }
  }
  vtkCamera* cam = renderer_->GetActiveCamera();
  const double distance = std::max(1.0, b.diagonal());
  cam->SetFocalPoint(focus.x, focus.y, focus.z);
  cam->SetPosition(focus.x - direction.x * distance, focus.y - direction.y * distance, focus.z - direction.z * distance);
  cam->SetViewUp(up.x, up.y, up.z);
  cam->OrthogonalizeViewUp();
  cam->SetParallelScale(view == StandardView::EnFace ? 30.0 : 0.55 * std::max({b.size().x, b.size().y, b.size().z}));
  renderer_->ResetCameraClippingRange();
  render();
}

}  // namespace reamsim::ui

