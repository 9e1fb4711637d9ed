#include "VtkMessages.h"

#include <vtkAlgorithm.h>
#include <vtkCallbackCommand.h>
#include <vtkCommand.h>
#include <vtkLogger.h>
#include <vtkObjectFactory.h>
#include <vtkOutputWindow.h>
#include <vtkSmartPointer.h>

#include <cctype>
#include <mutex>
#include <vector>

namespace reamsim::ct::io {
namespace {

class RecordingWindow : public vtkOutputWindow {
 public:
  static RecordingWindow* New();
  vtkTypeMacro(RecordingWindow, vtkOutputWindow)
  void DisplayText(const char*) override {}
  void DisplayErrorText(const char* t) override { errors.emplace_back(t ? t : ""); }
  void DisplayWarningText(const char*) override {}
  void DisplayGenericWarningText(const char*) override {}
  void DisplayDebugText(const char*) override {}
  std::vector<std::string> errors;
};
vtkStandardNewMacro(RecordingWindow);

std::mutex& captureMutex() {
  static std::mutex m;
  return m;
}

std::string condense(std::string m) {
  const std::size_t colon = m.find("): ");
  if (colon != std::string::npos) m = m.substr(colon + 3);
  for (char& c : m)
    if (c == '\n' || c == '\r') c = ' ';
  while (!m.empty() && std::isspace(static_cast<unsigned char>(m.back()))) m.pop_back();
  // vtk-dicom writes some messages as "... in/path/file.dcm".
  for (std::size_t at = m.find(" in/"); at != std::string::npos; at = m.find(" in/", at)) m.insert(at + 3, " ");
  return m.size() > 300 ? m.substr(0, 300) + "..." : m;
}

}  // namespace

struct VtkMessageCapture::Impl {
  std::lock_guard<std::mutex> lock{captureMutex()};
  vtkLogger::Verbosity previousVerbosity = vtkLogger::GetCurrentVerbosityCutoff();
  vtkSmartPointer<vtkOutputWindow> previous = vtkOutputWindow::GetInstance();
  vtkSmartPointer<RecordingWindow> window = vtkSmartPointer<RecordingWindow>::New();
  vtkSmartPointer<vtkCallbackCommand> callback = vtkSmartPointer<vtkCallbackCommand>::New();
  std::vector<std::string> events;
  std::function<bool(double)> tick;
  bool cancelled = false;
  vtkSmartPointer<vtkCallbackCommand> progress = vtkSmartPointer<vtkCallbackCommand>::New();
};

VtkMessageCapture::VtkMessageCapture() : impl_(std::make_unique<Impl>()) {
  vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_OFF);
  vtkOutputWindow::SetInstance(impl_->window);
  impl_->callback->SetClientData(&impl_->events);
  impl_->callback->SetCallback([](vtkObject*, unsigned long event, void* client, void* data) {
    if (event == vtkCommand::ErrorEvent)
      static_cast<std::vector<std::string>*>(client)->emplace_back(data ? static_cast<const char*>(data) : "error");
  });
}

VtkMessageCapture::~VtkMessageCapture() {
  vtkOutputWindow::SetInstance(impl_->previous);
  vtkLogger::SetStderrVerbosity(impl_->previousVerbosity);
}

void VtkMessageCapture::observe(vtkObject* o) {
  o->AddObserver(vtkCommand::ErrorEvent, impl_->callback);
  o->AddObserver(vtkCommand::WarningEvent, impl_->callback);
}

void VtkMessageCapture::observeProgress(vtkObject* algorithm, std::function<bool(double)> tick) {
  impl_->tick = std::move(tick);
  impl_->progress->SetClientData(impl_.get());
  impl_->progress->SetCallback([](vtkObject* caller, unsigned long, void* client, void* data) {
    auto* impl = static_cast<Impl*>(client);
    const double f = data ? *static_cast<double*>(data) : 0.0;
    if (impl->tick && !impl->cancelled && !impl->tick(0.95 * f)) {
      impl->cancelled = true;
      if (auto* a = vtkAlgorithm::SafeDownCast(caller)) a->SetAbortExecute(1);
    }
  });
  algorithm->AddObserver(vtkCommand::ProgressEvent, impl_->progress);
}

bool VtkMessageCapture::cancelled() const { return impl_->cancelled; }

bool VtkMessageCapture::anyError() const { return !impl_->events.empty() || !impl_->window->errors.empty(); }

std::string VtkMessageCapture::firstMessage() const {
  if (!impl_->events.empty()) return condense(impl_->events.front());
  if (!impl_->window->errors.empty()) return condense(impl_->window->errors.front());
  return {};
}

void VtkMessageCapture::clear() {
  impl_->events.clear();
  impl_->window->errors.clear();
}

}  // namespace reamsim::ct::io
