#pragma once
// Frames in which only the reamer moved (every key press, every drag) copy the bone's last picture, colour
// and depth, instead of drawing the bone again; the reamer is then drawn over it, depth-tested against the
// bone as before. Under a software rasteriser (llvmpipe) drawing a 400k-face bone is most of a frame.
//
// The bone and everything that is not the reamer live in one renderer (layer 0), the reamer in an overlay
// renderer (layer 1, same camera and lights, depth buffer preserved). The bone layer is drawn again whenever
// anything it shows may have changed: the camera, the lights, any of its props (actor, mapper, input,
// property, lookup table: their redraw times), the renderer's own settings, the window size, or an explicit
// invalidate(). If the OpenGL copy fails the cache switches itself off and says why; frames are then drawn
// in full as before.
#include <vtkSmartPointer.h>
#include <vtkType.h>

#include <cstddef>
#include <string>

class vtkCallbackCommand;
class vtkObject;
class vtkOpenGLRenderWindow;
class vtkRenderer;

namespace reamsim::ui {

class CachedBoneLayer {
 public:
  CachedBoneLayer(vtkOpenGLRenderWindow* window, vtkRenderer* bone, vtkRenderer* overlay);
  ~CachedBoneLayer();
  CachedBoneLayer(const CachedBoneLayer&) = delete;
  CachedBoneLayer& operator=(const CachedBoneLayer&) = delete;

  void setEnabled(bool on);  // off: every frame draws everything (the reference the tests compare with)
  bool enabled() const { return enabled_; }
  void invalidate() { valid_ = false; }
  // Call right before each Render(): decides whether the bone layer is drawn or copied.
  void prepareFrame();
  // Call when the OpenGL context goes away.
  void releaseGraphicsResources();

  // True once after a frame whose restore failed (that frame lacks the bone): render again.
  bool takeFailedFrame() {
    const bool f = failedFrame_;
    failedFrame_ = false;
    return f;
  }
  std::size_t drawnFrames() const { return drawn_; }
  std::size_t reusedFrames() const { return reused_; }
  const std::string& disabledReason() const { return disabledReason_; }

 private:
  static void onEvent(vtkObject* caller, unsigned long event, void* self, void*);
  vtkMTimeType boneSignature() const;
  bool ensureTarget(int width, int height);
  std::string copy(bool toSaved);
  void save();
  void restore();
  void fail(const std::string& why);

  vtkOpenGLRenderWindow* window_;
  vtkRenderer* bone_;
  vtkRenderer* overlay_;
  vtkSmartPointer<vtkCallbackCommand> callback_;
  unsigned long boneEndTag_ = 0, overlayStartTag_ = 0;
  bool enabled_ = true, valid_ = false, restoring_ = false, drawing_ = false;
  vtkMTimeType signature_ = 0;
  int width_ = 0, height_ = 0, fboWidth_ = 0, fboHeight_ = 0;
  bool failedFrame_ = false;
  unsigned int fbo_ = 0, colour_ = 0, depth_ = 0;  // the saved picture (OpenGL names)
  std::size_t drawn_ = 0, reused_ = 0;
  std::string disabledReason_;
};

}  // namespace reamsim::ui
