// Public entry points: choose the format by extension, apply the unit policy, write by extension.
#include "reamsim/mesh/MeshIO.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <stdexcept>

#include "FileBytes.h"
#include "Formats.h"
#include "reamsim/mesh/FileReplace.h"
#include "reamsim/mesh/MeshError.h"

namespace reamsim {
namespace {

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

std::string extensionOf(const std::string& path) { return lower(std::filesystem::path(path).extension().string()); }

std::string supportedList() {
  std::string all;
  for (const std::string& e : supportedMeshExtensions()) all += (all.empty() ? "" : " ") + e;
  return all;
}

// Below this bounding-box diagonal (in file units) Units::Auto takes the data for metres.
constexpr double kMetreDiagonalThreshold = 2.0;

}  // namespace

std::vector<std::string> supportedMeshExtensions() { return {".stl", ".obj", ".ply", ".off", ".vtp"}; }

Units parseUnits(const std::string& text) {
  const std::string t = lower(text);
  if (t == "auto") return Units::Auto;
  if (t == "mm" || t == "millimetre" || t == "millimetres" || t == "millimeter" || t == "millimeters")
    return Units::Millimetres;
  if (t == "m" || t == "metre" || t == "metres" || t == "meter" || t == "meters") return Units::Metres;
  throw std::invalid_argument("unknown units '" + text + "' (expected m, mm or auto)");
}

LoadedMesh readMesh(const std::string& path, const ReadOptions& options) {
  const std::string ext = extensionOf(path);
  io::RawMesh (*reader)(const std::string&, std::string_view, const StageProgress*) = nullptr;
  if (ext == ".stl") reader = io::readStl;
  else if (ext == ".obj") reader = io::readObj;
  else if (ext == ".ply") reader = io::readPly;
  else if (ext == ".off") reader = io::readOff;
  else if (ext == ".vtp") reader = io::readVtp;
  else
    throw InputError(path, "unknown mesh file extension '" + ext + "' (supported: " + supportedList() + ")");

  // The bytes first (a fifth of the bar: the parse of a text format takes longer), then the parse.
  const StageProgress reading{&options.progress, 0.0, 0.2, "reading"};
  const StageProgress parsing{&options.progress, 0.2, 1.0, "parsing"};
  const bool watched = bool(options.progress);
  const std::string bytes = io::readFileBytes(path, watched ? &reading : nullptr);
  io::RawMesh raw = reader(path, bytes, watched ? &parsing : nullptr);

  LoadedMesh out;
  out.mesh = std::move(raw.mesh);
  out.format = std::move(raw.format);
  out.notes = std::move(raw.notes);
  out.comments = std::move(raw.comments);
  double scale = 1.0;
  if (options.units == Units::Metres) {
    scale = 1000.0;
  } else if (options.units == Units::Auto) {
    const double diagonal = computeBounds(out.mesh).diagonal();
    if (diagonal < kMetreDiagonalThreshold) {
      scale = 1000.0;
      char buf[64];
      std::snprintf(buf, sizeof buf, "%.4g", diagonal);
      out.notes.push_back(std::string("coordinates look like metres (bounding box diagonal ") + buf +
                          " m); scaled \u00d71000 to mm; pass --units mm to keep them");
    }
  }
  if (scale != 1.0) {
    scaleInPlace(out.mesh, scale);
    for (std::size_t i = 0; i < out.mesh.vertices.size(); ++i)
      if (!isFinite(out.mesh.vertices[i]))
        throw InputError(path, "vertex " + std::to_string(i) + " overflows when its metres are scaled ×1000 to mm "
                               "(coordinates beyond ±1.8e305)");
  }
  out.scaleToMillimetres = scale;
  return out;
}

namespace io {

std::vector<std::string> commentLinesToWrite(const std::vector<std::string>& comments) {
  std::vector<std::string> out{kWrittenByComment};
  for (std::string c : comments) {
    for (char& ch : c)
      if (ch == '\n' || ch == '\r' || ch == '\0') ch = ' ';
    out.push_back(std::move(c));
  }
  return out;
}

}  // namespace io

std::vector<std::string> commentsKept(const std::string& path, const WriteOptions& options) {
  if (extensionOf(path) == ".stl" && options.binary) return io::binaryStlCommentsKept(options.comments);
  std::vector<std::string> lines = io::commentLinesToWrite(options.comments);
  lines.erase(lines.begin());  // "written by ReamSim"
  return lines;
}

void writeMesh(const TriangleMesh& mesh, const std::string& path, const WriteOptions& options) {
  const ProgressCallback& progress = options.progress;
  const auto ask = [&](double fraction, const std::string& stage) {
    if (progress && !progress(fraction, stage)) throw WriteCancelled(stage);
  };
  ask(0, "checking");
  const std::string ext = extensionOf(path);
  for (const Triangle& t : mesh.triangles)
    for (std::uint32_t i : t)
      if (i >= mesh.vertices.size())
        throw InputError(path, "cannot write: a triangle refers to vertex " + std::to_string(i) + " but the mesh has " +
                                   std::to_string(mesh.vertices.size()) + " vertices");
  ask(0.05, "encoding");
  std::string bytes;
  if (ext == ".stl") bytes = io::writeStl(mesh, path, options.binary, options.comments);
  else if (ext == ".ply") bytes = io::writePly(mesh, path, options.binary, options.comments);
  else if (ext == ".obj") bytes = io::writeObj(mesh, options.comments);
  else if (ext == ".off") bytes = io::writeOff(mesh, options.comments);
  else if (ext == ".vtp") bytes = io::writeVtp(mesh, path, options.comments);
  else throw InputError(path, "unknown mesh file extension '" + ext + "' for writing (supported: " + supportedList() + ")");
  // Encoding takes about a third of a save, writing and flushing the rest (a 405k PLY: 0.2 s in all).
  ProgressCallback writing;
  if (progress)
    writing = [&progress](double f, const std::string& stage) { return progress(0.35 + 0.65 * f, stage); };
  replaceFile(path, bytes, writing);
}

}  // namespace reamsim
