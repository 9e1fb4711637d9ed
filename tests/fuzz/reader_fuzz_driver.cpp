// Fuzz driver for the file readers (scripts/fuzz-readers.py runs it on mutated files, docs/CT_IMPORT.md).
//   reader_fuzz_driver MODE FILE...   MODE = mesh | plan | presets | landmarks | volume
//     prints "@@ FILE", then "OK ..." or "EXC message" per input, and "FINDING ..." when a read that
//     succeeded breaks an invariant the rest of the program relies on. Each input has FUZZ_TIMEOUT seconds
//     (default 10): a hang ends the process with SIGALRM, so the runner knows which input it was.
//   reader_fuzz_driver seeds DIR      writes small valid volumes to mutate: DIR/volume (NIfTI-1/-2,
//     NRRD, MetaImage) and DIR/dicom/<series>/ (vtk-dicom, several transfer syntaxes), through the
//     CT-import tests' phantom writers and VTK's own NIfTI writer.
#include <vtkImageData.h>
#include <vtkMatrix4x4.h>
#include <vtkNIFTIImageWriter.h>
#include <vtkPointData.h>
#include <vtkShortArray.h>
#include <vtkSmartPointer.h>

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "Phantom.h"
#include "reamsim/ctimport/VolumeIO.h"
#include "reamsim/mesh/MeshIO.h"
#include "reamsim/ream/Plan.h"
#include "reamsim/ream/ScapularFrame.h"
#include "reamsim/tools/ReamerPresets.h"

namespace {

using namespace reamsim;
namespace fs = std::filesystem;

std::string slurp(const std::string& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

bool finite(const Vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// Returns "" or what is wrong with a mesh a reader returned.
std::string meshFinding(const TriangleMesh& m) {
  for (const Vec3& v : m.vertices)
    if (!finite(v)) return "non-finite vertex";
  for (const Triangle& t : m.triangles)
    for (auto i : t)
      if (i >= m.vertices.size()) return "vertex index out of range";
  return "";
}

// What the import pipeline assumes of every volume readVolume returns (checked here independently of
// ct::checkVolume, so a gap in that check shows up as a FINDING).
std::string volumeFinding(const ct::CtVolume& v) {
  for (int a = 0; a < 3; ++a) {
    if (v.dims[a] < 2) return "axis with fewer than 2 samples";
    if (!(std::isfinite(v.spacing[a]) && v.spacing[a] > 0)) return "spacing not finite and positive";
    if (!(std::abs(norm(v.axis(a)) - 1) < 1e-3)) return "direction not unit";
  }
  if (std::uint64_t(v.dims[0]) * std::uint64_t(v.dims[1]) * std::uint64_t(v.dims[2]) != v.values.size())
    return "value count differs from dims";
  if (!finite(v.origin)) return "non-finite origin";
  for (float x : v.values)
    if (!std::isfinite(x)) return "non-finite value";
  const Vec3 far = v.indexToWorld(v.dims[0] - 1, v.dims[1] - 1, v.dims[2] - 1);
  if (!finite(far)) return "non-finite far corner";
  const Vec3 back = v.worldToIndex(far);
  if (!finite(back) || std::abs(back.x - (v.dims[0] - 1)) > 1e-3 * v.dims[0]) return "worldToIndex does not invert indexToWorld";
  return "";
}

std::string readOne(const std::string& mode, const std::string& file) {
  if (mode == "mesh") {
    const LoadedMesh m = readMesh(file);
    const std::string f = meshFinding(m.mesh);
    return f.empty() ? "OK v=" + std::to_string(m.mesh.vertices.size()) + " t=" + std::to_string(m.mesh.triangles.size())
                     : "FINDING " + f;
  }
  if (mode == "plan") {
    const ReamPlan p = parsePlan(slurp(file), file);
    const auto poses = p.expandedPoses();
    for (const Pose& q : poses)
      if (!finite(q.tip) || !std::isfinite(q.rollDeg) || !(std::abs(norm(q.axis) - 1) < 1e-6))
        return "FINDING pose not finite or axis not unit";
    return "OK poses=" + std::to_string(poses.size());
  }
  if (mode == "landmarks") {
    const ScapulaLandmarks l = parseLandmarksJson(slurp(file), file);
    for (ScapulaLandmark which : kScapulaLandmarks)
      if (l[which] && !finite(*l[which])) return "FINDING landmark not finite";
    return std::string("OK side=") + toString(l.side);
  }
  if (mode == "presets") {
    const auto specs = parsePresets(slurp(file), file, fs::path(file).parent_path().string());
    return "OK presets=" + std::to_string(specs.size());
  }
  if (mode == "volume") {
    const ct::CtVolume v = ct::readVolume(file);
    const std::string f = volumeFinding(v);
    return f.empty() ? "OK " + v.format + " " + std::to_string(v.dims[0]) + "x" + std::to_string(v.dims[1]) + "x" +
                           std::to_string(v.dims[2])
                     : "FINDING " + f;
  }
  throw std::invalid_argument("unknown mode " + mode);
}

vtkSmartPointer<vtkImageData> shortImage(const phantom::Grid& g, const std::vector<float>& hu) {
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->SetDimensions(g.dims[0], g.dims[1], g.dims[2]);
  image->SetSpacing(g.spacing[0], g.spacing[1], g.spacing[2]);
  auto values = vtkSmartPointer<vtkShortArray>::New();
  values->SetNumberOfValues(vtkIdType(hu.size()));
  for (std::size_t i = 0; i < hu.size(); ++i) values->SetValue(vtkIdType(i), short(std::lround(hu[i])));
  image->GetPointData()->SetScalars(values);
  return image;
}

// NIfTI as VTK writes it (int16, qform and sform, version 1 or 2): other header layouts than the phantom's.
void writeVtkNifti(const std::string& path, const phantom::Grid& g, const std::vector<float>& hu, int version) {
  auto m = vtkSmartPointer<vtkMatrix4x4>::New();
  m->SetElement(0, 3, 5);
  m->SetElement(1, 3, -7);
  auto writer = vtkSmartPointer<vtkNIFTIImageWriter>::New();
  writer->SetInputData(shortImage(g, hu));
  writer->SetNIFTIVersion(version);
  writer->SetQFormMatrix(m);
  writer->SetSFormMatrix(m);
  writer->SetFileName(path.c_str());
  writer->Write();
  if (writer->GetErrorCode() != 0) throw std::runtime_error("vtkNIFTIImageWriter failed on " + path);
}

void writeSeeds(const fs::path& dir) {
  // 16×16×8 voxels around a small ball: a few kilobytes per file, fast to read under the sanitizers.
  const phantom::Grid g = phantom::gridAround({0, 0, 0}, 7, {1, 1, 2}, phantom::rotation({1, 2, 3}, 20));
  const std::vector<float> hu = phantom::sample(g, [](const Vec3& p) { return norm(p) < 4; }, -1000, 1200, 1);
  const fs::path vol = dir / "volume", dcm = dir / "dicom";
  fs::create_directories(vol);
  phantom::writeNifti((vol / "phantom.nii").string(), g, hu);
  phantom::writeNifti((vol / "phantom.nii.gz").string(), g, hu);
  writeVtkNifti((vol / "vtk1.nii").string(), g, hu, 1);
  writeVtkNifti((vol / "vtk2.nii").string(), g, hu, 2);
  writeVtkNifti((vol / "vtk2.nii.gz").string(), g, hu, 2);
  phantom::writeNrrd((vol / "phantom.nrrd").string(), g, hu);
  phantom::writeMha((vol / "phantom.mha").string(), g, hu, false);
  phantom::writeMha((vol / "phantom_zlib.mha").string(), g, hu, true);
  // Slices slanted by 20° (a gantry tilt kept in the header): resampled by readVolume (SlantedSlices.h).
  phantom::Grid slanted = g;
  slanted.direction = {1, 0, 0, 0, 1, std::sin(0.35), 0, 0, std::cos(0.35)};
  phantom::writeNrrd((vol / "slanted.nrrd").string(), slanted, hu);
  phantom::writeNifti((vol / "slanted.nii").string(), slanted, hu);
  phantom::writeDicomSeries((dcm / "explicit_le").string(), g, hu);
  phantom::writeDicomSeries((dcm / "implicit_le").string(), g, hu, "1.2.840.10008.1.2");
  phantom::writeDicomSeries((dcm / "explicit_be").string(), g, hu, "1.2.840.10008.1.2.2");
  phantom::writeDicomSeries((dcm / "rle").string(), g, hu, "1.2.840.10008.1.2.5");
  phantom::writeDicomMultiFrame((dcm / "multiframe" / "frames.dcm").string(), g, hu);
  std::printf("seeds written to %s\n", dir.string().c_str());
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: %s mesh|plan|presets|landmarks|volume FILE...\n       %s seeds DIR\n", argv[0], argv[0]);
    return 2;
  }
  const std::string mode = argv[1];
  if (mode == "seeds") {
    writeSeeds(argv[2]);
    return 0;
  }
  const char* t = std::getenv("FUZZ_TIMEOUT");
  const unsigned timeout = t ? unsigned(std::atoi(t)) : 10u;
  for (int i = 2; i < argc; ++i) {
    std::printf("@@ %s\n", argv[i]);
    std::fflush(stdout);  // the runner blames the last "@@" line when the process dies
    alarm(timeout);
    std::string line;
    try {
      line = readOne(mode, argv[i]);
    } catch (const std::exception& e) {
      line = std::string("EXC ") + e.what();
      if (line.size() > 4000) line.resize(4000);
    }
    for (char& c : line)  // one line, and a NUL in a message must not cut it short
      if (static_cast<unsigned char>(c) < 0x20) c = c == '\0' ? '?' : ' ';
    std::printf("%s\n", line.c_str());
    std::fflush(stdout);
  }
  alarm(0);
  return 0;
}
