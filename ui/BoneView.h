#pragma once
// The central 3D view: bone and reamer of the shared document in an orthographic VTK view (sizes are
// true; perspective would hide over-reaming), standard views, wireframe, the freshly cut surface
// highlighted, and a depth-coloured mode showing how far the surface was removed.
#include <QVTKOpenGLNativeWidget.h>
#include <vtkSmartPointer.h>

#include <cmath>
#include <cstdint>
#include <memory>
#include <optional>

#include "BoneSurface.h"
#include "RenderSettings.h"
#include "reamsim/core/Pose.h"
#include "reamsim/core/ScapulaLandmarks.h"
#include "reamsim/ream/ScapularFrame.h"
#include "reamsim/core/Signal.h"

class vtkActor;
class vtkCallbackCommand;
class vtkLight;
class vtkLookupTable;
class vtkPolyDataMapper;
class vtkRenderer;
class vtkScalarBarActor;

namespace reamsim::ui {

class CachedBoneLayer;
class LandmarksLayer;
class ReamSession;
class ThesisInteractorStyle;

class BoneView : public QVTKOpenGLNativeWidget {
  Q_OBJECT
 public:
  enum class StandardView { Anterior, Posterior, Superior, EnFace };
  enum class ColourMode { Surface, Depth };

  BoneView(ReamSession& session, QWidget* parent = nullptr);
  ~BoneView() override;

  void setRenderSettings(const RenderSettings& settings);
  const RenderSettings& renderSettings() const { return settings_; }
  void setWireframe(bool on);
  bool wireframe() const { return wireframe_; }
  void setColourMode(ColourMode mode);
  ColourMode colourMode() const { return colourMode_; }
  void setStandardView(StandardView view);
  void resetView();

  std::size_t freshTriangleCount() const { return freshTriangles_; }
  double maxDepthMm() const { return maxDepthMm_; }
  std::size_t displayedTriangleCount() const;
  vtkRenderer* renderer() const;
  // Frames where only the reamer moved reuse the bone's picture (see CachedBoneLayer.h); off: full frames.
  void setBoneCacheEnabled(bool on);
  const CachedBoneLayer& boneCache() const;
  double lastRenderMs() const { return lastRenderMs_; }  // VTK's part of the last render() (benchmark)
  // The first point of the bone's surface under display point (x, y) (pixels, origin bottom left, as VTK
  // counts them), along the view direction; nullopt when the bone is not there.
  std::optional<Vec3> boneSurfaceAt(double x, double y) const;
  const LandmarksLayer& landmarksLayer() const { return *landmarksLayer_; }

 Q_SIGNALS:
  void reamerDragged(double mm);  // Ctrl + left drag, along the reamer axis

 public Q_SLOTS:
  void render();         // now
  void requestRender();  // coalesced: once per turn of the event loop

 private:
  void onDocumentEvent();
  void rebuildBone();
  void rebuildReamer();
  void placeReamer();
  void applyColouring();
  void applyLights();
  void placePointLight();
  void onBoneReplaced();
  void prepareFrame();
  void updateClippingRange();
  bool placeRequestedLandmark(int x, int y);
  void showLandmarks();
  bool measureGlenoidFace();  // true when what is drawn changes

  ReamSession& session_;
  Subscription subscription_;
  RenderSettings settings_;
  BoneSurfaceBuilder surfaces_;
  vtkSmartPointer<vtkRenderer> renderer_, reamerRenderer_;
  std::unique_ptr<CachedBoneLayer> boneCache_;
  std::unique_ptr<LandmarksLayer> landmarksLayer_;
  BonePlanning shownPlanning_;
  // The glenoid face's outward direction on the bone as opened, measured once per (its first state, glenoid
  // centre): O(bone) on this thread, ~4 ms at 400k triangles, when a bone opens or the centre is placed.
  struct GlenoidShown {
    std::uint64_t openedRevision = 0;
    std::optional<Vec3> centre;
    std::optional<Vec3> outward;
  } glenoid_;
  vtkSmartPointer<vtkCallbackCommand> beforeFrame_;
  double clipBox_[6] = {0, -1, 0, -1, 0, -1}, clipBone_[6] = {0, 0, 0, 0, 0, 0};
  unsigned long clipCameraTime_ = 0;
  double lastRenderMs_ = 0;
  vtkSmartPointer<vtkActor> boneActor_, reamerActor_;
  vtkSmartPointer<vtkPolyDataMapper> boneMapper_, reamerMapper_;
  vtkSmartPointer<vtkLookupTable> depthLut_;
  vtkSmartPointer<vtkScalarBarActor> scalarBar_;
  vtkSmartPointer<vtkLight> directional_, point_;
  vtkSmartPointer<ThesisInteractorStyle> style_;
  bool wireframe_ = false;
  bool renderPending_ = false;
  Pose shownPose_{{NAN, NAN, NAN}, {NAN, NAN, NAN}, 0};
  ColourMode colourMode_ = ColourMode::Surface;
  std::uint64_t initialRevision_ = 0, shownRevision_ = 0, shownBoneChange_ = UINT64_MAX, shownReamerChange_ = UINT64_MAX;
  const void* shownCuttingVolume_ = nullptr;
  std::size_t freshTriangles_ = 0;
  double maxDepthMm_ = 0;
};

}  // namespace reamsim::ui
