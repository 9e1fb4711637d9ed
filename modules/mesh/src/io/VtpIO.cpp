// VTK XML PolyData (.vtp) through vtkXMLPolyDataReader/Writer. VTK reports problems through its output
// window and error events rather than return values, so both are captured and turned into InputError.
#include <cctype>
#include <mutex>
#include <new>
#include <string>
#include <vector>

#include <vtkCallbackCommand.h>
#include <vtkCellArray.h>
#include <vtkCommand.h>
#include <vtkDoubleArray.h>
#include <vtkLogger.h>
#include <vtkObjectFactory.h>
#include <vtkOutputWindow.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkXMLPolyDataReader.h>
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

// VTK allocates arrays from the declared NumberOfPoints/NumberOfPolys before reading any data, so
// declared counts are checked against what the file size can justify first.
void checkDeclaredCounts(const std::string& path, std::string_view data) {
  const bool compressed = data.find("compressor=\"") != std::string_view::npos;
  const bool lzma = data.find("vtkLZMADataCompressor") != std::string_view::npos;
  const std::uint64_t ratio = !compressed ? 1 : (lzma ? 10000 : 1100);
  const std::uint64_t limit = static_cast<std::uint64_t>(data.size()) * ratio;
  for (const char* attr : {"NumberOfPoints=\"", "NumberOfPolys=\"", "NumberOfStrips=\"", "NumberOfVerts=\"",
                           "NumberOfLines=\""}) {
    const std::string_view key(attr);
    for (std::size_t pos = data.find(key); pos != std::string_view::npos; pos = data.find(key, pos + 1)) {
      std::uint64_t n = 0;
      bool overflow = false;
      for (std::size_t i = pos + key.size(); i < data.size() && std::isdigit(static_cast<unsigned char>(data[i])); ++i) {
        if (n > (UINT64_MAX - 9) / 10) overflow = true;
        else n = n * 10 + static_cast<std::uint64_t>(data[i] - '0');
      }
      const std::uint64_t values = key == "NumberOfPoints=\"" ? 3 : 1;  // at least one byte per value
      if (overflow || n > limit / values)
        throw InputError(path, "the file declares " + std::string(key.substr(0, key.size() - 2)) + " = " +
                                   (overflow ? std::string("(overflow)") : std::to_string(n)) +
                                   ", more than its size of " + std::to_string(data.size()) +
                                   " bytes can hold (corrupt or lying header)");
    }
  }
}

void checkLooksLikeVtkXml(const std::string& path, std::string_view data) {
  std::size_t i = 0;
  if (data.substr(0, 3) == "\xEF\xBB\xBF") i = 3;  // UTF-8 BOM
  while (i < data.size() && std::isspace(static_cast<unsigned char>(data[i]))) ++i;
  const std::string_view head = data.substr(i, 512);
  if (head.substr(0, 1) != "<" || (head.find("<?xml") != 0 && head.find("<VTKFile") == std::string_view::npos))
    throw InputError(path, "not a VTK XML file (expected '<?xml' or '<VTKFile' at the start)");
  if (data.find("<VTKFile") == std::string_view::npos) throw InputError(path, "not a VTK XML file (no <VTKFile> element)");
  if (data.find("type=\"PolyData\"") == std::string_view::npos)
    throw InputError(path, "not a VTK PolyData file (the VTKFile type is not \"PolyData\")");
}

}  // namespace

RawMesh readVtp(const std::string& path, std::string_view data) {
  checkLooksLikeVtkXml(path, data);
  checkDeclaredCounts(path, data);

  vtkSmartPointer<vtkPolyData> poly;
  {
    VtkMessageCapture capture;
    auto reader = vtkSmartPointer<vtkXMLPolyDataReader>::New();
    capture.observe(reader);
    reader->SetFileName(path.c_str());
    try {
      reader->Update();
    } catch (const std::bad_alloc&) {
      throw InputError(path, "VTK ran out of memory reading the file (corrupt counts?)");
    } catch (const std::exception& e) {
      throw InputError(path, std::string("VTK failed to read the file: ") + e.what());
    }
    if (capture.any()) throw InputError(path, "VTK could not read the file: " + capture.firstMessage());
    poly = reader->GetOutput();
    if (!poly) throw InputError(path, "VTK returned no data");
  }

  RawMesh out;
  out.format = "vtp";
  MeshBuilder b(path);
  const vtkIdType np = poly->GetNumberOfPoints();
  vtkCellArray* polys = poly->GetPolys();
  vtkCellArray* strips = poly->GetStrips();
  b.reserve(static_cast<std::size_t>(np), static_cast<std::size_t>(polys ? polys->GetNumberOfConnectivityIds() : 0));
  for (vtkIdType i = 0; i < np; ++i) {
    double p[3];
    poly->GetPoint(i, p);
    b.addVertex({p[0], p[1], p[2]}, 0);
  }
  std::vector<std::int64_t> ids;
  std::size_t face = 0;
  vtkIdType n = 0;
  const vtkIdType* pts = nullptr;
  if (polys) {
    for (polys->InitTraversal(); polys->GetNextCell(n, pts);) {
      ids.assign(pts, pts + n);
      b.addPolygon(ids, static_cast<std::uint64_t>(np), 0, face++);
    }
  }
  std::size_t stripCount = 0, stripTriangles = 0;
  if (strips) {
    for (strips->InitTraversal(); strips->GetNextCell(n, pts); ++stripCount) {
      if (n < 3)
        throw InputError(path, "triangle strip " + std::to_string(stripCount) + " has only " + std::to_string(n) +
                                   " points (at least 3 needed)");
      for (vtkIdType k = 0; k + 2 < n; ++k) {
        const vtkIdType a = pts[k], c = pts[k + 2];
        const vtkIdType bb = pts[k + 1];
        if (a == bb || bb == c || a == c) continue;  // degenerate joint triangle of a strip
        // Alternate the winding so that every triangle keeps the strip's orientation.
        if (k % 2 == 0) ids = {a, bb, c};
        else ids = {bb, a, c};
        b.addPolygon(ids, static_cast<std::uint64_t>(np), 0, face++);
        ++stripTriangles;
      }
    }
  }
  if (stripCount > 0)
    out.notes.push_back(std::to_string(stripCount) + " triangle strips were converted to " +
                        std::to_string(stripTriangles) + " triangles");
  const vtkIdType ignored = poly->GetNumberOfVerts() + poly->GetNumberOfLines();
  if (ignored > 0) out.notes.push_back(std::to_string(ignored) + " vertex/line cells were ignored");
  out.mesh = b.finish(out.notes);
  return out;
}

void writeVtp(const TriangleMesh& mesh, const std::string& path) {
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

  VtkMessageCapture capture;
  auto writer = vtkSmartPointer<vtkXMLPolyDataWriter>::New();
  capture.observe(writer);
  writer->SetInputData(poly);
  writer->SetFileName(path.c_str());
  writer->SetDataModeToAppended();
  writer->EncodeAppendedDataOff();
  const int ok = writer->Write();
  if (ok != 1 || capture.any())
    throw InputError(path, "cannot write the file" +
                               (capture.any() ? ": " + capture.firstMessage() : std::string(" (VTK writer failed)")));
}

}  // namespace reamsim::io
