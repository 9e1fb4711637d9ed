#include "CachedBoneLayer.h"

// clang-format off
#include <vtk_glew.h>  // before any other OpenGL header
// clang-format on

#include <vtkCallbackCommand.h>
#include <vtkCamera.h>
#include <vtkLight.h>
#include <vtkLightCollection.h>
#include <vtkOpenGLFramebufferObject.h>
#include <vtkOpenGLRenderWindow.h>
#include <vtkOpenGLState.h>
#include <vtkProp.h>
#include <vtkPropCollection.h>
#include <vtkRenderer.h>

#include <algorithm>

namespace reamsim::ui {

CachedBoneLayer::CachedBoneLayer(vtkOpenGLRenderWindow* window, vtkRenderer* bone, vtkRenderer* overlay)
    : window_(window), bone_(bone), overlay_(overlay) {
  callback_ = vtkSmartPointer<vtkCallbackCommand>::New();
  callback_->SetClientData(this);
  callback_->SetCallback(&CachedBoneLayer::onEvent);
  boneEndTag_ = bone_->AddObserver(vtkCommand::EndEvent, callback_);
  overlayStartTag_ = overlay_->AddObserver(vtkCommand::StartEvent, callback_);
}

CachedBoneLayer::~CachedBoneLayer() {
  bone_->RemoveObserver(boneEndTag_);
  overlay_->RemoveObserver(overlayStartTag_);
  bone_->DrawOn();
  // The OpenGL objects die with the context; releaseGraphicsResources() frees them earlier when it can.
}

void CachedBoneLayer::setEnabled(bool on) {
  enabled_ = on;
  valid_ = false;
  if (!on) bone_->DrawOn();
}

void CachedBoneLayer::onEvent(vtkObject* caller, unsigned long event, void* self, void*) {
  auto* me = static_cast<CachedBoneLayer*>(self);
  if (event == vtkCommand::EndEvent && caller == me->bone_ && me->drawing_) me->save();
  if (event == vtkCommand::StartEvent && caller == me->overlay_ && me->restoring_) me->restore();
}

// The latest modification time of anything the bone layer shows (VTK's times are one global counter, so the
// maximum moves whenever any of them changes). Not the renderer's own time: every render modifies it (the
// allocated render time); its settings (background) are changed through the view, which invalidates.
vtkMTimeType CachedBoneLayer::boneSignature() const {
  vtkMTimeType t = 0;
  if (vtkCamera* c = bone_->GetActiveCamera()) t = std::max(t, c->GetMTime());
  vtkLightCollection* lights = bone_->GetLights();
  t = std::max(t, lights->GetMTime());  // a collection is modified when an item is added or removed
  lights->InitTraversal();
  while (vtkLight* l = lights->GetNextItem()) t = std::max(t, l->GetMTime());
  vtkPropCollection* props = bone_->GetViewProps();
  t = std::max(t, props->GetMTime());
  props->InitTraversal();
  while (vtkProp* p = props->GetNextProp()) t = std::max(t, p->GetRedrawMTime());
  return t;
}

void CachedBoneLayer::prepareFrame() {
  const int* size = window_->GetSize();
  const vtkMTimeType signature = boneSignature();
  const bool reuse = enabled_ && valid_ && signature == signature_ && size[0] == width_ && size[1] == height_;
  restoring_ = reuse;
  drawing_ = !reuse && enabled_;
  bone_->SetDraw(reuse ? 0 : 1);
  if (reuse) {
    ++reused_;
  } else {
    ++drawn_;
    signature_ = signature;
    width_ = size[0];
    height_ = size[1];
    valid_ = false;  // until save() succeeds
  }
}

void CachedBoneLayer::fail(const std::string& why) {
  disabledReason_ = why;
  enabled_ = false;
  valid_ = false;
  restoring_ = drawing_ = false;
  bone_->DrawOn();
}

bool CachedBoneLayer::ensureTarget(int width, int height) {
  if (fbo_ && width == fboWidth_ && height == fboHeight_) return true;
  // Match the render framebuffer's depth format: a depth blit needs identical formats.
  GLint depthBits = 0, stencilBits = 0, depthType = 0;
  glGetFramebufferAttachmentParameteriv(GL_READ_FRAMEBUFFER, GL_DEPTH_ATTACHMENT,
                                        GL_FRAMEBUFFER_ATTACHMENT_DEPTH_SIZE, &depthBits);
  glGetFramebufferAttachmentParameteriv(GL_READ_FRAMEBUFFER, GL_DEPTH_ATTACHMENT,
                                        GL_FRAMEBUFFER_ATTACHMENT_STENCIL_SIZE, &stencilBits);
  glGetFramebufferAttachmentParameteriv(GL_READ_FRAMEBUFFER, GL_DEPTH_ATTACHMENT,
                                        GL_FRAMEBUFFER_ATTACHMENT_COMPONENT_TYPE, &depthType);
  GLenum depthFormat = GL_DEPTH_COMPONENT24;
  if (stencilBits > 0) depthFormat = depthBits > 24 ? GL_DEPTH32F_STENCIL8 : GL_DEPTH24_STENCIL8;
  else if (depthType == GL_FLOAT) depthFormat = GL_DEPTH_COMPONENT32F;
  else if (depthBits > 24) depthFormat = GL_DEPTH_COMPONENT32;
  else if (depthBits == 16) depthFormat = GL_DEPTH_COMPONENT16;

  releaseGraphicsResources();
  glGenFramebuffers(1, &fbo_);
  glGenRenderbuffers(1, &colour_);
  glGenRenderbuffers(1, &depth_);
  glBindRenderbuffer(GL_RENDERBUFFER, colour_);
  glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, width, height);
  glBindRenderbuffer(GL_RENDERBUFFER, depth_);
  glRenderbufferStorage(GL_RENDERBUFFER, depthFormat, width, height);
  glBindRenderbuffer(GL_RENDERBUFFER, 0);
  glBindFramebuffer(GL_DRAW_FRAMEBUFFER, fbo_);
  glFramebufferRenderbuffer(GL_DRAW_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, colour_);
  glFramebufferRenderbuffer(GL_DRAW_FRAMEBUFFER, stencilBits > 0 ? GL_DEPTH_STENCIL_ATTACHMENT : GL_DEPTH_ATTACHMENT,
                            GL_RENDERBUFFER, depth_);
  fboWidth_ = width;
  fboHeight_ = height;
  return glCheckFramebufferStatus(GL_DRAW_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
}

// Copies colour and depth between the framebuffer VTK is drawing into and the saved one (toSaved: into it),
// with the scissor test off and VTK's bindings and state as they were afterwards. "" on success, else what
// went wrong.
std::string CachedBoneLayer::copy(bool toSaved) {
  vtkOpenGLState* state = window_->GetState();
  state->PushFramebufferBindings();
  vtkOpenGLState::ScopedglEnableDisable scissor(state, GL_SCISSOR_TEST);
  state->vtkglDisable(GL_SCISSOR_TEST);
  while (glGetError() != GL_NO_ERROR) {
  }
  std::string problem;
  if (toSaved) {
    GLint drawing = 0;
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &drawing);
    state->vtkglBindFramebuffer(GL_READ_FRAMEBUFFER, static_cast<unsigned int>(drawing));
    if (ensureTarget(width_, height_))
      state->vtkglBindFramebuffer(GL_DRAW_FRAMEBUFFER, fbo_);
    else
      problem = "the copy framebuffer is incomplete";
  } else {
    state->vtkglBindFramebuffer(GL_READ_FRAMEBUFFER, fbo_);
  }
  if (problem.empty()) {
    glBlitFramebuffer(0, 0, width_, height_, 0, 0, width_, height_, GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT,
                      GL_NEAREST);
    if (const GLenum error = glGetError(); error != GL_NO_ERROR)
      problem = "OpenGL error " + std::to_string(error) + (toSaved ? " copying" : " restoring") + " the bone layer";
  }
  state->PopFramebufferBindings();
  return problem;
}

// After the bone layer was drawn: copy colour and depth of the render framebuffer aside.
void CachedBoneLayer::save() {
  const std::string problem = copy(true);
  if (!problem.empty()) return fail(problem);
  valid_ = true;
}

// Before the reamer is drawn in a frame that skipped the bone: put the saved bone picture back.
void CachedBoneLayer::restore() {
  const std::string problem = copy(false);
  if (problem.empty()) return;
  fail(problem);
  failedFrame_ = true;  // this frame lacks the bone
}

void CachedBoneLayer::releaseGraphicsResources() {
  if (fbo_) glDeleteFramebuffers(1, &fbo_);
  if (colour_) glDeleteRenderbuffers(1, &colour_);
  if (depth_) glDeleteRenderbuffers(1, &depth_);
  fbo_ = colour_ = depth_ = 0;
  fboWidth_ = fboHeight_ = 0;
  valid_ = false;
}

}  // namespace reamsim::ui
