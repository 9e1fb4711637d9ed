// Writing VTK XML PolyData (.vtp) through vtkXMLPolyDataWriter. VTK reports problems through its output window
// and error events rather than return values, so both are captured and turned into InputError. Reading is
// VtpReader.cpp's own parser (VTK's reader trusts the file's counts and offsets).
#include <cctype>
#include <mutex>
#include <string>
#include <vector>

#include <vtkCallbackCommand.h>
#include <vtkCellArray.h>
#include <vtkCommand.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkLogger.h>
#include <vtkObjectFactory.h>
#include <vtkOutputWindow.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkStringArray.h>
#include <vtkXMLPolyDataWriter.h>

#include "Formats.h"
#include "MeshBuilder.h"
#include "reamsim/mesh/MeshError.h"

namespace reamsim::io {
namespace {

// Output window that records instead of printing.
class CapturingOutputWindow : public vtkOutputWindow {
 public:
  static CapturingOutputWindow* New();
  vtkTypeMacro(CapturingOutputWindow, vtkOutputWindow)
  void DisplayText(const char* t) override { record(t); }
  void DisplayErrorText(const char* t) override { record(t); }
  void DisplayWarningText(const char* t) override { record(t); }
  void DisplayGenericWarningText(const char* t) override { record(t); }
  void DisplayDebugText(const char*) override {}
  std::vector<std::string> messages;

 private:
  void record(const char* t) { messages.emplace_back(t ? t : ""); }
};
vtkStandardNewMacro(CapturingOutputWindow);

// Installs the capturing window and an error/warning observer for the lifetime of the guard.
// VTK's output window is process-global, hence the mutex.
class VtkMessageCapture {
 public:
  VtkMessageCapture() : lock_(mutex()) {
    // VTK 9 also logs every error straight to stderr through vtkLogger; mute that while capturing.
    previousVerbosity_ = vtkLogger::GetCurrentVerbosityCutoff();
    vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_OFF);
    previous_ = vtkOutputWindow::GetInstance();
    window_ = vtkSmartPointer<CapturingOutputWindow>::New();
    vtkOutputWindow::SetInstance(window_);
    callback_ = vtkSmartPointer<vtkCallbackCommand>::New();
    callback_->SetClientData(&events_);
    callback_->SetCallback([](vtkObject*, unsigned long, void* client, void* callData) {
      static_cast<std::vector<std::string>*>(client)->emplace_back(callData ? static_cast<const char*>(callData) : "");
    });
  }
  ~VtkMessageCapture() {
    vtkOutputWindow::SetInstance(previous_);
    vtkLogger::SetStderrVerbosity(previousVerbosity_);
  }
  VtkMessageCapture(const VtkMessageCapture&) = delete;
  VtkMessageCapture& operator=(const VtkMessageCapture&) = delete;

  void observe(vtkObject* o) {
    o->AddObserver(vtkCommand::ErrorEvent, callback_);
    o->AddObserver(vtkCommand::WarningEvent, callback_);
  }
  // The first captured message, condensed to one line; empty if VTK said nothing.
  std::string firstMessage() const {
    const std::vector<std::string>& all = !events_.empty() ? events_ : window_->messages;
    if (all.empty()) return {};
    std::string m = all.front();
    // VTK prefixes "ERROR: In file.cxx, line N\nvtkClass (0x...): "; keep the message proper.
    const std::size_t colon = m.find("): ");
    if (colon != std::string::npos) m = m.substr(colon + 3);
    for (char& c : m)
      if (c == '\n' || c == '\r') c = ' ';
    while (!m.empty() && std::isspace(static_cast<unsigned char>(m.back()))) m.pop_back();
    return m.size() > 300 ? m.substr(0, 300) + "..." : m;
  }
  bool any() const { return !events_.empty() || !window_->messages.empty(); }

 private:
  static std::mutex& mutex() {
    static std::mutex m;
    return m;
  }
  std::lock_guard<std::mutex> lock_;
  vtkLogger::Verbosity previousVerbosity_ = vtkLogger::VERBOSITY_INFO;
  vtkSmartPointer<vtkOutputWindow> previous_;
  vtkSmartPointer<CapturingOutputWindow> window_;
  vtkSmartPointer<vtkCallbackCommand> callback_;
  std::vector<std::string> events_;
};

}  // namespace

std::string writeVtp(const TriangleMesh& mesh, const std::string& path, const std::vector<std::string>& comments) {
  auto points = vtkSmartPointer<vtkPoints>::New();
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(static_cast<vtkIdType>(mesh.vertices.size()));
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    const Vec3& p = mesh.vertices[i];
    points->SetPoint(static_cast<vtkIdType>(i), p.x, p.y, p.z);
  }
  auto cells = vtkSmartPointer<vtkCellArray>::New();
  cells->AllocateExact(static_cast<vtkIdType>(mesh.triangles.size()), static_cast<vtkIdType>(3 * mesh.triangles.size()));
  for (const Triangle& t : mesh.triangles) {
    const vtkIdType ids[3] = {t[0], t[1], t[2]};
    cells->InsertNextCell(3, ids);
  }
  auto poly = vtkSmartPointer<vtkPolyData>::New();
  poly->SetPoints(points);
  poly->SetPolys(cells);
  // The comments as a field-data string array (kept by VTK and ParaView when they rewrite the file).
  auto notes = vtkSmartPointer<vtkStringArray>::New();
  notes->SetName(kVtpCommentsArray);
  for (const std::string& c : commentLinesToWrite(comments)) notes->InsertNextValue(c);
  poly->GetFieldData()->AddArray(notes);

  VtkMessageCapture capture;
  auto writer = vtkSmartPointer<vtkXMLPolyDataWriter>::New();
  capture.observe(writer);
  writer->SetInputData(poly);
  writer->WriteToOutputStringOn();  // the file is then replaced as a whole, as the other formats (replaceFile)
  writer->SetDataModeToAppended();
  writer->EncodeAppendedDataOff();
  const int ok = writer->Write();
  if (ok != 1 || capture.any())
    throw InputError(path, "cannot write the file" +
                               (capture.any() ? ": " + capture.firstMessage() : std::string(" (VTK writer failed)")));
  return writer->GetOutputString();
}

}  // namespace reamsim::io
