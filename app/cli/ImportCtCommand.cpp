// import-ct: CT volume → closed bone mesh (modules/ctimport). With --json it prints one JSON object with the
// import report, per-stage times and the peak resident memory: this is the CT-import benchmark
// (docs/CT_IMPORT.md).
#include <sys/resource.h>

#include <chrono>
#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>

#include "CliArgs.h"
#include "Commands.h"
#include "reamsim/ctimport/CtImport.h"
#include "reamsim/ctimport/VolumeIO.h"
#include "reamsim/mesh/MeshError.h"
#include "reamsim/mesh/MeshIO.h"

namespace reamsim::cli {
namespace {

using Clock = std::chrono::steady_clock;

double msSince(Clock::time_point t0) { return std::chrono::duration<double, std::milli>(Clock::now() - t0).count(); }

double peakRssMb() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return double(u.ru_maxrss) / 1024.0;  // Linux: kilobytes
}

ct::ImportOptions parseOptions(const CliArgs& a) {
  ct::ImportOptions o;
  o.lowerThreshold = a.number("threshold", o.lowerThreshold);
  if (a.has("upper-threshold")) o.upperThreshold = a.number("upper-threshold", 0);
  o.targetFaces = static_cast<std::size_t>(a.number("target-faces", double(o.targetFaces)));
  o.smoothingIterations = static_cast<int>(a.number("smooth", o.smoothingIterations));
  o.smoothingPassBand = a.number("pass-band", o.smoothingPassBand);
  o.volumeSmoothingSigmaMm = a.number("volume-sigma", 0);
  o.fillCavities = !a.has("keep-cavities");
  o.cgalSelfIntersectionCheck = a.has("cgal-check");
  const std::string component = a.value("component", "largest");
  if (component == "largest") o.component = ct::ComponentMode::Largest;
  else if (component == "all") o.component = ct::ComponentMode::All;
  else throw UsageError("--component must be 'largest' or 'all' (or pass --seed X,Y,Z)");
  if (a.has("seed")) {
    std::string s = a.value("seed");
    for (char& c : s)
      if (c == ',') c = ' ';
    std::istringstream in(s);
    Vec3 p;
    std::string rest;
    if (!(in >> p.x >> p.y >> p.z) || (in >> rest)) throw UsageError("--seed expects X,Y,Z in mm");
    o.component = ct::ComponentMode::Seed;
    o.seedWorld = p;
  }
  const std::string space = a.value("space", "lps");
  if (space == "lps") o.outputSpace = ct::PatientSpace::LPS;
  else if (space == "ras") o.outputSpace = ct::PatientSpace::RAS;
  else if (space == "native") o.outputSpace = std::nullopt;
  else throw UsageError("--space must be lps, ras or native");
  if (o.targetFaces != 0 && o.targetFaces < 100) throw UsageError("--target-faces must be 0 (keep all) or at least 100");
  return o;
}

}  // namespace

int runImportCt(const std::vector<std::string>& args) {
  const Clock::time_point start = Clock::now();
  CliArgs a(args,
            {"threshold", "upper-threshold", "target-faces", "smooth", "pass-band", "volume-sigma", "component", "seed",
             "space", "out"},
            {"json", "keep-cavities", "cgal-check"});
  if (a.positionals().size() != 1) throw UsageError("expected exactly one VOLUME (file or DICOM directory)");
  const std::string out = a.required("out");
  ct::ImportOptions options = parseOptions(a);
  const bool json = a.has("json");

  const auto show = [&](double fraction, const std::string& stage) {
    if (!json) std::fprintf(stderr, "\r%3.0f%% %-32s", 100 * fraction, stage.c_str());
    return true;
  };
  const Clock::time_point t0 = Clock::now();
  const ct::CtVolume volume = ct::readVolume(a.positionals()[0], show);
  const double readMs = msSince(t0);
  if (!json) {
    std::fprintf(stderr, "\rread %s: %d x %d x %d voxels in %.0f ms\n", a.positionals()[0].c_str(), volume.dims[0],
                 volume.dims[1], volume.dims[2], readMs);
  }
  // --seed is given in the output space (what the user sees in the mesh); the pipeline wants the volume's.
  if (options.seedWorld && options.outputSpace)
    options.seedWorld = ct::convertPoint(*options.seedWorld, *options.outputSpace, volume.space);

  ct::ImportResult result;
  try {
    result = ct::importBone(volume, options, show);
    if (!json) std::fputc('\n', stderr);
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }

  const Clock::time_point tw = Clock::now();
  try {
    writeMesh(result.mesh, out);
  } catch (const InputError& e) {
    std::fprintf(stderr, "reamsim-cli import-ct: error: %s\n", e.what());
    return kWriteFailed;
  }
  const double writeMs = msSince(tw);
  const bool clean = result.report.validation.isCleanSolid();
  if (json) {
    nlohmann::json j = nlohmann::json::parse(ct::toJson(result.report, -1));
    j["output"] = out;
    j["read_ms"] = readMs;
    j["pipeline_ms"] = result.report.totalMs;
    j["volume_to_mesh_ms"] = readMs + result.report.totalMs;
    j["write_ms"] = writeMs;
    j["wall_ms"] = msSince(start);
    j["peak_rss_mb"] = peakRssMb();
    j["threads"] = "TBB default (all cores)";
    std::cout << j.dump(2) << "\n";
  } else {
    std::cout << ct::toText(result.report);
    std::printf("read %.0f ms, pipeline %.0f ms, write %.0f ms; peak memory %.0f MB\n", readMs, result.report.totalMs,
                writeMs, peakRssMb());
    std::printf("written: %s (%zu triangles, %s coordinates)\n", out.c_str(), result.mesh.triangles.size(),
                ct::toString(result.space));
  }
  return clean ? kOk : kFailed;
}

}  // namespace reamsim::cli
