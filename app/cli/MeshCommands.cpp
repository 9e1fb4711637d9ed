// info, repair, export: mesh inspection and conversion.
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>

#include "CliArgs.h"
#include "Commands.h"
#include "DefaultCase.h"
#include "TerminalProgress.h"
#include "reamsim/mesh/MeshError.h"
#include "reamsim/mesh/MeshIO.h"
#include "reamsim/mesh/Repair.h"
#include "reamsim/mesh/Validation.h"

namespace reamsim::cli {
namespace {

LoadedMesh loadPositional(const CliArgs& a, const char* what) {
  if (a.positionals().size() != 1) throw UsageError(std::string("expected exactly one ") + what);
  ReadOptions options;
  options.units = parseUnits(a.value("units", "auto"));
  return readMesh(a.positionals()[0], options);
}

void printNotes(const LoadedMesh& m, const std::string& path) {
  for (const std::string& note : m.notes) std::fprintf(stderr, "note: %s: %s\n", path.c_str(), note.c_str());
}

}  // namespace

int runInfo(const std::vector<std::string>& args) {
  CliArgs a(args, {"units"}, {"json", "no-self-intersections"});
  LoadedMesh m = loadPositional(a, "MESH");
  ValidationOptions options;
  options.checkSelfIntersections = !a.has("no-self-intersections");
  const ValidationReport report = validateMesh(m.mesh, options);
  if (a.has("json")) {
    // The file's comments too: where ReamSim keeps the bone's patient frame ("reamsim patient_frame LPS").
    nlohmann::json j = nlohmann::json::parse(toJson(report));
    j["comments"] = m.comments;
    std::cout << j.dump(2) << "\n";
  } else {
    printNotes(m, a.positionals()[0]);
    std::cout << "file:                   " << a.positionals()[0] << " (" << m.format << ")\n" << toText(report);
    for (const std::string& c : m.comments) std::cout << "comment:                " << c << "\n";
  }
  return kOk;
}

int runRepair(const std::vector<std::string>& args) {
  CliArgs a(args, {"units", "out", "voxel", "target-faces", "max-hole-edges"}, {"json", "no-remesh"});
  const std::string out = a.required("out");
  LoadedMesh m = loadPositional(a, "MESH");
  RepairOptions options;
  options.remesh.voxelMm = a.number("voxel", options.remesh.voxelMm);
  options.remesh.targetTriangles = static_cast<std::size_t>(a.number("target-faces", 0));
  options.maxHoleBoundaryEdges = static_cast<std::size_t>(a.number("max-hole-edges", double(options.maxHoleBoundaryEdges)));
  options.allowRemesh = !a.has("no-remesh");
  options.progress = terminalProgress("repair");
  RepairResult r = repairMesh(m.mesh, options);
  try {
    writeMesh(r.mesh, out);
  } catch (const InputError& e) {
    std::fprintf(stderr, "reamsim-cli repair: error: %s\n", e.what());
    return kWriteFailed;
  }
  if (a.has("json")) std::cout << toJson(r.report) << "\n";
  else {
    printNotes(m, a.positionals()[0]);
    std::cout << toText(r.report) << "written: " << out << "\n";
  }
  return r.report.success() ? kOk : kFailed;
}

int runExport(const std::vector<std::string>& args) {
  CliArgs a(args, {"units", "out"}, {"repair", "ascii"});
  const std::string out = a.required("out");
  if (a.positionals().size() != 1) throw UsageError("expected exactly one MESH (or 'default')");
  TriangleMesh mesh;
  WriteOptions w;
  if (a.positionals()[0] == "default") {
    mesh = loadDefaultBone().mesh;
  } else {
    LoadedMesh m = loadPositional(a, "MESH");
    printNotes(m, a.positionals()[0]);
    mesh = std::move(m.mesh);
    // The patient frame goes on into the new file where its format has room. What a save recorded of the cut log
    // beside the file (`reamsim cut_log`, `reamsim removed_mm3`) does not: no log is beside the export.
    for (std::string& c : m.comments)
      if (c.rfind("reamsim patient_frame ", 0) == 0) w.comments.push_back(std::move(c));
  }
  if (a.has("repair")) {
    RepairOptions options;
    options.progress = terminalProgress("export --repair");
    RepairResult r = repairMesh(mesh, options);
    std::cerr << toText(r.report);
    mesh = std::move(r.mesh);
  }
  w.binary = !a.has("ascii");
  try {
    writeMesh(mesh, out, w);
  } catch (const InputError& e) {
    std::fprintf(stderr, "reamsim-cli export: error: %s\n", e.what());
    return kWriteFailed;
  }
  std::cout << "written: " << out << " (" << mesh.triangles.size() << " triangles)\n";
  return kOk;
}

}  // namespace reamsim::cli

#include "reamsim/ream/CutLogIO.h"
#include "reamsim/ream/Glenoid.h"

namespace reamsim::cli {

int runGlenoid(const std::vector<std::string>& args) {
  CliArgs a(args, {"units", "out"}, {});
  LoadedMesh m = loadPositional(a, "MESH");
  const GlenoidFrame g = findGlenoid(m.mesh);
  const std::string json = glenoidToJson(
      g, "reamsim-cli glenoid (docs/DEFAULT_CASE.md): least-squares sphere fits of 13 mm vertex patches within "
         "35 mm of the most lateral point (+Z), facing laterally, concave, radius 15-80 mm; best = lowest rms "
         "residual / lateral cosine; then grown to the on-sphere region within 22 mm and re-centred");
  if (a.has("out")) {
    try {
      writeTextFile(a.value("out"), json + "\n");
    } catch (const InputError& e) {
      std::fprintf(stderr, "reamsim-cli glenoid: error: %s\n", e.what());
      return kWriteFailed;
    }
  }
  std::cout << json << "\n";
  return kOk;
}

}  // namespace reamsim::cli
